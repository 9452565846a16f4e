! A Fortran user: the module from the installed package.
program user
    use loopsurf
    use, intrinsic :: iso_c_binding
    implicit none
    real(c_double) :: xyz(3, 4) = reshape([0d0, 0d0, 0d0, 1d0, 0d0, 0d0, 0d0, 1d0, 0d0, 0d0, 0d0, 1d0], [3, 4])
    integer :: tris(3, 4) = reshape([1, 3, 2, 1, 2, 4, 2, 3, 4, 1, 4, 3], [3, 4])
    type(c_ptr) :: net, surface
    real(c_double) :: r(18)
    if (loopsurf_from_arrays(xyz, tris, net) /= LS_OK) error stop 1
    if (ls_surface_build(net, surface) /= LS_OK) error stop 2
    if (loopsurf_evaluate(surface, 1, 0.25d0, 0.25d0, r) /= LS_OK) error stop 3
    print '(a, 3f10.6)', "X =", r(1:3)
    call ls_surface_free(surface)
    call ls_net_free(net)
end program
