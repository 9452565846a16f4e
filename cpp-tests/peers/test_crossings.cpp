// Whether loopsurf's meshes bound a volume, judged by an independent
// checker: CGAL's self_intersections counts the pairs of triangles that
// meet anywhere but in the vertices and edges they share (exact
// predicates). A volume mesher (TetGen, gmsh) refuses a surface with one.
//
// Cases: the peer cases adapted at the default tolerance and at a uniform
// size. None may cross itself where its limit surface does not: a pair is
// excused only over control triangles where a chart mesh of the surface,
// 8 to the control edge, crosses itself too (CGAL's count of that mesh),
// which is where anchor's surface crosses beside the inner corners of its
// L-shaped faces (131 pairs). How many pairs a mesh has there follows how
// finely it meshes them, not whether it bounds a volume anywhere else; so
// the count is printed, not pinned (anchor adapted: 58 before the
// remesher's last pass removed crossings, 12 from a start of the control
// triangles' copies, 25 since long slivers start cut by their lengths).
// With those corners seamed (ls_net_seam_concave_corners) its surface
// does not cross, and no pair is excused.
#include "mesh.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <set>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel Epick;
typedef CGAL::Surface_mesh<Epick::Point_3> SurfaceMesh;

struct Case {
    const char* file;
    double angle;     // hard angle, degrees (< 0: none)
    double relative;  // uniform size as a share of the diagonal; 0: adapted
    bool seams;       // concave corners seamed: no pair excused
};

// The crossing pairs CGAL finds in `mesh`, as the control triangles under
// each pair's nodes.
static std::vector<std::set<int32_t>> cgal_crossings(ls_trimesh* mesh) {
    size_t nv, nt, per;
    const double* xyz;
    const int32_t* tris;
    const int32_t* node_tri;
    const double* node_vw;
    if (ls_trimesh_counts(mesh, &nv, &nt, &per) != LS_OK || ls_trimesh_xyz(mesh, &xyz) != LS_OK ||
        ls_trimesh_elements(mesh, &tris) != LS_OK || ls_trimesh_node_params(mesh, &node_tri, &node_vw) != LS_OK ||
        per != 3)
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
    std::vector<std::set<int32_t>> under;
    for (auto [f, g] : pairs) {
        std::set<int32_t> tri;
        for (auto face : {f, g})
            for (auto v : m.vertices_around_face(m.halfedge(face))) tri.insert(node_tri[size_t(v)]);
        under.push_back(tri);
    }
    return under;
}

// The control triangles where the limit surface itself crosses: those
// under a crossing pair of its chart mesh 8 to the control edge.
static std::set<int32_t> where_the_surface_crosses(const ls_surface* surface) {
    ls_mesh_options options;
    ls_mesh_options_default(&options);
    options.uniform = 8;
    options.tolerance = 0;
    options.adapt_curvature = 0;
    ls_trimesh* chart = nullptr;
    if (ls_mesh(surface, &options, &chart) != LS_OK) fail("ls_mesh");
    std::set<int32_t> out;
    for (const auto& tri : cgal_crossings(chart)) out.insert(tri.begin(), tri.end());
    ls_trimesh_free(chart);
    return out;
}

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s DATA_DIR\n", argv[0]);
        return 2;
    }
    const std::string dir = argv[1];
    const Case cases[] = {
        {"joint.off", 30, 0},
        {"fandisk.off", 30, 0},
        {"pig.off", -1, 0},
        {"mech-holes-shark.off", 40, 0},
        {"anchor.off", 30, 0},
        {"joint.off", 30, 0.01},
        {"fandisk.off", 30, 0.005},
        {"pig.off", -1, 0.005},
        {"mech-holes-shark.off", 40, 0.01},
        {"anchor.off", 30, 0, true},
        {"anchor.off", 30, 0.01, true},
    };
    for (const Case& c : cases) {
        Net n = load_net(dir + "/" + c.file, c.angle, c.seams);
        ls_remesh_options options;
        ls_remesh_options_default(&options);
        if (c.relative > 0) {
            options.size = c.relative * n.diagonal;
            options.tolerance = 0;
            options.adapt_curvature = 0;
        }
        ls_trimesh* mesh = nullptr;
        if (ls_remesh(n.surface, &options, &mesh) != LS_OK) fail(c.file);
        const auto pairs = cgal_crossings(mesh);
        const char* mode = c.relative > 0 ? (c.seams ? "uniform, seamed" : "uniform") : (c.seams ? "adapted, seamed" : "adapted");
        size_t outside = 0;
        if (!pairs.empty()) {
            const std::set<int32_t> crossing = where_the_surface_crosses(n.surface);
            for (const auto& tri : pairs)
                if (std::none_of(tri.begin(), tri.end(), [&](int32_t t) { return crossing.count(t) > 0; })) outside++;
            std::printf("%s, %s: %zu crossing pairs, %zu where the surface does not cross (its chart mesh crosses over %zu control triangles)\n",
                        c.file, mode, pairs.size(), outside, crossing.size());
        } else {
            std::printf("%s, %s: no crossing pairs\n", c.file, mode);
        }
        CHECK(outside == 0, "%s (%s): %zu crossing pairs where the surface does not cross", c.file, mode, outside);
        CHECK(!c.seams || pairs.empty(), "%s (%s): %zu crossing pairs", c.file, mode, pairs.size());
        ls_trimesh_free(mesh);
        ls_surface_free(n.surface);
    }
    return failures == 0 ? 0 : 1;
}
