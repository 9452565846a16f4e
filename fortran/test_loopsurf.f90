! The Fortran module against real properties of the surface: an octahedron
! net built from 1-based arrays, evaluated one by one and in a batch,
! translated, streamed, refined, snapped, interpolated, and fed bad input.
! Fortran may evaluate the operands of .and. in any order (or skip one), so
! a call and a test of its outputs always take two statements.
program test_loopsurf
    use loopsurf
    use, intrinsic :: iso_c_binding
    implicit none
    real(c_double) :: xyz(3, 6), moved(3, 6), r(18), r2(18), many(18, 4), vw(2, 4), k(8)
    real(c_double) :: p(3), q(3), uv(2), dist, shift(3), q2(3), uv2(2), dist2, bound
    integer :: tris(3, 8), i, failures, tri, tri2
    integer(c_int32_t) :: tri0(4)
    integer(c_size_t) :: n, nv, nt, nh
    type(c_ptr) :: net, net2, surf, surf2, surf3, bytes, rxyz, rtris, mvw
    integer(c_int) :: major, minor, patch
    type(c_ptr) :: net3
    character(len=1024) :: tmpdir, path
    integer :: unit

    failures = 0
    xyz = reshape([1d0, 0d0, 0d0, -1d0, 0d0, 0d0, 0d0, 1d0, 0d0, &
                   0d0, -1d0, 0d0, 0d0, 0d0, 1d0, 0d0, 0d0, -1d0], [3, 6])
    tris = reshape([1, 3, 5, 3, 2, 5, 2, 4, 5, 4, 1, 5, &
                    3, 1, 6, 2, 3, 6, 4, 2, 6, 1, 4, 6], [3, 8])
    call check(loopsurf_from_arrays(xyz, tris, net) == LS_OK, "from_arrays")
    call check(ls_net_counts(net, nv, nt, nh) == LS_OK, "counts")
    call check(nv == 6 .and. nt == 8 .and. nh == 0, "counts: 6, 8, 0")
    call check(loopsurf_tag_edge(net, 1, 3) == LS_OK, "tag_edge (1-based)")
    call check(loopsurf_tag_edge(net, 1, 2) == LS_ERR_INVALID_ARGUMENT, "not an edge")
    call check(loopsurf_tag_edge(net, 1, 7) == LS_ERR_INDEX_OUT_OF_RANGE, "vertex 7 of 6")
    call check(len(loopsurf_last_error()) > 0, "last error set")
    call check(ls_surface_build(net, surf) == LS_OK, "build")

    ! Batch equals one by one, bit for bit.
    vw = reshape([0.1d0, 0.2d0, 0.3d0, 0.3d0, 0d0, 0d0, 0.5d0, 0.5d0], [2, 4])
    tri0 = [0, 3, 5, 7]
    call check(ls_evaluate_many(surf, 4_c_size_t, tri0, vw, many) == LS_OK, "evaluate_many")
    do i = 1, 4
        call check(loopsurf_evaluate(surf, int(tri0(i)) + 1, vw(1, i), vw(2, i), r) == LS_OK, "evaluate")
        call check(all(r == many(:, i)), "batch equals single")
    end do

    ! Affine invariance: translating the net translates the surface.
    shift = [0.25d0, -1.5d0, 3d0]
    do i = 1, 6
        moved(:, i) = xyz(:, i) + shift
    end do
    call check(loopsurf_from_arrays(moved, tris, net2) == LS_OK, "moved net")
    call check(loopsurf_tag_edge(net2, 1, 3) == LS_OK, "moved tag")
    call check(ls_surface_build(net2, surf2) == LS_OK, "moved build")
    call check(loopsurf_evaluate(surf, 2, 0.2d0, 0.3d0, r) == LS_OK, "eval")
    call check(loopsurf_evaluate(surf2, 2, 0.2d0, 0.3d0, r2) == LS_OK, "eval moved")
    call check(maxval(abs(r2(1:3) - r(1:3) - shift)) < 1d-14, "translated point")
    call check(maxval(abs(r2(4:18) - r(4:18))) < 1d-13, "same derivatives")

    ! Curvature of the rounded octahedron is positive (convex), k1 >= k2.
    call check(loopsurf_curvature(surf, 3, 0.3d0, 0.3d0, k) == LS_OK, "curvature")
    call check(k(1) >= k(5) .and. k(5) > 0d0, "convex curvature")

    ! Errors: bad triangle, parameter out of range, NaN.
    call check(loopsurf_evaluate(surf, 9, 0.1d0, 0.1d0, r) == LS_ERR_INDEX_OUT_OF_RANGE, "triangle 9 of 8")
    call check(loopsurf_evaluate(surf, 1, 0.8d0, 0.8d0, r) == LS_ERR_PARAMETER_OUT_OF_RANGE, "v + w > 1")
    call check(loopsurf_evaluate(surf, 1, ieee_nan(), 0.1d0, r) == LS_ERR_NOT_FINITE, "NaN")
    call check(index(loopsurf_status_string(LS_ERR_NOT_FINITE), "LS_ERR_NOT_FINITE") == 1, "status string")

    ! Save, load: bit-identical evaluations.
    call check(ls_surface_save(surf, bytes, n) == LS_OK, "save")
    call check(n > 0, "save: bytes")
    call check(ls_surface_load(bytes, n, surf3) == LS_OK, "load")
    call check(ls_surface_load(bytes, n - 1, surf2) == LS_ERR_BAD_STREAM, "truncated stream")
    call check(c_associated(surf2), "truncated stream: a handle")
    call ls_free_bytes(bytes, n)
    call check(loopsurf_evaluate(surf3, 5, 0.1d0, 0.7d0, r2) == LS_OK, "eval loaded")
    call check(loopsurf_evaluate(surf, 5, 0.1d0, 0.7d0, r) == LS_OK, "eval original")
    call check(all(r == r2), "loaded evaluates bit-identically")
    call ls_surface_free(surf3)

    ! Refinement counts: 8 * 4**2 triangles, Euler: V = T/2 + 2.
    call check(ls_refine(surf, 2_c_int, 0_c_int, nv, rxyz, nt, rtris) == LS_OK, "refine")
    call check(nt == 128 .and. nv == 66, "refined counts")
    call ls_free_array(rxyz)
    call ls_free_array(rtris)
    call check(ls_refine_origins(surf, 2_c_int, n, rxyz, rtris) == LS_OK, "refine origins")
    call check(n == 66, "refine origins: 66")
    call ls_free_array(rxyz)
    call ls_free_array(rtris)
    ! Partition of the octahedron into 4 parts of 2 triangles each; the
    ! same parts twice; K = 9 of 8 triangles refused (the C test checks
    ! that the outputs stay untouched: here they are intent(out)).
    block
        type(ls_partition_options) :: po
        type(c_ptr) :: part_c, part2_c
        integer(c_int32_t), pointer :: part(:), part2(:)
        integer(c_size_t) :: cut, cut2
        call check(ls_partition_options_default(po) == LS_OK, "partition options")
        call check(po%struct_size == c_sizeof(po) .and. po%parts == 1 .and. po%seed == 1, &
                   "partition options: defaults")
        po%parts = 4
        call check(ls_net_partition(net, po, nt, part_c, cut) == LS_OK, "partition")
        call check(nt == 8, "partition: 8 triangles")
        call c_f_pointer(part_c, part, [nt])
        do i = 0, 3
            call check(count(part == i) == 2, "partition: two triangles a part")
        end do
        call check(cut >= 4 .and. cut <= 12, "partition: cut")
        call check(ls_net_partition(net, po, nt, part2_c, cut2) == LS_OK, "partition again")
        call c_f_pointer(part2_c, part2, [nt])
        call check(all(part == part2) .and. cut == cut2, "partition: deterministic")
        call ls_free_array(part2_c)
        po%parts = 9
        call check(ls_net_partition(net, po, nt, part2_c, cut2) == LS_ERR_INVALID_ARGUMENT, "K = 9 of 8")
        call check(index(loopsurf_last_error(), "K = 9") > 0, "partition: refusal names K")
        call ls_free_array(part_c)
    end block
    ! One part of four, its maps and its stream.
    block
        type(ls_part_options) :: qo
        type(c_ptr) :: part, back, sub, global_c, owned_c, bytes
        integer(c_int32_t), pointer :: global(:), owned(:)
        integer(c_size_t) :: n_owned, n_halo, n_verts, n_tris, n_bytes
        call check(ls_part_options_default(qo) == LS_OK .and. qo%struct_size == c_sizeof(qo) &
                   .and. qo%parts == 1 .and. qo%part == 0, "part options")
        qo%parts = 4
        qo%part = 2
        call check(ls_net_part(net, qo, part) == LS_OK, "part")
        call check(ls_part_counts(part, n_owned, n_halo, n_verts) == LS_OK .and. n_owned == 2, "part counts")
        call check(ls_part_triangles(part, n_tris, global_c, owned_c) == LS_OK &
                   .and. n_tris == n_owned + n_halo, "part triangles")
        call c_f_pointer(global_c, global, [n_tris])
        call c_f_pointer(owned_c, owned, [n_tris])
        call check(count(owned == 1) == 2 .and. all(global >= 0 .and. global < 8), "part maps")
        call check(ls_part_net(part, sub) == LS_OK, "part net")
        call check(ls_part_save(part, bytes, n_bytes) == LS_OK, "part save")
        call check(ls_part_load(bytes, n_bytes, back) == LS_OK, "part load")
        call check(ls_part_load(bytes, n_bytes - 1, back) == LS_ERR_BAD_STREAM, "part load: truncated")
        qo%part = 4
        call check(ls_net_part(net, qo, back) == LS_ERR_INVALID_ARGUMENT, "part 4 of 4")
        call ls_free_bytes(bytes, n_bytes)
        call ls_free_array(global_c)
        call ls_free_array(owned_c)
        call ls_net_free(sub)
        call ls_part_free(part)
    end block
    ! The surface of one part of four: a walk on its own triangles is the
    ! whole's, and its closest point is the whole's or names a nearer part.
    block
        type(ls_partition_options) :: po
        type(ls_part_options) :: qo
        type(c_ptr) :: part, ps, bounds_c, global_c, owned_c
        real(c_double), pointer :: bounds(:)
        integer(c_int32_t), pointer :: global(:), owned(:)
        integer(c_size_t) :: nparts, n_tris, n_near, n_bytes
        integer(c_int32_t) :: t0, wt, pt, left_at, near(3)
        real(c_double) :: e(18), p(3), wvw(2), wx(3), wd, pvw(2), px(3), pd
        call check(ls_partition_options_default(po) == LS_OK, "part surface: options")
        po%parts = 4
        call check(ls_net_part_bounds(net, po, nparts, bounds_c) == LS_OK .and. nparts == 4, "part bounds")
        call c_f_pointer(bounds_c, bounds, [6 * nparts])
        call check(all(bounds(1:3) <= bounds(4:6)), "part bounds: low below high")
        call check(ls_part_options_default(qo) == LS_OK, "part surface: part options")
        qo%parts = 4
        qo%part = 2
        call check(ls_net_part(net, qo, part) == LS_OK, "part surface: part")
        call check(ls_part_surface_build(part, 2_c_int, nparts, bounds, ps) == LS_OK, "part surface")
        call check(ls_part_triangles(part, n_tris, global_c, owned_c) == LS_OK, "part surface: maps")
        call c_f_pointer(global_c, global, [n_tris])
        call c_f_pointer(owned_c, owned, [n_tris])
        t0 = global(findloc(owned, 1, dim=1))
        call check(ls_evaluate(surf, t0, 0.2d0, 0.3d0, e) == LS_OK, "part surface: a point")
        p = 1.01d0 * e(1:3)
        call check(ls_project(surf, p, t0, [0.3d0, 0.3d0], wt, wvw, wx, wd) == LS_OK, "whole project")
        call check(ls_part_project(ps, p, t0, [0.3d0, 0.3d0], pt, pvw, px, pd, left_at) == LS_OK, &
                   "part project")
        call check(left_at == -1 .and. pt == wt .and. all(pvw == wvw) .and. pd == wd, &
                   "part project: the whole's")
        call check(ls_part_closest_point(ps, p, pt, pvw, px, pd, 3_c_size_t, near, n_near) == LS_OK, &
                   "part closest point")
        call check(ls_snap(surf, p, wt, wvw, wx, wd) == LS_OK, "whole snap")
        call check(pd >= wd - 1d-12 .and. n_near <= 3, "part closest point: certified")
        call check(pd <= wd + 1d-12 .or. n_near > 0, "part closest point: a nearer part named")
        call check(ls_part_surface_bytes(ps, n_bytes) == LS_OK .and. n_bytes > 0, "part surface bytes")
        call check(ls_part_project(ps, p, -1_c_int32_t, [0.3d0, 0.3d0], pt, pvw, px, pd, left_at) &
                   == LS_ERR_INVALID_ARGUMENT, "part project: a negative triangle")
        call ls_part_surface_free(ps)
        call ls_part_free(part)
        call ls_free_array(global_c)
        call ls_free_array(owned_c)
        call ls_free_array(bounds_c)
    end block
    ! Mesher, uniform 3 on the octahedron: 8 * 9 triangles, closed.
    block
        type(ls_mesh_options) :: mo
        type(c_ptr) :: mesh, ftris_c, ftri_c, fvw_c
        integer(c_size_t) :: per
        integer(c_int32_t), pointer :: ftri(:), ftris(:), fcurves(:)
        real(c_double), pointer :: fvw(:)
        type(c_ptr) :: hpairs, hcurves
        integer(c_size_t) :: nhard
        call check(ls_mesh_options_default(mo) == LS_OK, "mesh options")
        call check(mo%struct_size == c_sizeof(mo) .and. mo%tolerance == 1d-3, "mesh options: defaults")
        mo%uniform = 3
        mo%tolerance = 0d0
        mo%adapt_curvature = 0
        call check(ls_mesh(surf, mo, mesh) == LS_OK, "mesh")
        call check(ls_trimesh_counts(mesh, nv, nt, per) == LS_OK, "mesh counts")
        call check(nt == 72 .and. nv == 38 .and. per == 3, "mesh: 72 triangles, 38 vertices")
        ! The tagged edge (1, 3) is the model's one curve: 3 mesh edges lie on it.
        call check(ls_trimesh_elements(mesh, ftris_c) == LS_OK, "mesh elements")
        call check(ls_trimesh_node_params(mesh, ftri_c, fvw_c) == LS_OK, "mesh node params")
        call c_f_pointer(ftri_c, ftri, [nv])
        call c_f_pointer(fvw_c, fvw, [2 * nv])
        call c_f_pointer(ftris_c, ftris, [3 * nt])
        call check(ls_mesh_hard_edges(surf, nv, ftri, fvw, nt, ftris, nhard, hpairs, hcurves, &
            c_null_ptr) == LS_OK, "mesh hard edges")
        call c_f_pointer(hcurves, fcurves, [nhard])
        call check(nhard == 3, "three mesh edges on the hard edge")
        call check(all(fcurves == 0), "all on curve 0")
        call ls_free_array(hpairs)
        call ls_free_array(hcurves)
        call ls_trimesh_free(mesh)
        ! A budget the caller sets: uniform 10 would make 800 triangles.
        mo%uniform = 10
        mo%max_triangles = 100
        call check(ls_mesh(surf, mo, mesh) == LS_ERR_OVER_BUDGET, "mesh: over the budget")
        call check(index(loopsurf_last_error(), "over the limit of 100") > 0, "mesh: names the budget")
    end block
    ! Remeshing in parts as a job of one rank, its bytes handed back to it
    ! as a transport would: the mesh of loopsurf_remesh in as many parts.
    block
        type(ls_remesh_options) :: jo
        type(c_ptr) :: job, sent, stage, jmesh, piece, gids
        integer(c_int) :: done
        integer(c_size_t) :: nb, counts(1)
        integer(c_int8_t), pointer :: b(:)
        integer(c_int8_t), allocatable :: gathered(:)
        integer(c_int64_t), pointer :: ids(:)
        real(c_double), allocatable :: jx(:, :), jvw(:, :), rx(:, :), rvw(:, :)
        integer, allocatable :: jt(:, :), jtri(:), rt(:, :), rtri(:), rface(:)
        real(c_double) :: dev
        integer :: stages
        call check(ls_remesh_options_default(jo) == LS_OK, "job options")
        jo%size = 0.3d0
        jo%tolerance = 0d0
        jo%adapt_curvature = 0
        jo%parts = 2
        call check(ls_remesh_job_new(surf, jo, 0_c_int, 1_c_int, job) == LS_OK, "job")
        stages = 0
        do
            call check(ls_remesh_job_done(job, done, stage) == LS_OK, "job done")
            if (done /= 0 .or. stages > 10) exit
            call check(ls_remesh_job_run(job, sent, nb) == LS_OK, "job run")
            call c_f_pointer(sent, b, [nb])
            gathered = b
            counts(1) = nb
            call check(ls_remesh_job_advance(job, gathered, counts) == LS_OK, "job advance")
            stages = stages + 1
        end do
        call check(done == 1, "job done")
        call check(stages >= 3, "job: its stages")
        call check(ls_remesh_job_mesh(job, jmesh) == LS_OK, "job mesh")
        call check(loopsurf_trimesh_arrays(jmesh, jx, jt, jtri, jvw) == LS_OK, "job mesh arrays")
        call ls_trimesh_free(jmesh)
        call check(loopsurf_remesh(surf, jo, rx, rt, rtri, rvw, rface, dev) == LS_OK, "remesh in 2 parts")
        call check(size(jx, 2) == size(rx, 2), "job: the nodes of the remesh")
        if (size(jx, 2) == size(rx, 2)) call check(all(jx == rx), "job: bit for bit")
        call check(ls_remesh_job_piece(job, piece, gids) == LS_OK, "job piece")
        call check(ls_trimesh_counts(piece, nv, nt, nh) == LS_OK, "piece counts")
        call c_f_pointer(gids, ids, [nv])
        call check(int(nv) == size(rx, 2), "one rank's piece is the whole mesh")
        call check(minval(ids) == 0, "piece ids 0-based")
        call check(maxval(ids) == nv - 1, "piece ids: every node")
        call ls_free_array(gids)
        call ls_trimesh_free(piece)
        call ls_remesh_job_free(job)
    end block
    ! The quality remesher, 1-based: vertices on the surface at their
    ! parameters, faces of the model (the one curve bounds no face: 1 face).
    block
        real(c_double), allocatable :: rx(:, :), rvw(:, :)
        integer, allocatable :: rt(:, :), rtri(:), rface(:)
        real(c_double) :: dev
        type(ls_remesh_options) :: ro
        call check(ls_remesh_options_default(ro) == LS_OK, "remesh options")
        ro%size = 0.3d0
        ro%tolerance = 0d0
        ro%adapt_curvature = 0
        call check(loopsurf_remesh(surf, ro, rx, rt, rtri, rvw, rface, dev) == LS_OK, "remesh")
        call check(size(rx, 2) > 6 .and. size(rt, 2) > 8 .and. size(rtri) == size(rx, 2), "remesh counts")
        call check(minval(rt) == 1 .and. maxval(rt) == size(rx, 2), "remesh: 1-based vertices")
        call check(minval(rtri) >= 1 .and. maxval(rtri) <= 8 .and. all(rface == 1), "remesh: triangles, faces")
        call check(dev == -1d0, "remesh: no tolerance, no deviation")
        i = size(rx, 2) / 2
        call check(loopsurf_evaluate(surf, rtri(i), rvw(1, i), rvw(2, i), r) == LS_OK, "eval remeshed vertex")
        call check(maxval(abs(r(1:3) - rx(:, i))) <= 1d-13, "remeshed vertex on the surface")
        ro%tolerance = 1d-3
        ro%adapt_curvature = 1
        ro%gradation = 1.5d0
        call check(loopsurf_remesh(surf, ro, rx, rt, rtri, rvw, rface, dev) == LS_OK, "adaptive remesh")
        call check(dev >= 0d0, "adaptive remesh: deviation measured")
        ro%tolerance = 0d0
        ro%adapt_curvature = 0
        ro%gradation = 0.5d0
        call check(loopsurf_remesh(surf, ro, rx, rt, rtri, rvw, rface, dev) &
            == LS_ERR_INVALID_ARGUMENT, "remesh: gradation 0.5")
        call check(index(loopsurf_last_error(), "gradation") > 0, "remesh: names gradation")
        ro%gradation = 1.3d0
        ro%size = 1d-4
        call check(loopsurf_remesh(surf, ro, rx, rt, rtri, rvw, rface, dev) == LS_ERR_OVER_BUDGET, &
            "remesh: over the budget")
        ! The parts worth remeshing in: whole at this net's size.
        block
            integer(c_size_t) :: parts
            parts = 99
            ro%size = 0.3d0
            call check(ls_remesh_suggested_parts(surf, ro, parts) == LS_OK, "suggested parts")
            call check(parts == 1_c_size_t, "suggested parts: whole")
        end block
        ! A remeshed mesh handle to a file, and a file name it refuses.
        block
            type(c_ptr) :: handle
            type(ls_trimesh_write_options) :: wo
            logical :: exists
            integer :: unit
            ro%size = 0.3d0
            call check(ls_remesh(surf, ro, handle) == LS_OK, "remesh handle")
            call check(ls_trimesh_write_options_default(wo) == LS_OK, "write options")
            call check(wo%struct_size == c_sizeof(wo) .and. wo%first_element_tag == 1_c_int64_t, &
                "write options: defaults")
            wo%binary = 1
            call check(loopsurf_trimesh_write(handle, surf, "fortran_test.msh", wo) == LS_OK, "write .msh")
            inquire(file="fortran_test.msh", exist=exists)
            call check(exists, "write .msh: the file")
            if (exists) then
                open(newunit=unit, file="fortran_test.msh")
                close(unit, status="delete")
            end if
            call check(loopsurf_trimesh_write(handle, surf, "fortran_test.obj", wo) == LS_ERR_UNSUPPORTED, &
                "write .obj: refused")
            call ls_trimesh_free(handle)
        end block
        ! The remeshed mesh curved to P2: its vertices first and unmoved,
        ! every node on the surface at its 1-based parameters.
        block
            real(c_double), allocatable :: cn(:, :), cvw(:, :)
            integer, allocatable :: ctri(:), cel(:, :), cface(:)
            real(c_double) :: moved, jac
            type(ls_mesh_curve_options) :: co
            ro%size = 0.4d0
            call check(loopsurf_remesh(surf, ro, rx, rt, rtri, rvw, rface, dev) == LS_OK, "remesh for curve")
            call check(ls_mesh_curve_options_default(co) == LS_OK, "curve options")
            call check(co%order == 2, "curve options: order 2")
            call check(loopsurf_mesh_curve(surf, rx, rt, co, cn, ctri, cvw, cel, cface, moved, jac) == LS_OK, &
                "curve")
            call check(size(cel, 1) == 6 .and. size(cel, 2) == size(rt, 2), "curve: P2 elements")
            call check(all(cel(1:3, :) == rt), "curve: vertices first")
            call check(maxval(abs(cn(:, 1:size(rx, 2)) - rx)) <= 1d-12, "curve: vertices kept")
            call check(moved < 1d-12 .and. jac > 0d0 .and. all(cface == 1), "curve: moves, Jacobian, faces")
            do i = 1, size(cn, 2)
                call check(loopsurf_evaluate(surf, ctri(i), cvw(1, i), cvw(2, i), r) == LS_OK, "eval node")
                call check(maxval(abs(r(1:3) - cn(:, i))) <= 1d-12, "node on the surface")
            end do
            co%order = 7
            call check(loopsurf_mesh_curve(surf, rx, rt, co, cn, ctri, cvw, cel, cface, moved, jac) &
                == LS_ERR_INVALID_ARGUMENT, "curve: order 7")
            call check(index(loopsurf_last_error(), "order") > 0, "curve: names the order")
        end block
    end block
    ! Adaptive subdivision at angle 0 is uniform: 8 * 4**2 triangles, closed.
    block
        type(ls_adapt_options) :: ao
        type(c_ptr) :: mesh
        integer(c_size_t) :: per
        call check(ls_adapt_options_default(ao) == LS_OK, "adapt options")
        ao%angle = 0d0
        ao%levels = 2
        call check(ls_adapt(surf, ao, mesh) == LS_OK, "adapt")
        call check(ls_trimesh_counts(mesh, nv, nt, per) == LS_OK, "adapt counts")
        call check(nt == 128 .and. nv == 66, "adapt: 128 triangles, 66 vertices")
        call ls_trimesh_free(mesh)
        ao%angle = 5d0
        ao%levels = 11
        call check(ls_adapt(surf, ao, mesh) == LS_ERR_INVALID_ARGUMENT, "adapt levels 11")
    end block
    call check(ls_net_hard_edges(net, n, rxyz) == LS_OK, "hard edges")
    call check(n == 1, "hard edges: 1")
    call ls_free_array(rxyz)
    ! The octahedron's surface does not fold, nor does its net.
    call check(ls_surface_folded_patches(surf, n, rxyz) == LS_OK, "folded patches")
    call check(n == 0, "folded patches: none")
    call ls_free_array(rxyz)
    call check(ls_net_folds(net, 150d0, n, rxyz, rtris, mvw) == LS_OK, "net folds")
    call check(n == 0, "net folds: none")
    call ls_free_array(rxyz)
    call ls_free_array(rtris)
    call ls_free_array(mvw)

    ! A surface point snaps to itself; the triangle comes back 1-based.
    call check(loopsurf_evaluate(surf, 4, 0.2d0, 0.3d0, r) == LS_OK, "eval for snap")
    p = r(1:3)
    call check(loopsurf_snap(surf, p, tri, uv, q, dist) == LS_OK, "snap")
    call check(dist < 1d-13 .and. tri >= 1 .and. tri <= 8, "snapped onto itself")

    ! The certified snap: the same answer, its lower bound within the tolerance.
    p = [10d0, 20d0, 30d0]
    call check(loopsurf_snap(surf, p, tri, uv, q, dist) == LS_OK, "far snap")
    call check(loopsurf_snap_certified(surf, p, 1d-12, tri2, uv2, q2, dist2, bound) == LS_OK, "certified snap")
    call check(tri2 == tri .and. dist2 == dist .and. all(q2 == q), "certified = plain snap")
    call check(bound <= dist2 .and. dist2 - bound <= 4d-12, "certificate within the tolerance")
    call check(loopsurf_snap_certified(surf, p, 1d-6, tri2, uv2, q2, dist2, bound) == LS_OK, "loose snap")
    call check(dist2 - bound <= 4d-6, "loose certificate")
    call check(loopsurf_snap_certified(surf, p, 0d0, tri2, uv2, q2, dist2, bound) == LS_ERR_INVALID_ARGUMENT, &
        "zero tolerance refused")

    ! Local projection from the global answer of a nearby point: the same point.
    call check(loopsurf_project(surf, p * 1.0001d0, tri, uv, tri2, uv2, q2, dist2) == LS_OK, "project")
    call check(loopsurf_snap(surf, p * 1.0001d0, tri, uv, q, dist) == LS_OK, "snap for project")
    call check(abs(dist2 - dist) < 1d-12 .and. tri2 >= 1 .and. tri2 <= 8, "projected = snapped")
    call check(loopsurf_evaluate(surf, tri2, uv2(1), uv2(2), r) == LS_OK, "eval at projection")
    call check(all(r(1:3) == q2), "projected point on the surface")
    call check(loopsurf_project(surf, p, 9, uv, tri2, uv2, q2, dist2) == LS_ERR_INDEX_OUT_OF_RANGE, &
        "project: bad triangle")
    call check(loopsurf_project(surf, p, 0, uv, tri2, uv2, q2, dist2) == LS_ERR_INDEX_OUT_OF_RANGE, &
        "project: triangle 0 (1-based)")
    call check(loopsurf_project(surf, p, tri, [0.9d0, 0.9d0], tri2, uv2, q2, dist2) == LS_ERR_PARAMETER_OUT_OF_RANGE, &
        "project: guess outside its triangle")
    call check(loopsurf_project(surf, [ieee_nan(), 0d0, 0d0], tri, uv, tri2, uv2, q2, dist2) == LS_ERR_NOT_FINITE, &
        "project: NaN point")

    ! Displacement interpolation passes through the original points.
    call check(ls_surface_build_interpolating(net, LS_INTERPOLATE_DISPLACEMENT, surf3) == LS_OK, "interpolating")
    call check(loopsurf_evaluate(surf3, 1, 0d0, 0d0, r) == LS_OK, "eval at corner")
    call check(all(r(1:3) == xyz(:, 1)), "through the original point")
    call check(ls_surface_build_interpolating(net, 7_c_int, surf3) == LS_ERR_INVALID_ARGUMENT, "bad mode")
    call ls_surface_free(surf3)

    ! A dirty file: the octahedron with two triangles turned, refused
    ! plainly and repaired with LS_LOAD_ORIENT, which says what it did.
    call get_environment_variable("TMPDIR", tmpdir)
    if (len_trim(tmpdir) == 0) tmpdir = "/tmp"
    write(path, '(a, a, i0, a)') trim(tmpdir), "/loopsurf_fortran_", getpid(), ".off"
    open(newunit=unit, file=trim(path), status="replace", action="write")
    write(unit, '(a)') "OFF", "6 8 0", "1 0 0", "-1 0 0", "0 1 0", "0 -1 0", "0 0 1", "0 0 -1", &
        "3 0 4 2", "3 2 1 4", "3 1 3 4", "3 3 0 4", "3 2 0 5", "3 2 1 5", "3 3 1 5", "3 0 3 5"
    close(unit)
    call check(loopsurf_load(trim(path), net3) == LS_ERR_NON_MANIFOLD, "shuffled refused")
    call check(index(loopsurf_last_error(), "LS_LOAD_ORIENT") > 0, "names the flag")
    call check(loopsurf_load_with(trim(path), LS_LOAD_ORIENT, 0d0, net3) == LS_OK, "load_with orient")
    call check(loopsurf_repair_report(net3) == "orient: flipped 2 of the 8 triangles of the piece of " // &
        "triangle 0 (closed: now facing outward)", "repair report")
    call ls_net_free(net3)
    open(newunit=unit, file=trim(path), status="old")
    close(unit, status="delete")

    call test_model()
    call test_fit()

    call ls_version(major, minor, patch)
    call check(major == 1 .and. minor >= 0, "version")

    call ls_surface_free(surf)
    call ls_surface_free(surf2)
    call ls_net_free(net)
    call ls_net_free(net2)
    if (failures > 0) then
        print '(i0, a)', failures, " Fortran checks failed"
        error stop 1
    end if
    print '(a)', "Fortran: all checks passed"

