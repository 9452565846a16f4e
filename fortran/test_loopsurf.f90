! The Fortran module against real properties of the surface: an octahedron
! net built from 1-based arrays, evaluated one by one and in a batch,
! translated, streamed, refined, snapped, interpolated, and fed bad input.
program test_loopsurf
    use loopsurf
    use, intrinsic :: iso_c_binding
    implicit none
    real(c_double) :: xyz(3, 6), moved(3, 6), r(18), r2(18), many(18, 4), vw(2, 4), k(8)
    real(c_double) :: p(3), q(3), uv(2), dist, shift(3), q2(3), uv2(2), dist2, bound
    integer :: tris(3, 8), i, failures, tri, tri2
    integer(c_int32_t) :: tri0(4)
    integer(c_size_t) :: n, nv, nt, nh
    type(c_ptr) :: net, net2, surf, surf2, surf3, bytes, rxyz, rtris, mtri, mvw
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
    call check(ls_net_counts(net, nv, nt, nh) == LS_OK .and. nv == 6 .and. nt == 8 .and. nh == 0, "counts")
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
    call check(ls_surface_save(surf, bytes, n) == LS_OK .and. n > 0, "save")
    call check(ls_surface_load(bytes, n, surf3) == LS_OK, "load")
    call check(ls_surface_load(bytes, n - 1, surf2) == LS_ERR_BAD_STREAM .and. c_associated(surf2), "truncated stream")
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
    call check(ls_refine_origins(surf, 2_c_int, n, rxyz, rtris) == LS_OK .and. n == 66, "refine origins")
    call ls_free_array(rxyz)
    call ls_free_array(rtris)
    ! Mesher, uniform 3 on the octahedron: 8 * 9 triangles, closed.
    call check(ls_mesh(surf, 3_c_int, 0d0, 0d0, 0_c_int, nv, rxyz, nt, rtris, mtri, mvw, &
        c_null_ptr, c_null_ptr) == LS_OK, "mesh")
    call check(nt == 72 .and. nv == 38, "mesh counts")
    call ls_free_array(rxyz)
    call ls_free_array(rtris)
    call ls_free_array(mtri)
    call ls_free_array(mvw)
    ! Adaptive subdivision at angle 0 is uniform: 8 * 4**2 triangles, closed.
    call check(ls_adapt(surf, 0d0, 0d0, 2_c_int, 0_c_int, nv, rxyz, nt, rtris, mtri, mvw) == LS_OK, "adapt")
    call check(nt == 128 .and. nv == 66, "adapt counts")
    call ls_free_array(rxyz)
    call ls_free_array(rtris)
    call ls_free_array(mtri)
    call ls_free_array(mvw)
    call check(ls_adapt(surf, 5d0, 0d0, 11_c_int, 0_c_int, nv, rxyz, nt, rtris, mtri, mvw) &
        == LS_ERR_INVALID_ARGUMENT, "adapt levels 11")
    call check(ls_net_hard_edges(net, n, rxyz) == LS_OK .and. n == 1, "hard edges")
    call ls_free_array(rxyz)

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

    call ls_version(major, minor, patch)
    call check(major == 0 .and. minor >= 1, "version")

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
