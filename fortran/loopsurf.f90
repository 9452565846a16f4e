! Fortran bindings for loopsurf (module `loopsurf`).
!
! Two layers:
!  * `ls_*` — bind(C) interfaces to the C ABI, one for one (see loopsurf.h).
!    Handles are type(c_ptr); indices are 0-BASED, exactly as in C.
!  * `loopsurf_*` — thin convenience wrappers taking Fortran strings and
!    arrays. Their triangle and vertex indices, and the model's face, curve
!    and corner ids, are 1-BASED (Fortran convention; 0 means none):
!    triangle 1 is the first triangle of the file, and
!    `loopsurf_from_arrays` takes tris(3, ntris) with 1-based vertex numbers.
!    Parameters (v, w) and a curve's t are the same in both layers.
! Every function returns a status: LS_OK (0) or a negative LS_ERR_* code;
! `loopsurf_last_error()` then says what failed and why.
module loopsurf
    use, intrinsic :: iso_c_binding
    implicit none
    private :: c_string, c_strlen, f_string

    integer(c_int), parameter :: LS_OK = 0
    integer(c_int), parameter :: LS_ERR_NULL_POINTER = -1
    integer(c_int), parameter :: LS_ERR_IO = -2
    integer(c_int), parameter :: LS_ERR_PARSE = -3
    integer(c_int), parameter :: LS_ERR_NON_MANIFOLD = -4
    integer(c_int), parameter :: LS_ERR_DEGENERATE = -5
    integer(c_int), parameter :: LS_ERR_INDEX_OUT_OF_RANGE = -6
    integer(c_int), parameter :: LS_ERR_PARAMETER_OUT_OF_RANGE = -7
    integer(c_int), parameter :: LS_ERR_NOT_FINITE = -8
    integer(c_int), parameter :: LS_ERR_UNSUPPORTED = -9
    integer(c_int), parameter :: LS_ERR_BAD_STREAM = -10
    integer(c_int), parameter :: LS_ERR_INVALID_ARGUMENT = -11
    integer(c_int), parameter :: LS_ERR_INTERNAL = -12
    integer(c_int), parameter :: LS_ERR_OVER_BUDGET = -13
    integer(c_int), parameter :: LS_INTERPOLATE_SOLVE = 1
    integer(c_int), parameter :: LS_INTERPOLATE_DISPLACEMENT = 2
    !> Flags of ls_net_load_with / loopsurf_load_with (sum them).
    integer(c_int32_t), parameter :: LS_LOAD_TRIANGULATE = 1
    integer(c_int32_t), parameter :: LS_LOAD_WELD = 2
    integer(c_int32_t), parameter :: LS_LOAD_ORIENT = 4
    integer(c_int32_t), parameter :: LS_LOAD_SPLIT_NONMANIFOLD = 8
    integer(c_int32_t), parameter :: LS_LOAD_ALLOW_DEGENERATE = 16
    integer(c_int32_t), parameter :: LS_LOAD_REPAIR = 31

    !> Options of ls_snap_certified (fill with ls_snap_options_default).
    type, bind(C) :: ls_snap_options
        integer(c_size_t) :: struct_size
        real(c_double) :: tolerance
    end type

    !> The answer of ls_snap_certified; set struct_size = c_sizeof(result) first.
    type, bind(C) :: ls_snap_result
        integer(c_size_t) :: struct_size
        integer(c_int32_t) :: tri
        real(c_double) :: vw(2), xyz(3), distance, lower_bound
    end type

    ! Options structs: fill each with its ls_*_options_default, then change
    ! what you need (the fields and their defaults are those of loopsurf.h).

    !> Options of ls_mesh, the chart mesher.
    type, bind(C) :: ls_mesh_options
        integer(c_size_t) :: struct_size
        integer(c_int) :: uniform
        real(c_double) :: size, tolerance
        integer(c_int) :: adapt_curvature
        integer(c_size_t) :: max_triangles
    end type

    !> Options of ls_net_fit, the fitted control net.
    type, bind(C) :: ls_fit_options
        integer(c_size_t) :: struct_size
        real(c_double) :: resolution, tolerance
    end type

    !> Options of ls_remesh, the quality remesher.
    type, bind(C) :: ls_remesh_options
        integer(c_size_t) :: struct_size
        real(c_double) :: size, tolerance
        integer(c_int) :: adapt_curvature
        real(c_double) :: gradation
        integer(c_size_t) :: max_triangles
        integer(c_size_t) :: parts, threads
    end type

    !> Options of ls_adapt, adaptive subdivision.
    type, bind(C) :: ls_adapt_options
        integer(c_size_t) :: struct_size
        real(c_double) :: angle, tolerance
        integer(c_int) :: levels, to_limit
        integer(c_size_t) :: max_triangles
    end type

    !> Options of ls_net_partition: the number of parts and METIS's random seed.
    type, bind(C) :: ls_partition_options
        integer(c_size_t) :: struct_size
        integer(c_int) :: parts, seed
    end type

    !> Options of ls_net_part: the number of parts, which part, METIS's seed.
    type, bind(C) :: ls_part_options
        integer(c_size_t) :: struct_size
        integer(c_int) :: parts, part, seed
    end type

    !> Options of ls_mesh_curve, curving another tool's mesh.
    type, bind(C) :: ls_mesh_curve_options
        integer(c_size_t) :: struct_size
        integer(c_int) :: order
        real(c_double) :: max_move
    end type

    !> Options of ls_trimesh_write: binary files, a piece's global node ids
    !> (0-based, c_loc of an int64 array, or c_null_ptr) and first element tag.
    type, bind(C) :: ls_trimesh_write_options
        integer(c_size_t) :: struct_size
        integer(c_int) :: binary
        type(c_ptr) :: global_ids
        integer(c_int64_t) :: first_element_tag
    end type

    interface
        integer(c_int) function ls_net_load(path, out) bind(C, name="ls_net_load")
            import :: c_int, c_char, c_ptr
            character(kind=c_char), intent(in) :: path(*)
            type(c_ptr), intent(out) :: out
        end function
        integer(c_int) function ls_net_load_with(path, flags, weld_eps, out) bind(C, name="ls_net_load_with")
            import :: c_int, c_char, c_ptr, c_int32_t, c_double
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int32_t), value :: flags
            real(c_double), value :: weld_eps
            type(c_ptr), intent(out) :: out
        end function
        integer(c_int) function ls_net_repair_report(net, buf, size, needed) bind(C, name="ls_net_repair_report")
            import :: c_int, c_char, c_ptr, c_size_t
            type(c_ptr), value :: net
            character(kind=c_char), intent(out) :: buf(*)
            integer(c_size_t), value :: size
            integer(c_size_t), intent(out) :: needed
        end function
        integer(c_int) function ls_net_from_arrays(nverts, xyz, ntris, tris, out) &
                bind(C, name="ls_net_from_arrays")
            import :: c_int, c_size_t, c_double, c_int32_t, c_ptr
            integer(c_size_t), value :: nverts, ntris
            real(c_double), intent(in) :: xyz(*)
            integer(c_int32_t), intent(in) :: tris(*)
            type(c_ptr), intent(out) :: out
        end function
        integer(c_int) function ls_net_tag_edge(net, a, b) bind(C, name="ls_net_tag_edge")
            import :: c_int, c_int32_t, c_ptr
            type(c_ptr), value :: net
            integer(c_int32_t), value :: a, b
        end function
        integer(c_int) function ls_net_tag_vertex(net, v) bind(C, name="ls_net_tag_vertex")
            import :: c_int, c_int32_t, c_ptr
            type(c_ptr), value :: net
            integer(c_int32_t), value :: v
        end function
        integer(c_int) function ls_net_tag_by_angle(net, degrees, ntagged) &
                bind(C, name="ls_net_tag_by_angle")
            import :: c_int, c_double, c_size_t, c_ptr
            type(c_ptr), value :: net
            real(c_double), value :: degrees
            integer(c_size_t), intent(out) :: ntagged
        end function
        integer(c_int) function ls_net_seam_concave_corners(net, nseamed, nleft) &
                bind(C, name="ls_net_seam_concave_corners")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: net
            integer(c_size_t), intent(out) :: nseamed, nleft
        end function
        integer(c_int) function ls_net_counts(net, nverts, ntris, nhard) bind(C, name="ls_net_counts")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: net
            integer(c_size_t), intent(out) :: nverts, ntris, nhard
        end function
        integer(c_int) function ls_net_hard_edges(net, n, pairs) bind(C, name="ls_net_hard_edges")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: net
            integer(c_size_t), intent(out) :: n
            type(c_ptr), intent(out) :: pairs
        end function
        ! Folded edges (worst first): vertex pairs and triangle pairs (int32,
        ! 0-based, 2 per fold) and turns in degrees, freed with ls_free_array.
        integer(c_int) function ls_net_folds(net, degrees, n, edges, triangles, turns) &
                bind(C, name="ls_net_folds")
            import :: c_int, c_double, c_size_t, c_ptr
            type(c_ptr), value :: net
            real(c_double), value :: degrees
            integer(c_size_t), intent(out) :: n
            type(c_ptr), intent(out) :: edges, triangles, turns
        end function
        integer(c_int) function ls_partition_options_default(options) &
                bind(C, name="ls_partition_options_default")
            import :: c_int, ls_partition_options
            type(ls_partition_options), intent(out) :: options
        end function
        ! Each triangle's part (int32, 0-based parts, ntris entries), freed
        ! with ls_free_array, and the number of control edges between parts.
        integer(c_int) function ls_net_partition(net, options, ntris, part, cut) &
                bind(C, name="ls_net_partition")
            import :: c_int, c_size_t, c_ptr, ls_partition_options
            type(c_ptr), value :: net
            type(ls_partition_options), intent(in) :: options
            integer(c_size_t), intent(out) :: ntris, cut
            type(c_ptr), intent(out) :: part
        end function
        integer(c_int) function ls_part_options_default(options) bind(C, name="ls_part_options_default")
            import :: c_int, ls_part_options
            type(ls_part_options), intent(out) :: options
        end function
        ! One part of the net with its halo, freed with ls_part_free.
        integer(c_int) function ls_net_part(net, options, out) bind(C, name="ls_net_part")
            import :: c_int, c_ptr, ls_part_options
            type(c_ptr), value :: net
            type(ls_part_options), intent(in) :: options
            type(c_ptr), intent(out) :: out
        end function
        subroutine ls_part_free(part) bind(C, name="ls_part_free")
            import :: c_ptr
            type(c_ptr), value :: part
        end subroutine
        integer(c_int) function ls_part_counts(part, owned, halo, vertices) bind(C, name="ls_part_counts")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: part
            integer(c_size_t), intent(out) :: owned, halo, vertices
        end function
        ! Each local triangle's 0-based id in the whole net and whether it is
        ! owned (1) or halo (0): int32 arrays freed with ls_free_array.
        integer(c_int) function ls_part_triangles(part, ntris, global, owned) &
                bind(C, name="ls_part_triangles")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: part
            integer(c_size_t), intent(out) :: ntris
            type(c_ptr), intent(out) :: global, owned
        end function
        ! Each local vertex's 0-based id in the whole net (int32), freed with
        ! ls_free_array.
        integer(c_int) function ls_part_vertices(part, nverts, global) bind(C, name="ls_part_vertices")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: part
            integer(c_size_t), intent(out) :: nverts
            type(c_ptr), intent(out) :: global
        end function
        ! A copy of the part's net, freed with ls_net_free.
        integer(c_int) function ls_part_net(part, out) bind(C, name="ls_part_net")
            import :: c_int, c_ptr
            type(c_ptr), value :: part
            type(c_ptr), intent(out) :: out
        end function
        integer(c_int) function ls_part_save(part, bytes, n) bind(C, name="ls_part_save")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: part
            type(c_ptr), intent(out) :: bytes
            integer(c_size_t), intent(out) :: n
        end function
        integer(c_int) function ls_part_load(bytes, n, out) bind(C, name="ls_part_load")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: bytes
            integer(c_size_t), value :: n
            type(c_ptr), intent(out) :: out
        end function
        ! Every part's box (6 doubles a part), freed with ls_free_array.
        integer(c_int) function ls_net_part_bounds(net, options, nparts, bounds) &
                bind(C, name="ls_net_part_bounds")
            import :: c_int, c_size_t, c_ptr, ls_partition_options
            type(c_ptr), value :: net
            type(ls_partition_options), intent(in) :: options
            integer(c_size_t), intent(out) :: nparts
            type(c_ptr), intent(out) :: bounds
        end function
        ! The surface of part index (0-based) of nparts, freed with
        ! ls_part_surface_free.
        integer(c_int) function ls_part_surface_build(part, index, nparts, bounds, out) &
                bind(C, name="ls_part_surface_build")
            import :: c_int, c_size_t, c_ptr, c_double
            type(c_ptr), value :: part
            integer(c_int), value :: index
            integer(c_size_t), value :: nparts
            real(c_double), intent(in) :: bounds(*)
            type(c_ptr), intent(out) :: out
        end function
        subroutine ls_part_surface_free(surface) bind(C, name="ls_part_surface_free")
            import :: c_ptr
            type(c_ptr), value :: surface
        end subroutine
        integer(c_int) function ls_part_surface_bytes(surface, bytes) bind(C, name="ls_part_surface_bytes")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: surface
            integer(c_size_t), intent(out) :: bytes
        end function
        ! ls_project kept to the part's owned triangles (0-based global ids);
        ! left_at is -1, or the first triangle the walk wanted and the part
        ! does not own.
        integer(c_int) function ls_part_project(surface, xyz, tri_guess, vw_guess, tri, vw, xyz_out, &
                distance, left_at) bind(C, name="ls_part_project")
            import :: c_int, c_int32_t, c_double, c_ptr
            type(c_ptr), value :: surface
            real(c_double), intent(in) :: xyz(3), vw_guess(2)
            integer(c_int32_t), value :: tri_guess
            integer(c_int32_t), intent(out) :: tri, left_at
            real(c_double), intent(out) :: vw(2), xyz_out(3), distance
        end function
        ! The closest point over the owned triangles, the count of the parts
        ! that may hold a nearer one and the first capacity of them.
        integer(c_int) function ls_part_closest_point(surface, xyz, tri, vw, xyz_out, distance, &
                capacity, nearer, n_nearer) bind(C, name="ls_part_closest_point")
            import :: c_int, c_int32_t, c_size_t, c_double, c_ptr
            type(c_ptr), value :: surface
            real(c_double), intent(in) :: xyz(3)
            integer(c_int32_t), intent(out) :: tri
            real(c_double), intent(out) :: vw(2), xyz_out(3), distance
            integer(c_size_t), value :: capacity
            integer(c_int32_t), intent(out) :: nearer(*)
            integer(c_size_t), intent(out) :: n_nearer
        end function
        integer(c_int) function ls_fit_options_default(options) bind(C, name="ls_fit_options_default")
            import :: c_int, ls_fit_options
            type(ls_fit_options), intent(out) :: options
        end function
        ! A new net fitted to the vertices of net (docs/fitting.md).
        integer(c_int) function ls_net_fit(net, options, out) bind(C, name="ls_net_fit")
            import :: c_int, c_ptr, ls_fit_options
            type(c_ptr), value :: net
            type(ls_fit_options), intent(in) :: options
            type(c_ptr), intent(out) :: out
        end function
        subroutine ls_net_free(net) bind(C, name="ls_net_free")
            import :: c_ptr
            type(c_ptr), value :: net
        end subroutine
        integer(c_int) function ls_surface_build(net, out) bind(C, name="ls_surface_build")
            import :: c_int, c_ptr
            type(c_ptr), value :: net
            type(c_ptr), intent(out) :: out
        end function
        integer(c_int) function ls_surface_build_interpolating(net, mode, out) &
                bind(C, name="ls_surface_build_interpolating")
            import :: c_int, c_ptr
            type(c_ptr), value :: net
            integer(c_int), value :: mode
            type(c_ptr), intent(out) :: out
        end function
        integer(c_int) function ls_surface_num_triangles(surface, ntris) &
                bind(C, name="ls_surface_num_triangles")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: surface
            integer(c_size_t), intent(out) :: ntris
        end function
        ! 0-based control triangle indices (int32), freed with ls_free_array.
        integer(c_int) function ls_surface_folded_patches(surface, n, triangles) &
                bind(C, name="ls_surface_folded_patches")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: surface
            integer(c_size_t), intent(out) :: n
            type(c_ptr), intent(out) :: triangles
        end function
        integer(c_int) function ls_evaluate(surface, tri, v, w, result) bind(C, name="ls_evaluate")
            import :: c_int, c_int32_t, c_double, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: tri
            real(c_double), value :: v, w
            real(c_double), intent(out) :: result(18)
        end function
        integer(c_int) function ls_evaluate_many(surface, n, tri, vw, results) &
                bind(C, name="ls_evaluate_many")
            import :: c_int, c_size_t, c_int32_t, c_double, c_ptr
            type(c_ptr), value :: surface
            integer(c_size_t), value :: n
            integer(c_int32_t), intent(in) :: tri(*)
            real(c_double), intent(in) :: vw(*)
            real(c_double), intent(out) :: results(*)
        end function
        integer(c_int) function ls_normal(surface, tri, v, w, normal) bind(C, name="ls_normal")
            import :: c_int, c_int32_t, c_double, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: tri
            real(c_double), value :: v, w
            real(c_double), intent(out) :: normal(3)
        end function
        integer(c_int) function ls_curvature(surface, tri, v, w, result) bind(C, name="ls_curvature")
            import :: c_int, c_int32_t, c_double, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: tri
            real(c_double), value :: v, w
            real(c_double), intent(out) :: result(8)
        end function
        integer(c_int) function ls_snap(surface, xyz, tri, vw, xyz_out, distance) bind(C, name="ls_snap")
            import :: c_int, c_int32_t, c_double, c_ptr
            type(c_ptr), value :: surface
            real(c_double), intent(in) :: xyz(3)
            integer(c_int32_t), intent(out) :: tri
            real(c_double), intent(out) :: vw(2), xyz_out(3), distance
        end function
        integer(c_int) function ls_project(surface, xyz, tri_guess, vw_guess, tri, vw, xyz_out, distance) &
                bind(C, name="ls_project")
            import :: c_int, c_int32_t, c_double, c_ptr
            type(c_ptr), value :: surface
            real(c_double), intent(in) :: xyz(3), vw_guess(2)
            integer(c_int32_t), value :: tri_guess
            integer(c_int32_t), intent(out) :: tri
            real(c_double), intent(out) :: vw(2), xyz_out(3), distance
        end function
        integer(c_int) function ls_snap_options_default(options) bind(C, name="ls_snap_options_default")
            import :: c_int, ls_snap_options
            type(ls_snap_options), intent(out) :: options
        end function
        integer(c_int) function ls_snap_certified(surface, xyz, options, result) bind(C, name="ls_snap_certified")
            import :: c_int, c_double, c_ptr, ls_snap_options, ls_snap_result
            type(c_ptr), value :: surface
            real(c_double), intent(in) :: xyz(3)
            type(ls_snap_options), intent(in) :: options
            type(ls_snap_result), intent(inout) :: result
        end function
        integer(c_int) function ls_snap_guess(surface, xyz, tri_guess, vw_guess, tri, vw, xyz_out, distance) &
                bind(C, name="ls_snap_guess")
            import :: c_int, c_int32_t, c_double, c_ptr
            type(c_ptr), value :: surface
            real(c_double), intent(in) :: xyz(3), vw_guess(2)
            integer(c_int32_t), value :: tri_guess
            integer(c_int32_t), intent(out) :: tri
            real(c_double), intent(out) :: vw(2), xyz_out(3), distance
        end function
        integer(c_int) function ls_refine(surface, levels, to_limit, nverts, xyz, ntris, tris) &
                bind(C, name="ls_refine")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: surface
            integer(c_int), value :: levels, to_limit
            integer(c_size_t), intent(out) :: nverts, ntris
            type(c_ptr), intent(out) :: xyz, tris
        end function
        integer(c_int) function ls_refine_origins(surface, levels, nverts, tri, vw) &
                bind(C, name="ls_refine_origins")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: surface
            integer(c_int), value :: levels
            integer(c_size_t), intent(out) :: nverts
            type(c_ptr), intent(out) :: tri, vw
        end function
        integer(c_int) function ls_mesh_options_default(options) bind(C, name="ls_mesh_options_default")
            import :: c_int, ls_mesh_options
            type(ls_mesh_options), intent(out) :: options
        end function
        integer(c_int) function ls_mesh(surface, options, mesh) bind(C, name="ls_mesh")
            import :: c_int, c_ptr, ls_mesh_options
            type(c_ptr), value :: surface
            type(ls_mesh_options), intent(in) :: options
            type(c_ptr), intent(out) :: mesh
        end function
        integer(c_int) function ls_remesh_options_default(options) bind(C, name="ls_remesh_options_default")
            import :: c_int, ls_remesh_options
            type(ls_remesh_options), intent(out) :: options
        end function
        integer(c_int) function ls_remesh(surface, options, mesh) bind(C, name="ls_remesh")
            import :: c_int, c_ptr, ls_remesh_options
            type(c_ptr), value :: surface
            type(ls_remesh_options), intent(in) :: options
            type(c_ptr), intent(out) :: mesh
        end function
        ! The parts worth remeshing in (options%parts ignored): one per
        ! 30 000 triangles the sizes ask for, at most 64 and each of at
        ! least 16 control triangles; 1 below 60 000.
        integer(c_int) function ls_remesh_suggested_parts(surface, options, parts) &
                bind(C, name="ls_remesh_suggested_parts")
            import :: c_int, c_ptr, c_size_t, ls_remesh_options
            type(c_ptr), value :: surface
            type(ls_remesh_options), intent(in) :: options
            integer(c_size_t), intent(out) :: parts
        end function
        ! Remeshing in parts among ranks (ls_remesh_job, see the C header):
        ! every rank makes a job, then until done runs its tasks of the
        ! stage, sends their bytes to every rank (MPI_Allgatherv) and
        ! advances with everybody's bytes, counts(q) from rank q (0-based
        ! ranks). The job borrows the surface. stage points at a static
        ! C string.
        integer(c_int) function ls_remesh_job_new(surface, options, rank, ranks, job) &
                bind(C, name="ls_remesh_job_new")
            import :: c_int, c_ptr, ls_remesh_options
            type(c_ptr), value :: surface
            type(ls_remesh_options), intent(in) :: options
            integer(c_int), value :: rank, ranks
            type(c_ptr), intent(out) :: job
        end function
        integer(c_int) function ls_remesh_job_done(job, done, stage) bind(C, name="ls_remesh_job_done")
            import :: c_int, c_ptr
            type(c_ptr), value :: job
            integer(c_int), intent(out) :: done
            type(c_ptr), intent(out) :: stage
        end function
        integer(c_int) function ls_remesh_job_run(job, bytes, n) bind(C, name="ls_remesh_job_run")
            import :: c_int, c_ptr, c_size_t
            type(c_ptr), value :: job
            type(c_ptr), intent(out) :: bytes
            integer(c_size_t), intent(out) :: n
        end function
        integer(c_int) function ls_remesh_job_advance(job, all, counts) bind(C, name="ls_remesh_job_advance")
            import :: c_int, c_ptr, c_size_t, c_int8_t
            type(c_ptr), value :: job
            integer(c_int8_t), intent(in) :: all(*)
            integer(c_size_t), intent(in) :: counts(*)
        end function
        ! The whole mesh, or this rank's piece with its nodes' 0-based ids in
        ! the whole (int64, freed with ls_free_array).
        integer(c_int) function ls_remesh_job_mesh(job, mesh) bind(C, name="ls_remesh_job_mesh")
            import :: c_int, c_ptr
            type(c_ptr), value :: job
            type(c_ptr), intent(out) :: mesh
        end function
        integer(c_int) function ls_remesh_job_piece(job, piece, global_ids) bind(C, name="ls_remesh_job_piece")
            import :: c_int, c_ptr
            type(c_ptr), value :: job
            type(c_ptr), intent(out) :: piece, global_ids
        end function
        subroutine ls_remesh_job_free(job) bind(C, name="ls_remesh_job_free")
            import :: c_ptr
            type(c_ptr), value :: job
        end subroutine
        integer(c_int) function ls_adapt_options_default(options) bind(C, name="ls_adapt_options_default")
            import :: c_int, ls_adapt_options
            type(ls_adapt_options), intent(out) :: options
        end function
        integer(c_int) function ls_adapt(surface, options, mesh) bind(C, name="ls_adapt")
            import :: c_int, c_ptr, ls_adapt_options
            type(c_ptr), value :: surface
            type(ls_adapt_options), intent(in) :: options
            type(c_ptr), intent(out) :: mesh
        end function
        integer(c_int) function ls_mesh_curve_options_default(options) bind(C, name="ls_mesh_curve_options_default")
            import :: c_int, ls_mesh_curve_options
            type(ls_mesh_curve_options), intent(out) :: options
        end function
        ! Curves another tool's linear mesh (0-based tris): nodes on the
        ! surface, elements in gmsh's node order.
        integer(c_int) function ls_mesh_curve(surface, nverts, xyz, ntris, tris, options, mesh) &
                bind(C, name="ls_mesh_curve")
            import :: c_int, c_double, c_size_t, c_int32_t, c_ptr, ls_mesh_curve_options
            type(c_ptr), value :: surface
            integer(c_size_t), value :: nverts, ntris
            real(c_double), intent(in) :: xyz(*)
            integer(c_int32_t), intent(in) :: tris(*)
            type(ls_mesh_curve_options), intent(in) :: options
            type(c_ptr), intent(out) :: mesh
        end function
        ! A mesh handle's arrays are borrowed (valid until ls_trimesh_free):
        ! c_f_pointer them, or use loopsurf_trimesh_arrays.
        integer(c_int) function ls_trimesh_counts(mesh, nnodes, nelements, nodes_per_element) &
                bind(C, name="ls_trimesh_counts")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: mesh
            integer(c_size_t), intent(out) :: nnodes, nelements, nodes_per_element
        end function
        integer(c_int) function ls_trimesh_xyz(mesh, xyz) bind(C, name="ls_trimesh_xyz")
            import :: c_int, c_ptr
            type(c_ptr), value :: mesh
            type(c_ptr), intent(out) :: xyz
        end function
        integer(c_int) function ls_trimesh_elements(mesh, elements) bind(C, name="ls_trimesh_elements")
            import :: c_int, c_ptr
            type(c_ptr), value :: mesh
            type(c_ptr), intent(out) :: elements
        end function
        integer(c_int) function ls_trimesh_node_params(mesh, node_tri, node_vw) &
                bind(C, name="ls_trimesh_node_params")
            import :: c_int, c_ptr
            type(c_ptr), value :: mesh
            type(c_ptr), intent(out) :: node_tri, node_vw
        end function
        integer(c_int) function ls_trimesh_element_faces(mesh, face) bind(C, name="ls_trimesh_element_faces")
            import :: c_int, c_ptr
            type(c_ptr), value :: mesh
            type(c_ptr), intent(out) :: face
        end function
        integer(c_int) function ls_trimesh_element_charts(mesh, chart, chart_vw) &
                bind(C, name="ls_trimesh_element_charts")
            import :: c_int, c_ptr
            type(c_ptr), value :: mesh
            type(c_ptr), intent(out) :: chart, chart_vw
        end function
        integer(c_int) function ls_trimesh_deviation(mesh, deviation) bind(C, name="ls_trimesh_deviation")
            import :: c_int, c_double, c_ptr
            type(c_ptr), value :: mesh
            real(c_double), intent(out) :: deviation
        end function
        integer(c_int) function ls_trimesh_largest_move(mesh, largest_move) bind(C, name="ls_trimesh_largest_move")
            import :: c_int, c_double, c_ptr
            type(c_ptr), value :: mesh
            real(c_double), intent(out) :: largest_move
        end function
        integer(c_int) function ls_trimesh_min_scaled_jacobian(mesh, min_scaled_jacobian) &
                bind(C, name="ls_trimesh_min_scaled_jacobian")
            import :: c_int, c_double, c_ptr
            type(c_ptr), value :: mesh
            real(c_double), intent(out) :: min_scaled_jacobian
        end function
        integer(c_int) function ls_trimesh_write_options_default(options) &
                bind(C, name="ls_trimesh_write_options_default")
            import :: c_int, ls_trimesh_write_options
            type(ls_trimesh_write_options), intent(out) :: options
        end function
        ! Writes a mesh handle on the surface to .msh or .vtu; see
        ! loopsurf_trimesh_write for a Fortran string path.
        integer(c_int) function ls_trimesh_write(mesh, surface, path, options) bind(C, name="ls_trimesh_write")
            import :: c_int, c_char, c_ptr, ls_trimesh_write_options
            type(c_ptr), value :: mesh, surface
            character(kind=c_char), intent(in) :: path(*)
            type(ls_trimesh_write_options), intent(in) :: options
        end function
        subroutine ls_trimesh_free(mesh) bind(C, name="ls_trimesh_free")
            import :: c_ptr
            type(c_ptr), value :: mesh
        end subroutine
        integer(c_int) function ls_mesh_face_labels(surface, ntris, tri_chart, tri_face) &
                bind(C, name="ls_mesh_face_labels")
            import :: c_int, c_size_t, c_int32_t, c_ptr
            type(c_ptr), value :: surface
            integer(c_size_t), value :: ntris
            integer(c_int32_t), intent(in) :: tri_chart(*)
            integer(c_int32_t), intent(out) :: tri_face(*)
        end function
        integer(c_int) function ls_mesh_hard_edges(surface, nverts, vertex_tri, vertex_vw, ntris, tris, &
                nhard, pairs, curves, curve_t) bind(C, name="ls_mesh_hard_edges")
            import :: c_int, c_size_t, c_int32_t, c_double, c_ptr
            type(c_ptr), value :: surface
            integer(c_size_t), value :: nverts, ntris
            integer(c_int32_t), intent(in) :: vertex_tri(*), tris(*)
            real(c_double), intent(in) :: vertex_vw(*)
            integer(c_size_t), intent(out) :: nhard
            type(c_ptr), intent(out) :: pairs, curves
            ! Optional: c_null_ptr skips it; c_loc of a type(c_ptr) receives it.
            type(c_ptr), value :: curve_t
        end function
        ! The model: faces, curves, corners (0-based ids, -1 for none) and
        ! the exact limit curves, t in [0, n_edges].
        integer(c_int) function ls_model_counts(surface, nfaces, ncurves, ncorners) &
                bind(C, name="ls_model_counts")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: surface
            integer(c_size_t), intent(out) :: nfaces, ncurves, ncorners
        end function
        integer(c_int) function ls_model_corner(surface, corner, vertex, xyz) bind(C, name="ls_model_corner")
            import :: c_int, c_int32_t, c_double, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: corner
            integer(c_int32_t), intent(out) :: vertex
            real(c_double), intent(out) :: xyz(3)
        end function
        integer(c_int) function ls_model_curve(surface, curve, n_edges, corners, faces) &
                bind(C, name="ls_model_curve")
            import :: c_int, c_int32_t, c_size_t, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: curve
            integer(c_size_t), intent(out) :: n_edges
            integer(c_int32_t), intent(out) :: corners(2), faces(2)
        end function
        integer(c_int) function ls_model_curve_chain(surface, curve, chain) bind(C, name="ls_model_curve_chain")
            import :: c_int, c_int32_t, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: curve
            integer(c_int32_t), intent(out) :: chain(*)
        end function
        integer(c_int) function ls_model_face(surface, face, ntriangles, nloops) bind(C, name="ls_model_face")
            import :: c_int, c_int32_t, c_size_t, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: face
            integer(c_size_t), intent(out) :: ntriangles, nloops
        end function
        integer(c_int) function ls_model_face_triangles(surface, face, tris) &
                bind(C, name="ls_model_face_triangles")
            import :: c_int, c_int32_t, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: face
            integer(c_int32_t), intent(out) :: tris(*)
        end function
        ! Two calls: without curves and forward (both absent) only n is written.
        integer(c_int) function ls_model_face_loop(surface, face, loop_index, n, curves, forward) &
                bind(C, name="ls_model_face_loop")
            import :: c_int, c_int32_t, c_size_t, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: face, loop_index
            integer(c_size_t), intent(out) :: n
            integer(c_int32_t), intent(out), optional :: curves(*), forward(*)
        end function
        integer(c_int) function ls_model_triangle_face(surface, tri, face) bind(C, name="ls_model_triangle_face")
            import :: c_int, c_int32_t, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: tri
            integer(c_int32_t), intent(out) :: face
        end function
        integer(c_int) function ls_curve_evaluate(surface, curve, t, result) bind(C, name="ls_curve_evaluate")
            import :: c_int, c_int32_t, c_double, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: curve
            real(c_double), value :: t
            real(c_double), intent(out) :: result(9)
        end function
        integer(c_int) function ls_curve_length(surface, curve, t0, t1, length) bind(C, name="ls_curve_length")
            import :: c_int, c_int32_t, c_double, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: curve
            real(c_double), value :: t0, t1
            real(c_double), intent(out) :: length
        end function
        integer(c_int) function ls_curve_param_at_length(surface, curve, s, t) &
                bind(C, name="ls_curve_param_at_length")
            import :: c_int, c_int32_t, c_double, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: curve
            real(c_double), value :: s
            real(c_double), intent(out) :: t
        end function
        integer(c_int) function ls_curve_surface_points(surface, curve, t, n, faces, tris, vw) &
                bind(C, name="ls_curve_surface_points")
            import :: c_int, c_int32_t, c_size_t, c_double, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: curve
            real(c_double), value :: t
            integer(c_size_t), intent(out) :: n
            integer(c_int32_t), intent(out) :: faces(2), tris(2)
            real(c_double), intent(out) :: vw(4)
        end function
        integer(c_int) function ls_curve_project(surface, curve, xyz, t_guess, t, xyz_out, distance) &
                bind(C, name="ls_curve_project")
            import :: c_int, c_int32_t, c_double, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: curve
            real(c_double), intent(in) :: xyz(3)
            real(c_double), value :: t_guess
            real(c_double), intent(out) :: t, xyz_out(3), distance
        end function
        integer(c_int) function ls_curve_snap(surface, curve, xyz, tolerance, t, xyz_out, distance, lower_bound) &
                bind(C, name="ls_curve_snap")
            import :: c_int, c_int32_t, c_double, c_ptr
            type(c_ptr), value :: surface
            integer(c_int32_t), value :: curve
            real(c_double), intent(in) :: xyz(3)
            real(c_double), value :: tolerance
            real(c_double), intent(out) :: t, xyz_out(3), distance, lower_bound
        end function
        subroutine ls_free_array(array) bind(C, name="ls_free_array")
            import :: c_ptr
            type(c_ptr), value :: array
        end subroutine
        integer(c_int) function ls_surface_save(surface, bytes, n) bind(C, name="ls_surface_save")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: surface
            type(c_ptr), intent(out) :: bytes
            integer(c_size_t), intent(out) :: n
        end function
        subroutine ls_free_bytes(bytes, n) bind(C, name="ls_free_bytes")
            import :: c_size_t, c_ptr
            type(c_ptr), value :: bytes
            integer(c_size_t), value :: n
        end subroutine
        integer(c_int) function ls_surface_load(bytes, n, out) bind(C, name="ls_surface_load")
            import :: c_int, c_size_t, c_ptr
            type(c_ptr), value :: bytes
            integer(c_size_t), value :: n
            type(c_ptr), intent(out) :: out
        end function
        subroutine ls_surface_free(surface) bind(C, name="ls_surface_free")
            import :: c_ptr
            type(c_ptr), value :: surface
        end subroutine
        type(c_ptr) function ls_last_error() bind(C, name="ls_last_error")
            import :: c_ptr
        end function
        type(c_ptr) function ls_status_string(status) bind(C, name="ls_status_string")
            import :: c_int, c_ptr
            integer(c_int), value :: status
        end function
        subroutine ls_version(major, minor, patch) bind(C, name="ls_version")
            import :: c_int
            integer(c_int), intent(out) :: major, minor, patch
        end subroutine
        function c_strlen(s) bind(C, name="strlen") result(n)
            import :: c_ptr, c_size_t
            type(c_ptr), value :: s
            integer(c_size_t) :: n
        end function
    end interface