contains
    ! ls_net_fit on the octahedron with its edges hard: a finer closed net,
    ! its defaults as documented, a bad resolution refused.
    subroutine test_fit()
        type(c_ptr) :: oct, fitted
        type(ls_fit_options) :: fo
        integer(c_size_t) :: tagged, fv, ft, fh
        call check(loopsurf_from_arrays(xyz, tris, oct) == LS_OK, "fit: from_arrays")
        call check(ls_net_tag_by_angle(oct, 30d0, tagged) == LS_OK, "fit: tag")
        call check(tagged == 12, "fit: 12 tagged")
        call check(ls_fit_options_default(fo) == LS_OK, "fit options")
        call check(fo%resolution == 0.01d0 .and. fo%tolerance == 1d-4, "fit options: defaults")
        call check(ls_net_fit(oct, fo, fitted) == LS_OK, "fit")
        call check(ls_net_counts(fitted, fv, ft, fh) == LS_OK, "fitted counts")
        call check(fv > 100 .and. ft == 2 * fv - 4 .and. fh >= 12, "fitted counts: values")
        call ls_net_free(fitted)
        fo%resolution = 2d0
        call check(ls_net_fit(oct, fo, fitted) == LS_ERR_INVALID_ARGUMENT, "fit: resolution refused")
        call ls_net_free(oct)
    end subroutine

    ! The model of a unit cube from 1-based arrays, every cube edge hard by
    ! angle (90 > 30 degrees): 6 faces of 2 triangles, each with one loop of
    ! 4 curves, 12 straight curves of one control edge, 8 fixed corners.
    subroutine test_model()
        real(c_double) :: cube(3, 8), e(9), e2(9), corner_xyz(3, 8), vw(2, 2), q(3), q2(3)
        real(c_double) :: length, t, t2, dist, dist2, bound, r(18)
        integer :: cube_tris(3, 12), nfaces, ncurves, ncorners, v, c, f, i, j, n, nt, nl, face
        integer :: corners(2), faces(2), sides, sfaces(2), stris(2)
        integer, allocatable :: chain(:), tris(:), curves(:), next_chain(:)
        logical, allocatable :: forward(:)
        integer(c_size_t) :: ntagged, nloop, nseamed, nleft
        integer(c_int32_t) :: loop_curves(4), loop_forward(4)
        type(c_ptr) :: cnet, csurf

        cube = reshape([0d0, 0d0, 0d0, 1d0, 0d0, 0d0, 1d0, 1d0, 0d0, 0d0, 1d0, 0d0, &
                        0d0, 0d0, 1d0, 1d0, 0d0, 1d0, 1d0, 1d0, 1d0, 0d0, 1d0, 1d0], [3, 8])
        cube_tris = reshape([1, 3, 2, 1, 4, 3, 5, 6, 7, 5, 7, 8, 1, 2, 6, 1, 6, 5, &
                             2, 3, 7, 2, 7, 6, 3, 4, 8, 3, 8, 7, 4, 1, 5, 4, 5, 8], [3, 12])
        call check(loopsurf_from_arrays(cube, cube_tris, cnet) == LS_OK, "cube")
        call check(ls_net_tag_by_angle(cnet, 30d0, ntagged) == LS_OK, "tag cube")
        call check(ntagged == 12, "cube edges hard")
        ! A cube's corners are convex: nothing to seam.
        call check(ls_net_seam_concave_corners(cnet, nseamed, nleft) == LS_OK, "seam cube")
        call check(nseamed == 0 .and. nleft == 0, "cube has no concave corner")
        call check(ls_surface_build(cnet, csurf) == LS_OK, "cube surface")
        call check(loopsurf_model_counts(csurf, nfaces, ncurves, ncorners) == LS_OK, "model counts")
        call check(nfaces == 6 .and. ncurves == 12 .and. ncorners == 8, "6 faces, 12 curves, 8 corners")

        ! Corners are fixed: vertex k, at its own point.
        do i = 1, 8
            call check(loopsurf_model_corner(csurf, i, v, corner_xyz(:, i)) == LS_OK, "corner")
            call check(v == i .and. maxval(abs(corner_xyz(:, i) - cube(:, i))) <= 1d-15, "corner fixed")
        end do

        ! Each curve runs between its corners, straight; its ends are the
        ! corner points, and its points lie on both faces.
        do c = 1, 12
            call check(loopsurf_model_curve(csurf, c, n, corners, faces) == LS_OK, "curve")
            call check(n == 1 .and. all(corners >= 1) .and. all(faces >= 1) .and. faces(1) /= faces(2), &
                "curve of one edge between two faces")
            call check(loopsurf_model_curve_chain(csurf, c, chain) == LS_OK, "chain")
            call check(size(chain) == 2 .and. all(chain == corners), "chain ends at its corners")
            call check(loopsurf_curve_evaluate(csurf, c, 0d0, e) == LS_OK, "eval t = 0")
            call check(maxval(abs(e(1:3) - corner_xyz(:, corners(1)))) <= 1d-15, "t = 0 at its first corner")
            call check(loopsurf_curve_evaluate(csurf, c, 1d0, e) == LS_OK, "eval t = 1")
            call check(maxval(abs(e(1:3) - corner_xyz(:, corners(2)))) <= 1d-15, "t = 1 at its last corner")
            call check(loopsurf_curve_length(csurf, c, 0d0, 1d0, length) == LS_OK, "length")
            call check(abs(length - 1d0) <= 1d-14, "unit length")
            call check(loopsurf_curve_param_at_length(csurf, c, 0.25d0, t) == LS_OK, "param at length")
            call check(abs(t - 0.25d0) <= 1d-12, "straight: t = s")
            call check(loopsurf_curve_evaluate(csurf, c, t, e) == LS_OK, "eval at t")
            call check(maxval(abs(e(1:3) - (0.75d0 * cube(:, chain(1)) + 0.25d0 * cube(:, chain(2))))) <= 1d-15, &
                "on the straight edge")
            call check(loopsurf_curve_surface_points(csurf, c, t, sides, sfaces, stris, vw) == LS_OK, "surface points")
            call check(sides == 2 .and. all(sfaces == faces), "a point on both faces")
            do j = 1, 2
                call check(loopsurf_evaluate(csurf, stris(j), vw(1, j), vw(2, j), r) == LS_OK, "eval side")
                call check(maxval(abs(r(1:3) - e(1:3))) <= 1d-14, "surface = curve")
                call check(loopsurf_model_triangle_face(csurf, stris(j), face) == LS_OK, "triangle face")
                call check(face == faces(j), "triangle's face")
            end do
        end do

        ! Faces: two triangles and one loop of four curves that closes.
        do f = 1, 6
            call check(loopsurf_model_face(csurf, f, nt, nl) == LS_OK, "face")
            call check(nt == 2 .and. nl == 1, "face of 2 triangles and 1 loop")
            call check(loopsurf_model_face_triangles(csurf, f, tris) == LS_OK, "face triangles")
            call check(all(tris == [2 * f - 1, 2 * f]), "face triangles in file order")
            call check(loopsurf_model_face_loop(csurf, f, 1, curves, forward) == LS_OK, "face loop")
            call check(size(curves) == 4, "loop of 4 curves")
            do i = 1, 4
                j = mod(i, 4) + 1
                call check(loopsurf_model_curve_chain(csurf, curves(i), chain) == LS_OK, "loop chain")
                call check(loopsurf_model_curve_chain(csurf, curves(j), next_chain) == LS_OK, "next chain")
                call check(merge(chain(2), chain(1), forward(i)) == merge(next_chain(1), next_chain(2), forward(j)), &
                    "loop closes")
            end do
        end do
        ! The bind(C) layer: two calls, absent arrays first.
        call check(ls_model_face_loop(csurf, 0_c_int32_t, 0_c_int32_t, nloop) == LS_OK, "loop size")
        call check(nloop == 4, "loop of 4")
        call check(ls_model_face_loop(csurf, 0_c_int32_t, 0_c_int32_t, nloop, loop_curves, loop_forward) == LS_OK, &
            "loop arrays")
        call check(all(loop_curves + 1 == curves_of_face(csurf, 1)) .and. all(loop_forward == 0 .or. loop_forward == 1), &
            "0-based = 1-based - 1")

        ! Snap and project onto curve 1 from 0.1 off its point at t = 0.3.
        call check(loopsurf_curve_evaluate(csurf, 1, 0.3d0, e) == LS_OK, "eval for snap")
        q = e(1:3) + 0.1d0 * cross_unit(e(4:6))
        call check(loopsurf_curve_snap(csurf, 1, q, 0d0, t, q2, dist, bound) == LS_OK, "curve snap")
        call check(abs(t - 0.3d0) <= 1d-9 .and. abs(dist - 0.1d0) <= 1d-14, "snapped back")
        call check(bound <= dist .and. dist - bound <= 4d-12, "certificate")
        call check(loopsurf_curve_evaluate(csurf, 1, t, e2) == LS_OK, "eval at snap")
        call check(all(e2(1:3) == q2), "snap on the curve")
        call check(loopsurf_curve_project(csurf, 1, q, 0.6d0, t2, q2, dist2) == LS_OK, "curve project")
        call check(abs(t2 - t) <= 1d-9 .and. abs(dist2 - dist) <= 1d-14, "projected = snapped")

        ! Errors: ids 0 and 13 (1-based), t outside [0, 1], NaN, bad tolerance.
        call check(loopsurf_curve_evaluate(csurf, 0, 0d0, e) == LS_ERR_INDEX_OUT_OF_RANGE, "curve 0 (1-based)")
        call check(index(loopsurf_last_error(), "curve -1: out of range (the model has 12 curves)") > 0, &
            "message names the index and the count")
        call check(loopsurf_curve_evaluate(csurf, 13, 0d0, e) == LS_ERR_INDEX_OUT_OF_RANGE, "curve 13 of 12")
        call check(loopsurf_model_face(csurf, 7, nt, nl) == LS_ERR_INDEX_OUT_OF_RANGE, "face 7 of 6")
        call check(loopsurf_model_corner(csurf, 9, v, q) == LS_ERR_INDEX_OUT_OF_RANGE, "corner 9 of 8")
        call check(loopsurf_model_face_loop(csurf, 1, 2, curves, forward) == LS_ERR_INDEX_OUT_OF_RANGE, "loop 2 of 1")
        call check(loopsurf_curve_evaluate(csurf, 1, 1.5d0, e) == LS_ERR_PARAMETER_OUT_OF_RANGE, "t = 1.5")
        call check(loopsurf_curve_evaluate(csurf, 1, -0.5d0, e) == LS_ERR_PARAMETER_OUT_OF_RANGE, "t = -0.5")
        call check(loopsurf_curve_evaluate(csurf, 1, ieee_nan(), e) == LS_ERR_NOT_FINITE, "t NaN")
        call check(loopsurf_curve_param_at_length(csurf, 1, 2d0, t) == LS_ERR_PARAMETER_OUT_OF_RANGE, &
            "arc length beyond the curve")
        call check(loopsurf_curve_snap(csurf, 1, q, -1d0, t, q2, dist, bound) == LS_ERR_INVALID_ARGUMENT, &
            "negative tolerance")

        call ls_surface_free(csurf)
        call ls_net_free(cnet)
    end subroutine

    ! The 1-based curves of loop 1 of face f.
    function curves_of_face(surf, f) result(ids)
        type(c_ptr), intent(in) :: surf
        integer, intent(in) :: f
        integer, allocatable :: ids(:)
        logical, allocatable :: fw(:)
        if (loopsurf_model_face_loop(surf, f, 1, ids, fw) /= LS_OK) allocate(ids(0))
    end function

    ! A unit vector across direction d.
    function cross_unit(d) result(u)
        real(c_double), intent(in) :: d(3)
        real(c_double) :: u(3), a(3)
        a = 0d0
        a(minloc(abs(d), 1)) = 1d0
        u = [d(2) * a(3) - d(3) * a(2), d(3) * a(1) - d(1) * a(3), d(1) * a(2) - d(2) * a(1)]
        u = u / norm2(u)
    end function

    subroutine check(ok, what)
        logical, intent(in) :: ok
        character(len=*), intent(in) :: what
        if (.not. ok) then
            failures = failures + 1
            print '(a, a, a, a)', "FAILED: ", what, " -- ", loopsurf_last_error()
        end if
    end subroutine

    real(c_double) function ieee_nan()
        use, intrinsic :: ieee_arithmetic
        ieee_nan = ieee_value(0d0, ieee_quiet_nan)
    end function
end program
