// Whether loopsurf's meshes bound a volume, judged by an independent
// checker: CGAL's self_intersections counts the pairs of triangles that
// meet anywhere but in the vertices and edges they share (exact
// predicates). A volume mesher (TetGen, gmsh) refuses a surface with one.
//
// Cases: the peer cases adapted at the default tolerance and at a uniform
// size. Where pairs are left the count is pinned at what the remesher
// achieves, so that it can only fall (before its last pass removed
// crossings: joint 203, mech-holes-shark 549, anchor 58): anchor's surface
// crosses itself at its high-valence fans (131 pairs in a chart mesh 8 to
// the control edge). mech-holes-shark's net folds back at 4 edges; the 4
// pairs at that fin went when the last pass learnt to flip edges.
#include "mesh.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

typedef CGAL::Exact_predicates_inexact_constructions_kernel Epick;
typedef CGAL::Surface_mesh<Epick::Point_3> SurfaceMesh;

struct Case {
    const char* file;
    double angle;     // hard angle, degrees (< 0: none)
    double relative;  // uniform size as a share of the diagonal; 0: adapted
    size_t most;      // the most crossing pairs allowed
};

// The pairs of triangles of loopsurf's mesh that CGAL finds crossing.
static size_t cgal_crossings(ls_trimesh* mesh) {
    size_t nv, nt, per;
    const double* xyz;
    const int32_t* tris;
    if (ls_trimesh_counts(mesh, &nv, &nt, &per) != LS_OK || ls_trimesh_xyz(mesh, &xyz) != LS_OK ||
        ls_trimesh_elements(mesh, &tris) != LS_OK || per != 3)
        fail("ls_trimesh");
    SurfaceMesh m;
    for (size_t i = 0; i < nv; i++) m.add_vertex(Epick::Point_3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]));
    for (size_t t = 0; t < nt; t++) {
        auto f = m.add_face(SurfaceMesh::Vertex_index(uint32_t(tris[3 * t])), SurfaceMesh::Vertex_index(uint32_t(tris[3 * t + 1])),
                            SurfaceMesh::Vertex_index(uint32_t(tris[3 * t + 2])));
        CHECK(f != SurfaceMesh::null_face(), "triangle %zu is not manifold in CGAL's Surface_mesh", t);
    }
    std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> pairs;
    CGAL::Polygon_mesh_processing::self_intersections(m, std::back_inserter(pairs));
    return pairs.size();
}

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s DATA_DIR\n", argv[0]);
        return 2;
    }
    const std::string dir = argv[1];
    const Case cases[] = {
        {"joint.off", 30, 0, 0},
        {"fandisk.off", 30, 0, 0},
        {"pig.off", -1, 0, 0},
        {"mech-holes-shark.off", 40, 0, 0},
        {"anchor.off", 30, 0, 12},
        {"joint.off", 30, 0.01, 0},
        {"fandisk.off", 30, 0.005, 0},
        {"pig.off", -1, 0.005, 0},
        {"mech-holes-shark.off", 40, 0.01, 0},
    };
    for (const Case& c : cases) {
        Net n = load_net(dir + "/" + c.file, c.angle);
        ls_remesh_options options;
        ls_remesh_options_default(&options);
        if (c.relative > 0) {
            options.size = c.relative * n.diagonal;
            options.tolerance = 0;
            options.adapt_curvature = 0;
        }
        ls_trimesh* mesh = nullptr;
        if (ls_remesh(n.surface, &options, &mesh) != LS_OK) fail(c.file);
        size_t found = cgal_crossings(mesh);
        std::printf("%s, %s: %zu crossing pairs (at most %zu)\n", c.file, c.relative > 0 ? "uniform" : "adapted", found, c.most);
        CHECK(found <= c.most, "%s (%s): %zu crossing pairs, at most %zu expected", c.file,
              c.relative > 0 ? "uniform" : "adapted", found, c.most);
        ls_trimesh_free(mesh);
        ls_surface_free(n.surface);
    }
    return failures == 0 ? 0 : 1;
}
