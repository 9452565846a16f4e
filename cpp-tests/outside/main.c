/* A C user linked through pkg-config: the version, then the quality
 * remesher on a tetrahedron with its options struct and result handle. */
#include <loopsurf.h>
#include <stdio.h>

int main(void) {
    int major, minor, patch;
    ls_version(&major, &minor, &patch);
    printf("loopsurf %d.%d.%d: %s\n", major, minor, patch, ls_status_string(LS_ERR_OVER_BUDGET));
    if (major != 1) return 1;

    const double xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const int32_t tris[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    ls_net* net = NULL;
    ls_surface* surface = NULL;
    ls_trimesh* mesh = NULL;
    ls_remesh_options options;
    size_t nnodes = 0, nelements = 0, per = 0;
    const double* nodes = NULL;
    if (ls_net_from_arrays(4, xyz, 4, tris, &net) != LS_OK || ls_surface_build(net, &surface) != LS_OK ||
        ls_remesh_options_default(&options) != LS_OK) {
        fprintf(stderr, "failed: %s\n", ls_last_error());
        return 1;
    }
    options.size = 0.1;
    options.max_triangles = 100000;
    if (ls_remesh(surface, &options, &mesh) != LS_OK || ls_trimesh_counts(mesh, &nnodes, &nelements, &per) != LS_OK ||
        ls_trimesh_xyz(mesh, &nodes) != LS_OK) {
        fprintf(stderr, "failed: %s\n", ls_last_error());
        return 1;
    }
    printf("remeshed: %zu nodes, %zu triangles, first node %g %g %g\n", nnodes, nelements, nodes[0], nodes[1],
           nodes[2]);
    int ok = per == 3 && nelements > 4 && nnodes - 3 * nelements / 2 + nelements == 2;
    ls_trimesh_free(mesh);
    ls_surface_free(surface);
    ls_net_free(net);
    return ok ? 0 : 1;
}
