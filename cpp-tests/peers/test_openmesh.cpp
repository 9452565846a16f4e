// loopsurf against OpenMesh's Loop subdivider (double-precision points):
// k uniform levels give the same vertices and triangles to 1e-12 of the
// model size, and ls_evaluate at every dyadic point of level k equals the
// limit mask applied to OpenMesh's refined mesh. Closed and open meshes.
// Usage: test_openmesh DATA_DIR
#include "mesh.hpp"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

struct Traits : OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
    typedef OpenMesh::Vec3d Normal;
};
typedef OpenMesh::TriMesh_ArrayKernelT<Traits> Mesh;


static Mesh openmesh_of(const Net& n) {
    Mesh m;
    std::vector<Mesh::VertexHandle> vh;
    for (size_t i = 0; i < n.nverts(); i++) vh.push_back(m.add_vertex(Mesh::Point(n.xyz[3 * i], n.xyz[3 * i + 1], n.xyz[3 * i + 2])));
    for (size_t t = 0; t < n.ntris(); t++) m.add_face(vh[n.tris[3 * t]], vh[n.tris[3 * t + 1]], vh[n.tris[3 * t + 2]]);
    return m;
}

// Loop's limit mask, written from its formulas: smooth vertices
// (ω x + Σ neighbours) / (ω + n) with ω = 3 / (8 β(n)); boundary vertices the
// cubic B-spline (4 x + a + b) / 6 of their two boundary neighbours.
static Mesh::Point limit_of(const Mesh& m, Mesh::VertexHandle v) {
    Mesh::Point x = m.point(v);
    if (m.is_boundary(v)) {
        Mesh::Point s(0, 0, 0);
        for (auto h : m.voh_range(v)) {
            if (m.is_boundary(m.edge_handle(h))) s += m.point(m.to_vertex_handle(h));
        }
        return (4.0 * x + s) / 6.0;
    }
    Mesh::Point s(0, 0, 0);
    int n = 0;
    for (auto u : m.vv_range(v)) s += m.point(u), n++;
    double c = 3.0 / 8.0 + 0.25 * std::cos(2 * M_PI / n);
    double beta = (5.0 / 8.0 - c * c) / n;
    double omega = 3.0 / (8.0 * beta);
    return (omega * x + s) / (omega + n);
}

static void compare(const std::string& path, int levels) {
    Net n = load_net(path, -1);
    Mesh m = openmesh_of(n);
    OpenMesh::Subdivider::Uniform::LoopT<Mesh, double> loop;
    loop.attach(m);
    loop(levels);
    loop.detach();

    size_t nv, nt;
    double* xyz;
    int32_t* tris;
    if (ls_refine(n.surface, levels, 0, &nv, &xyz, &nt, &tris) != LS_OK) fail("refine");
    std::vector<double> ours(xyz, xyz + 3 * nv), theirs;
    std::vector<int32_t> our_tris(tris, tris + 3 * nt);
    ls_free_array(xyz);
    ls_free_array(tris);
    std::vector<int> their_tris;
    for (auto v : m.vertices()) {
        auto p = m.point(v);
        theirs.insert(theirs.end(), {p[0], p[1], p[2]});
    }
    for (auto f : m.faces())
        for (auto v : m.fv_range(f)) their_tris.push_back(v.idx());
    double tol = 1e-12 * n.diagonal;
    auto match = match_points(ours, theirs, tol);
    CHECK(nv == m.n_vertices() && nt == m.n_faces(), "%s: sizes %zu/%zu vs %zu/%zu", path.c_str(), nv, nt,
          size_t(m.n_vertices()), size_t(m.n_faces()));
    CHECK(same_triangles(match, our_tris, their_tris, m.n_vertices()), "%s: refined meshes differ (tolerance %g)",
          path.c_str(), tol);

    // Every dyadic point of level k: ls_evaluate at the vertex's origin
    // equals the limit mask on OpenMesh's refined mesh.
    size_t no;
    int32_t* tri;
    double* vw;
    if (ls_refine_origins(n.surface, levels, &no, &tri, &vw) != LS_OK) fail("origins");
    double worst = 0;
    for (size_t i = 0; i < no; i++) {
        if (tri[i] < 0 || match[i] < 0) continue;
        double r[18];
        if (ls_evaluate(n.surface, tri[i], vw[2 * i], vw[2 * i + 1], r) != LS_OK) fail("evaluate");
        Mesh::Point l = limit_of(m, m.vertex_handle(int(match[i])));
        worst = std::max(worst, std::hypot(r[0] - l[0], std::hypot(r[1] - l[1], r[2] - l[2])));
    }
    ls_free_array(tri);
    ls_free_array(vw);
    CHECK(worst <= tol, "%s: ls_evaluate vs OpenMesh limit: %g of the diagonal", path.c_str(), worst / n.diagonal);
    std::printf("%s: %d levels, %zu vertices, %zu triangles match OpenMesh; dyadic limit points within %.1e of the diagonal\n",
                path.c_str(), levels, nv, nt, worst / n.diagonal);
    ls_surface_free(n.surface);
}

int main(int argc, char** argv) {
    std::string dir = argc > 1 ? argv[1] : ".";
    compare(dir + "/cow.off", 2);       // closed, irregular
    compare(dir + "/elephant.off", 2);  // closed
    compare(dir + "/pig.off", 3);       // seven boundary loops
    compare(dir + "/mesh_with_border.off", 3);
    if (failures) return 1;
    return 0;
}
