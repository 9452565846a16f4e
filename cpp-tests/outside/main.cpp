// A C++ user: a tetrahedron, one evaluation.
#include <loopsurf.h>
#include <cstdio>

int main() {
    const double xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const int32_t tris[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    ls_net* net = nullptr;
    ls_surface* surface = nullptr;
    double r[18];
    if (ls_net_from_arrays(4, xyz, 4, tris, &net) != LS_OK || ls_surface_build(net, &surface) != LS_OK ||
        ls_evaluate(surface, 0, 0.25, 0.25, r) != LS_OK) {
        std::fprintf(stderr, "failed: %s\n", ls_last_error());
        return 1;
    }
    std::printf("X = %g %g %g\n", r[0], r[1], r[2]);
    ls_surface_free(surface);
    ls_net_free(net);
    return 0;
}
