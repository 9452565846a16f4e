// Shared by the peer tests and benchmark: a control net loaded through the
// C ABI (so vertex and triangle order are loopsurf's), its hard edges, and
// matching of two point sets by position.
#pragma once
#include <loopsurf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <tuple>
#include <vector>

struct Net {
    std::vector<double> xyz;     // 3 per vertex
    std::vector<int32_t> tris;   // 3 per triangle
    std::vector<int32_t> hard;   // 2 per hard edge (boundary included)
    double diagonal = 0;
    ls_surface* surface = nullptr;
    size_t nverts() const { return xyz.size() / 3; }
    size_t ntris() const { return tris.size() / 3; }
};

// Failed comparisons are counted and reported; the test fails at the end.
inline int failures = 0;
#define CHECK(c, ...)                                \
    do {                                             \
        if (!(c)) {                                  \
            std::fprintf(stderr, "FAILED %s: ", #c); \
            std::fprintf(stderr, __VA_ARGS__);       \
            std::fprintf(stderr, "\n");              \
            failures++;                              \
        }                                            \
    } while (0)

inline void fail(const char* what) {
    std::fprintf(stderr, "%s: %s\n", what, ls_last_error());
    std::exit(1);
}

// Loads a mesh, tags edges steeper than `angle` degrees (none if < 0), builds
// the surface and reads the net back (level-0 refinement is the net itself).
inline Net load_net(const std::string& path, double angle, bool concave_seams = false) {
    Net n;
    ls_net* net = nullptr;
    if (ls_net_load(path.c_str(), &net) != LS_OK) fail(path.c_str());
    if (angle >= 0 && ls_net_tag_by_angle(net, angle, nullptr) != LS_OK) fail("tag");
    if (concave_seams && ls_net_seam_concave_corners(net, nullptr, nullptr) != LS_OK) fail("seams");
    size_t nh = 0;
    int32_t* pairs = nullptr;
    if (ls_net_hard_edges(net, &nh, &pairs) != LS_OK) fail("hard edges");
    n.hard.assign(pairs, pairs + 2 * nh);
    ls_free_array(pairs);
    if (ls_surface_build(net, &n.surface) != LS_OK) fail("build");
    ls_net_free(net);
    size_t nv, nt;
    double* xyz;
    int32_t* tris;
    if (ls_refine(n.surface, 0, 0, &nv, &xyz, &nt, &tris) != LS_OK) fail("refine 0");
    n.xyz.assign(xyz, xyz + 3 * nv);
    n.tris.assign(tris, tris + 3 * nt);
    ls_free_array(xyz);
    ls_free_array(tris);
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (size_t i = 0; i < nv; i++)
        for (int k = 0; k < 3; k++) lo[k] = std::min(lo[k], n.xyz[3 * i + k]), hi[k] = std::max(hi[k], n.xyz[3 * i + k]);
    n.diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
    return n;
}

// For every point of `a`, the index of the point of `b` at the same
// position (within `tol`), or -1. Refined vertices are at least an edge
// length apart, so a grid of cell `tol` finds each match in its 27 cells.
inline std::vector<long> match_points(const std::vector<double>& a, const std::vector<double>& b, double tol) {
    auto key = [tol](const double* p) {
        return std::make_tuple(long(std::floor(p[0] / tol)), long(std::floor(p[1] / tol)), long(std::floor(p[2] / tol)));
    };
    std::map<std::tuple<long, long, long>, std::vector<long>> grid;
    for (size_t j = 0; j < b.size() / 3; j++) grid[key(&b[3 * j])].push_back(long(j));
    std::vector<long> out(a.size() / 3, -1);
    for (size_t i = 0; i < a.size() / 3; i++) {
        auto [x, y, z] = key(&a[3 * i]);
        double best = tol;
        for (long dx = -1; dx <= 1; dx++)
            for (long dy = -1; dy <= 1; dy++)
                for (long dz = -1; dz <= 1; dz++) {
                    auto it = grid.find({x + dx, y + dy, z + dz});
                    if (it == grid.end()) continue;
                    for (long j : it->second) {
                        double d = std::hypot(a[3 * i] - b[3 * j], std::hypot(a[3 * i + 1] - b[3 * j + 1], a[3 * i + 2] - b[3 * j + 2]));
                        if (d <= best) best = d, out[i] = j;
                    }
                }
    }
    return out;
}

// True when the matching is a bijection and maps triangles `ta` (indices
// into a) onto triangles `tb` (into b) as oriented triangles.
inline bool same_triangles(const std::vector<long>& match, const std::vector<int32_t>& ta, const std::vector<int>& tb, size_t nb) {
    std::vector<char> hit(nb, 0);
    for (long j : match) {
        if (j < 0 || hit[size_t(j)]) return false;
        hit[size_t(j)] = 1;
    }
    auto canon = [](std::array<long, 3> t) {
        while (t[0] != std::min({t[0], t[1], t[2]})) std::rotate(t.begin(), t.begin() + 1, t.end());
        return t;
    };
    std::vector<std::array<long, 3>> A, B;
    for (size_t t = 0; t < ta.size() / 3; t++) A.push_back(canon({match[ta[3 * t]], match[ta[3 * t + 1]], match[ta[3 * t + 2]]}));
    for (size_t t = 0; t < tb.size() / 3; t++) B.push_back(canon({tb[3 * t], tb[3 * t + 1], tb[3 * t + 2]}));
    std::sort(A.begin(), A.end());
    std::sort(B.begin(), B.end());
    return A == B;
}