contains

    !> Reads a mesh file (.off .obj .ply .stl .tri) into a new net.
    integer function loopsurf_load(path, net) result(status)
        character(len=*), intent(in) :: path
        type(c_ptr), intent(out) :: net
        status = ls_net_load(c_string(path), net)
    end function

    !> loopsurf_load with repairs of dirty files: flags is a sum of
    !> LS_LOAD_*, weld_eps the weld distance (fraction of the diagonal, 0
    !> for the default) used with LS_LOAD_WELD.
    integer function loopsurf_load_with(path, flags, weld_eps, net) result(status)
        character(len=*), intent(in) :: path
        integer, intent(in) :: flags
        real(c_double), intent(in) :: weld_eps
        type(c_ptr), intent(out) :: net
        status = ls_net_load_with(c_string(path), int(flags, c_int32_t), weld_eps, net)
    end function

    !> What the repairs of loopsurf_load_with changed, one line per repair
    !> (new_line('a')-separated; empty when nothing changed).
    function loopsurf_repair_report(net) result(report)
        type(c_ptr), intent(in) :: net
        character(len=:), allocatable :: report
        character(kind=c_char) :: probe(1)
        character(kind=c_char), allocatable :: buf(:)
        integer(c_size_t) :: needed
        integer :: i, n
        report = ""
        if (ls_net_repair_report(net, probe, 1_c_size_t, needed) /= LS_OK) return
        allocate(buf(needed))
        if (ls_net_repair_report(net, buf, needed, needed) /= LS_OK) return
        n = int(needed) - 1
        report = repeat(" ", n)
        do i = 1, n
            report(i:i) = buf(i)
        end do
    end function

    !> A net from points xyz(3, nverts) and triangles tris(3, ntris) with
    !> 1-BASED vertex numbers.
    integer function loopsurf_from_arrays(xyz, tris, net) result(status)
        real(c_double), intent(in) :: xyz(:, :)
        integer, intent(in) :: tris(:, :)
        type(c_ptr), intent(out) :: net
        integer(c_int32_t), allocatable :: zero_based(:, :)
        zero_based = int(tris - 1, c_int32_t)
        status = ls_net_from_arrays(size(xyz, 2, kind=c_size_t), xyz, &
            size(tris, 2, kind=c_size_t), zero_based, net)
    end function

    !> Tags the edge between 1-BASED vertices a and b hard.
    integer function loopsurf_tag_edge(net, a, b) result(status)
        type(c_ptr), intent(in) :: net
        integer, intent(in) :: a, b
        status = ls_net_tag_edge(net, int(a - 1, c_int32_t), int(b - 1, c_int32_t))
    end function

    !> X, Xv, Xw, Xvv, Xvw, Xww at (v, w) of 1-BASED triangle tri.
    integer function loopsurf_evaluate(surface, tri, v, w, result) result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(in) :: tri
        real(c_double), intent(in) :: v, w
        real(c_double), intent(out) :: result(18)
        status = ls_evaluate(surface, int(tri - 1, c_int32_t), v, w, result)
    end function

    !> k1, dir1, k2, dir2 at (v, w) of 1-BASED triangle tri.
    integer function loopsurf_curvature(surface, tri, v, w, result) result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(in) :: tri
        real(c_double), intent(in) :: v, w
        real(c_double), intent(out) :: result(8)
        status = ls_curvature(surface, int(tri - 1, c_int32_t), v, w, result)
    end function

    !> The closest surface point to xyz; tri comes back 1-BASED.
    integer function loopsurf_snap(surface, xyz, tri, vw, xyz_out, distance) result(status)
        type(c_ptr), intent(in) :: surface
        real(c_double), intent(in) :: xyz(3)
        integer, intent(out) :: tri
        real(c_double), intent(out) :: vw(2), xyz_out(3), distance
        integer(c_int32_t) :: t
        status = ls_snap(surface, xyz, t, vw, xyz_out, distance)
        if (status == LS_OK) tri = int(t) + 1
    end function

    !> The nearest LOCAL minimum of the distance to xyz, by Newton's method
    !> from the guess (tri_guess 1-BASED, vw_guess): for points moved a little,
    !> guessed from a neighbour; no global search. tri comes back 1-BASED.
    integer function loopsurf_project(surface, xyz, tri_guess, vw_guess, tri, vw, xyz_out, distance) result(status)
        type(c_ptr), intent(in) :: surface
        real(c_double), intent(in) :: xyz(3), vw_guess(2)
        integer, intent(in) :: tri_guess
        integer, intent(out) :: tri
        real(c_double), intent(out) :: vw(2), xyz_out(3), distance
        integer(c_int32_t) :: t
        status = ls_project(surface, xyz, int(tri_guess - 1, c_int32_t), vw_guess, t, vw, xyz_out, distance)
        if (status == LS_OK) tri = int(t) + 1
    end function

    !> The closest surface point to xyz with its certificate: a proven lower
    !> bound on the distance to the whole surface, within tolerance times the
    !> bounding-box diagonal of the distance (tolerance in (0, 1); 1d-12 is
    !> the default of ls_snap_options_default). tri comes back 1-BASED.
    integer function loopsurf_snap_certified(surface, xyz, tolerance, tri, vw, xyz_out, distance, lower_bound) &
            result(status)
        type(c_ptr), intent(in) :: surface
        real(c_double), intent(in) :: xyz(3), tolerance
        integer, intent(out) :: tri
        real(c_double), intent(out) :: vw(2), xyz_out(3), distance, lower_bound
        type(ls_snap_options) :: options
        type(ls_snap_result) :: answer
        status = ls_snap_options_default(options)
        if (status /= LS_OK) return
        options%tolerance = tolerance
        answer%struct_size = c_sizeof(answer)
        status = ls_snap_certified(surface, xyz, options, answer)
        if (status /= LS_OK) return
        tri = int(answer%tri) + 1
        vw = answer%vw
        xyz_out = answer%xyz
        distance = answer%distance
        lower_bound = answer%lower_bound
    end function

    !> The arrays of a mesh handle (ls_trimesh), copied into Fortran arrays
    !> with 1-BASED numbers: nodes(3, nnodes), elements(nodes_per_element,
    !> nelements) of node numbers, and per node its control triangle
    !> node_tri(nnodes) and (v, w) node_vw(2, nnodes), so that
    !> loopsurf_evaluate(surface, node_tri(i), node_vw(1, i), node_vw(2, i),
    !> r) gives r(1:3) = nodes(:, i).
    integer function loopsurf_trimesh_arrays(mesh, nodes, elements, node_tri, node_vw) result(status)
        type(c_ptr), intent(in) :: mesh
        real(c_double), allocatable, intent(inout) :: nodes(:, :), node_vw(:, :)
        integer, allocatable, intent(inout) :: elements(:, :), node_tri(:)
        integer(c_size_t) :: nn, ne, per
        type(c_ptr) :: cxyz, celems, ctri, cvw
        real(c_double), pointer :: pxyz(:, :), pvw(:, :)
        integer(c_int32_t), pointer :: pelems(:, :), ptri(:)
        status = ls_trimesh_counts(mesh, nn, ne, per)
        if (status == LS_OK) status = ls_trimesh_xyz(mesh, cxyz)
        if (status == LS_OK) status = ls_trimesh_elements(mesh, celems)
        if (status == LS_OK) status = ls_trimesh_node_params(mesh, ctri, cvw)
        if (status /= LS_OK) return
        call c_f_pointer(cxyz, pxyz, [3_c_size_t, nn])
        call c_f_pointer(celems, pelems, [per, ne])
        call c_f_pointer(ctri, ptri, [nn])
        call c_f_pointer(cvw, pvw, [2_c_size_t, nn])
        nodes = pxyz
        elements = int(pelems) + 1
        node_tri = int(ptri) + 1
        node_vw = pvw
    end function

    !> The 1-BASED model face of each element of a mesh handle.
    integer function loopsurf_trimesh_faces(mesh, faces) result(status)
        type(c_ptr), intent(in) :: mesh
        integer, allocatable, intent(inout) :: faces(:)
        integer(c_size_t) :: nn, ne, per
        type(c_ptr) :: cface
        integer(c_int32_t), pointer :: pface(:)
        status = ls_trimesh_counts(mesh, nn, ne, per)
        if (status == LS_OK) status = ls_trimesh_element_faces(mesh, cface)
        if (status /= LS_OK) return
        call c_f_pointer(cface, pface, [ne])
        faces = int(pface) + 1
    end function

    !> The quality remesher (ls_remesh) with its options (fill them with
    !> ls_remesh_options_default): near-equilateral triangles on the limit
    !> surface. Allocates xyz(3, nverts), tris(3, ntris) with 1-BASED vertex
    !> numbers, per vertex its 1-BASED control triangle vertex_tri(nverts)
    !> and (v, w) vertex_vw(2, nverts), and the 1-BASED model face of each
    !> triangle tri_face(ntris). deviation is the largest chord error
    !> measured, relative to the diagonal, or -1 when no tolerance applied.
    !> Everything is left untouched on failure.
    integer function loopsurf_remesh(surface, options, xyz, tris, vertex_tri, vertex_vw, tri_face, deviation) &
            result(status)
        type(c_ptr), intent(in) :: surface
        type(ls_remesh_options), intent(in) :: options
        real(c_double), allocatable, intent(inout) :: xyz(:, :), vertex_vw(:, :)
        integer, allocatable, intent(inout) :: tris(:, :), vertex_tri(:), tri_face(:)
        real(c_double), intent(inout) :: deviation
        type(c_ptr) :: mesh
        real(c_double) :: dev
        status = ls_remesh(surface, options, mesh)
        if (status /= LS_OK) return
        status = loopsurf_trimesh_arrays(mesh, xyz, tris, vertex_tri, vertex_vw)
        if (status == LS_OK) status = loopsurf_trimesh_faces(mesh, tri_face)
        if (status == LS_OK) then
            if (ls_trimesh_deviation(mesh, dev) /= LS_OK) dev = -1d0
            deviation = dev
        end if
        call ls_trimesh_free(mesh)
    end function

    !> Curves another tool's linear mesh (ls_mesh_curve) with its options
    !> (fill them with ls_mesh_curve_options_default): xyz(3, nverts) and
    !> tris(3, ntris) with 1-BASED vertex numbers, counter-clockwise like the
    !> net. Every vertex goes to its closest point on the surface (refused
    !> beyond options%max_move of the diagonal), and every triangle becomes
    !> a Lagrange triangle of order options%order (1 to 4). Allocates
    !> nodes(3, nnodes) (the input vertices first), per node its 1-BASED
    !> control triangle node_tri(nnodes) and (v, w) node_vw(2, nnodes),
    !> elements((order+1)(order+2)/2, ntris) with 1-BASED node numbers in
    !> gmsh's order, and the 1-BASED model face of each triangle
    !> tri_face(ntris); largest_move is in model units, min_jacobian the
    !> smallest scaled Jacobian (<= 0: an element folds). Everything is left
    !> untouched on failure.
    integer function loopsurf_mesh_curve(surface, xyz, tris, options, nodes, node_tri, node_vw, &
            elements, tri_face, largest_move, min_jacobian) result(status)
        type(c_ptr), intent(in) :: surface
        real(c_double), intent(in) :: xyz(:, :)
        integer, intent(in) :: tris(:, :)
        type(ls_mesh_curve_options), intent(in) :: options
        real(c_double), allocatable, intent(inout) :: nodes(:, :), node_vw(:, :)
        integer, allocatable, intent(inout) :: node_tri(:), elements(:, :), tri_face(:)
        real(c_double), intent(inout) :: largest_move, min_jacobian
        type(c_ptr) :: mesh
        integer(c_int32_t), allocatable :: ctris(:, :)
        real(c_double) :: moved, jac
        ctris = int(tris - 1, c_int32_t)
        status = ls_mesh_curve(surface, size(xyz, 2, kind=c_size_t), xyz, size(tris, 2, kind=c_size_t), ctris, &
            options, mesh)
        if (status /= LS_OK) return
        status = ls_trimesh_largest_move(mesh, moved)
        if (status == LS_OK) status = ls_trimesh_min_scaled_jacobian(mesh, jac)
        if (status == LS_OK) status = loopsurf_trimesh_arrays(mesh, nodes, elements, node_tri, node_vw)
        if (status == LS_OK) status = loopsurf_trimesh_faces(mesh, tri_face)
        if (status == LS_OK) then
            largest_move = moved
            min_jacobian = jac
        end if
        call ls_trimesh_free(mesh)
    end function

    ! The model with 1-BASED ids: faces, curves, corners, triangles and
    ! vertices all count from 1, and 0 means none. A curve's parameter t
    ! is the same as in C: [0, n_edges]. Arrays are allocated here, and left
    ! untouched on failure.

    !> The numbers of faces, curves and corners (ids 1 to each count).
    integer function loopsurf_model_counts(surface, nfaces, ncurves, ncorners) result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(out) :: nfaces, ncurves, ncorners
        integer(c_size_t) :: f, c, k
        status = ls_model_counts(surface, f, c, k)
        if (status /= LS_OK) return
        nfaces = int(f)
        ncurves = int(c)
        ncorners = int(k)
    end function

    !> Corner `corner`: its 1-BASED control vertex and its limit point.
    integer function loopsurf_model_corner(surface, corner, vertex, xyz) result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(in) :: corner
        integer, intent(out) :: vertex
        real(c_double), intent(out) :: xyz(3)
        integer(c_int32_t) :: v
        status = ls_model_corner(surface, int(corner - 1, c_int32_t), v, xyz)
        if (status == LS_OK) vertex = int(v) + 1
    end function

    !> Curve `curve`: its number of control edges (t runs over [0, n_edges]),
    !> its corners at t = 0 and t = n_edges (0, 0 for a closed loop) and its
    !> faces on the left and on the right (0 for none: a boundary).
    integer function loopsurf_model_curve(surface, curve, n_edges, corners, faces) result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(in) :: curve
        integer, intent(out) :: n_edges, corners(2), faces(2)
        integer(c_size_t) :: n
        integer(c_int32_t) :: k(2), f(2)
        status = ls_model_curve(surface, int(curve - 1, c_int32_t), n, k, f)
        if (status /= LS_OK) return
        n_edges = int(n)
        corners = int(k) + 1
        faces = int(f) + 1
    end function

    !> The n_edges + 1 control vertices (1-BASED) of curve `curve`, in
    !> parameter order: chain(k + 1) is the vertex at t = k.
    integer function loopsurf_model_curve_chain(surface, curve, chain) result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(in) :: curve
        integer, allocatable, intent(inout) :: chain(:)
        integer(c_size_t) :: n
        integer(c_int32_t) :: k(2), f(2)
        integer(c_int32_t), allocatable :: c(:)
        status = ls_model_curve(surface, int(curve - 1, c_int32_t), n, k, f)
        if (status /= LS_OK) return
        allocate(c(n + 1))
        status = ls_model_curve_chain(surface, int(curve - 1, c_int32_t), c)
        if (status == LS_OK) chain = int(c) + 1
    end function

    !> Face `face`: its numbers of control triangles and of bounding loops.
    integer function loopsurf_model_face(surface, face, ntriangles, nloops) result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(in) :: face
        integer, intent(out) :: ntriangles, nloops
        integer(c_size_t) :: nt, nl
        status = ls_model_face(surface, int(face - 1, c_int32_t), nt, nl)
        if (status /= LS_OK) return
        ntriangles = int(nt)
        nloops = int(nl)
    end function

    !> The control triangles (1-BASED, ascending) of face `face`.
    integer function loopsurf_model_face_triangles(surface, face, tris) result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(in) :: face
        integer, allocatable, intent(inout) :: tris(:)
        integer(c_size_t) :: nt, nl
        integer(c_int32_t), allocatable :: t(:)
        status = ls_model_face(surface, int(face - 1, c_int32_t), nt, nl)
        if (status /= LS_OK) return
        allocate(t(nt))
        status = ls_model_face_triangles(surface, int(face - 1, c_int32_t), t)
        if (status == LS_OK) tris = int(t) + 1
    end function

    !> Loop `loop` of face `face`: its curves in the order the face's
    !> triangles run its boundary, and whether each is run forward (from
    !> t = 0 to n_edges). Each curve ends where the next one begins.
    integer function loopsurf_model_face_loop(surface, face, loop, curves, forward) result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(in) :: face, loop
        integer, allocatable, intent(inout) :: curves(:)
        logical, allocatable, intent(inout) :: forward(:)
        integer(c_size_t) :: n
        integer(c_int32_t), allocatable :: c(:), fw(:)
        status = ls_model_face_loop(surface, int(face - 1, c_int32_t), int(loop - 1, c_int32_t), n)
        if (status /= LS_OK) return
        allocate(c(n), fw(n))
        status = ls_model_face_loop(surface, int(face - 1, c_int32_t), int(loop - 1, c_int32_t), n, c, fw)
        if (status /= LS_OK) return
        curves = int(c) + 1
        forward = fw /= 0
    end function

    !> The face of 1-BASED control triangle tri.
    integer function loopsurf_model_triangle_face(surface, tri, face) result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(in) :: tri
        integer, intent(out) :: face
        integer(c_int32_t) :: f
        status = ls_model_triangle_face(surface, int(tri - 1, c_int32_t), f)
        if (status == LS_OK) face = int(f) + 1
    end function

    !> X, X', X'' (9 numbers) of curve `curve` at t in [0, n_edges].
    integer function loopsurf_curve_evaluate(surface, curve, t, result) result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(in) :: curve
        real(c_double), intent(in) :: t
        real(c_double), intent(out) :: result(9)
        status = ls_curve_evaluate(surface, int(curve - 1, c_int32_t), t, result)
    end function

    !> The arc length of curve `curve` from t0 to t1.
    integer function loopsurf_curve_length(surface, curve, t0, t1, length) result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(in) :: curve
        real(c_double), intent(in) :: t0, t1
        real(c_double), intent(out) :: length
        status = ls_curve_length(surface, int(curve - 1, c_int32_t), t0, t1, length)
    end function

    !> The parameter t of curve `curve` at arc length s from t = 0.
    integer function loopsurf_curve_param_at_length(surface, curve, s, t) result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(in) :: curve
        real(c_double), intent(in) :: s
        real(c_double), intent(out) :: t
        status = ls_curve_param_at_length(surface, int(curve - 1, c_int32_t), s, t)
    end function

    !> The curve point at t on each side: n (1 on a boundary, else 2), and
    !> for side i its face faces(i), triangle tris(i) (1-BASED; 0 when
    !> unused) and (v, w) = vw(:, i), where loopsurf_evaluate gives the
    !> curve point. Sides in the order of loopsurf_model_curve's faces.
    integer function loopsurf_curve_surface_points(surface, curve, t, n, faces, tris, vw) result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(in) :: curve
        real(c_double), intent(in) :: t
        integer, intent(out) :: n, faces(2), tris(2)
        real(c_double), intent(out) :: vw(2, 2)
        integer(c_size_t) :: nn
        integer(c_int32_t) :: f(2), tr(2)
        status = ls_curve_surface_points(surface, int(curve - 1, c_int32_t), t, nn, f, tr, vw)
        if (status /= LS_OK) return
        n = int(nn)
        faces = int(f) + 1
        tris = int(tr) + 1
    end function

    !> The nearest LOCAL minimum of the distance from xyz to curve `curve`,
    !> by Newton's method from t_guess: for points moved a little.
    integer function loopsurf_curve_project(surface, curve, xyz, t_guess, t, xyz_out, distance) result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(in) :: curve
        real(c_double), intent(in) :: xyz(3), t_guess
        real(c_double), intent(out) :: t, xyz_out(3), distance
        status = ls_curve_project(surface, int(curve - 1, c_int32_t), xyz, t_guess, t, xyz_out, distance)
    end function

    !> The closest point of curve `curve` to xyz (global), with a proven
    !> lower bound on the distance, within tolerance times the bounding-box
    !> diagonal (0 for the default, 1d-12).
    integer function loopsurf_curve_snap(surface, curve, xyz, tolerance, t, xyz_out, distance, lower_bound) &
            result(status)
        type(c_ptr), intent(in) :: surface
        integer, intent(in) :: curve
        real(c_double), intent(in) :: xyz(3), tolerance
        real(c_double), intent(out) :: t, xyz_out(3), distance, lower_bound
        status = ls_curve_snap(surface, int(curve - 1, c_int32_t), xyz, tolerance, t, xyz_out, distance, lower_bound)
    end function

    !> The last error on this thread, as a Fortran string.
    function loopsurf_last_error() result(message)
        character(len=:), allocatable :: message
        message = f_string(ls_last_error())
    end function

    !> The name and meaning of a status code.
    function loopsurf_status_string(status) result(message)
        integer, intent(in) :: status
        character(len=:), allocatable :: message
        message = f_string(ls_status_string(int(status, c_int)))
    end function

    function f_string(p) result(s)
        type(c_ptr), intent(in) :: p
        character(len=:), allocatable :: s
        character(kind=c_char), pointer :: chars(:)
        integer :: i, n
        n = int(c_strlen(p))
        call c_f_pointer(p, chars, [n])
        allocate(character(len=n) :: s)
        do i = 1, n
            s(i:i) = chars(i)
        end do
    end function

    !> Writes a mesh handle (from ls_remesh, ls_mesh, ls_mesh_curve or a
    !> job's piece), which lies on `surface`, to `path`: gmsh .msh 4.1 or
    !> VTK .vtu, by the extension.
    integer function loopsurf_trimesh_write(mesh, surface, path, options) result(status)
        type(c_ptr), intent(in) :: mesh, surface
        character(len=*), intent(in) :: path
        type(ls_trimesh_write_options), intent(in) :: options
        status = ls_trimesh_write(mesh, surface, c_string(path), options)
    end function

    function c_string(s) result(c)
        character(len=*), intent(in) :: s
        character(kind=c_char) :: c(len_trim(s) + 1)
        integer :: i
        do i = 1, len_trim(s)
            c(i) = s(i:i)
        end do
        c(len_trim(s) + 1) = c_null_char
    end function
end module loopsurf
