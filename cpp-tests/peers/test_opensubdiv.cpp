// loopsurf against OpenSubdiv: Far uniform refinement gives the same
// vertices and triangles (hard edges as infinitely sharp creases, corners,
// boundaries), and Bfr's evaluation equals ls_evaluate — position and all
// first and second derivatives — on regular triangles, where Bfr is exact.
// (Bfr approximates irregular triangles, and OpenSubdiv 3.5.0 returns wrong
// second derivatives on many of them: they are not compared.)
// Usage: test_opensubdiv DATA_DIR
#include "osd.hpp"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>


static void compare(const std::string& path, double angle, int levels) {
    Net n = load_net(path, angle);
    std::vector<double> theirs;
    std::vector<int> their_tris;
    osd_refine(n, levels, theirs, their_tris);
    size_t nv, nt;
    double* xyz;
    int32_t* tris;
    if (ls_refine(n.surface, levels, 0, &nv, &xyz, &nt, &tris) != LS_OK) fail("refine");
    std::vector<double> ours(xyz, xyz + 3 * nv);
    std::vector<int32_t> our_tris(tris, tris + 3 * nt);
    ls_free_array(xyz);
    ls_free_array(tris);
    double tol = 1e-12 * n.diagonal;
    auto match = match_points(ours, theirs, tol);
    CHECK(nv == theirs.size() / 3 && nt == their_tris.size() / 3, "%s: sizes differ", path.c_str());
    CHECK(same_triangles(match, our_tris, their_tris, theirs.size() / 3), "%s: refined meshes differ (tolerance %g)",
          path.c_str(), tol);

    // Bfr on the regular triangles.
    typedef OpenSubdiv::Bfr::Surface<double> Surface;
    osd::TopologyRefiner* base = osd_refiner(n);
    OpenSubdiv::Bfr::RefinerSurfaceFactory<> factory(*base);
    Surface surface;
    std::vector<double> patch;
    Surface::PointDescriptor desc(3);
    const double uvs[][2] = {{0.2, 0.3}, {0.0, 0.0}, {1.0, 0.0}, {0.5, 0.5}, {0.1, 0.8}, {1.0 / 3, 1.0 / 3}};
    size_t regular = 0;
    double worst[6] = {0};
    for (size_t t = 0; t < n.ntris(); t++) {
        if (!factory.InitVertexSurface<double>(int(t), &surface) || !surface.IsRegular()) continue;
        regular++;
        patch.resize(3 * size_t(surface.GetNumPatchPoints()));
        surface.PreparePatchPoints(n.xyz.data(), desc, patch.data(), desc);
        for (auto& uv : uvs) {
            double d[6][3], r[18];
            surface.Evaluate(uv, patch.data(), desc, d[0], d[1], d[2], d[3], d[4], d[5]);
            if (ls_evaluate(n.surface, int32_t(t), uv[0], uv[1], r) != LS_OK) fail("evaluate");
            for (int k = 0; k < 6; k++)
                worst[k] = std::max(worst[k], std::hypot(d[k][0] - r[3 * k], std::hypot(d[k][1] - r[3 * k + 1], d[k][2] - r[3 * k + 2])));
        }
    }
    delete base;
    const char* names[] = {"X", "Xv", "Xw", "Xvv", "Xvw", "Xww"};
    for (int k = 0; k < 6; k++)
        CHECK(worst[k] <= tol, "%s: %s differs from Bfr by %g of the diagonal", path.c_str(), names[k], worst[k] / n.diagonal);
    CHECK(regular >= 50, "%s: only %zu regular triangles", path.c_str(), regular);
    std::printf("%s (%zu hard edges): %d levels match Far (%zu vertices); %zu regular triangles match Bfr to %.1e of the diagonal\n",
                path.c_str(), n.hard.size() / 2, levels, nv, regular,
                *std::max_element(worst, worst + 6) / n.diagonal);
    ls_surface_free(n.surface);
}

int main(int argc, char** argv) {
    std::string dir = argc > 1 ? argv[1] : ".";
    compare(dir + "/fandisk.off", 30, 2);  // sharp creases and corners
    compare(dir + "/pig.off", -1, 3);      // boundaries
    compare(dir + "/cow.off", -1, 2);      // smooth, irregular
    if (failures) return 1;
    return 0;
}
