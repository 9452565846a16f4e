// Peer benchmark (built by CMake, not run by ctest): loopsurf against
// OpenSubdiv Bfr evaluation, against OpenMesh LoopT and OpenSubdiv Far
// uniform refinement, its exact snap against CGAL's AABB-tree closest
// point on the flat control net, and its remesher against CGAL's isotropic
// remeshing of the control net, on the same meshes and points, in one run.
// Medians of several repetitions; single thread unless noted (run with
// RAYON_NUM_THREADS=1 for a single-thread loopsurf refinement; the
// remesher's rows name their threads).
//
// Usage: bench_peers DATA_DIR [--viking FILE] [SECTION...]
// SECTION is eval, refine, snap or remesh (all when none is named). The
// remeshing cases include the built-in Viking, which the C ABI does not
// expose; write its control net once with
//   target/release/loopsurf refine --example viking --levels 0 -o viking.off
// and pass that file as --viking (without it that case is skipped).
#include "cgal_remesh.hpp"
#include "osd.hpp"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/version.h>

#include <chrono>
#include <functional>
#include <random>
#include <set>

struct Traits : OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
};
typedef OpenMesh::TriMesh_ArrayKernelT<Traits> Mesh;
typedef OpenSubdiv::Bfr::Surface<double> BfrSurface;

// The median of at least `reps` runs, and of as many as fill a tenth of a
// second: a run of a fraction of a millisecond (the pig's build) is
// otherwise at the mercy of one page fault or one preemption.
static double median_seconds(int reps, const std::function<void()>& f) {
    std::vector<double> t;
    double total = 0;
    for (int i = 0; i < reps || (total < 0.1 && i < 10000); i++) {
        auto a = std::chrono::steady_clock::now();
        f();
        t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
        total += t.back();
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

static volatile double sink;

static void evaluation(const std::string& name, const std::string& path) {
    Net n = load_net(path, -1);
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(0, 1);
    auto random_vw = [&](double* vw) {
        double v = u(rng), w = u(rng);
        if (v + w > 1) v = 1 - v, w = 1 - w;
        vw[0] = v, vw[1] = w;
    };
    // (i) one point per triangle, triangles in random order.
    std::vector<int32_t> order(n.ntris());
    for (size_t t = 0; t < n.ntris(); t++) order[t] = int32_t(t);
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<double> vw1(2 * n.ntris());
    for (size_t i = 0; i < n.ntris(); i++) random_vw(&vw1[2 * i]);
    // (ii) 16 random points per triangle, triangles in order.
    std::vector<double> vw16(32 * n.ntris());
    for (size_t i = 0; i < 16 * n.ntris(); i++) random_vw(&vw16[2 * i]);

    double build_ours = median_seconds(3, [&] {
        ls_net* net;
        ls_surface* s;
        ls_net_from_arrays(n.nverts(), n.xyz.data(), n.ntris(), n.tris.data(), &net);
        ls_surface_build(net, &s);
        ls_surface_free(s);
        ls_net_free(net);
    });
    osd::TopologyRefiner* base = nullptr;
    double build_bfr = median_seconds(3, [&] {
        delete base;
        base = osd_refiner(n);
        OpenSubdiv::Bfr::RefinerSurfaceFactory<> f(*base);
    });
    OpenSubdiv::Bfr::RefinerSurfaceFactory<> factory(*base);
    BfrSurface::PointDescriptor desc(3);
    std::vector<double> patch;
    BfrSurface surface;
    double r[18], d[6][3];

    // Both sides make patches on first use (loopsurf its per-triangle
    // patches and configurations, Bfr its cached irregular patches), so the
    // build alone hides work: also time a fresh build followed by the first
    // 1 000 evaluations of (i), and by one whole pass of (ii).
    const size_t first = std::min<size_t>(1000, n.ntris());
    auto ours_fresh = [&](size_t points, bool whole) {
        return median_seconds(3, [&] {
            ls_net* net;
            ls_surface* s;
            ls_net_from_arrays(n.nverts(), n.xyz.data(), n.ntris(), n.tris.data(), &net);
            ls_surface_build(net, &s);
            double acc = 0;
            for (size_t i = 0; i < points; i++) {
                size_t t = whole ? i / 16 : size_t(order[i]);
                const double* vw = whole ? &vw16[2 * i] : &vw1[2 * i];
                ls_evaluate(s, int32_t(t), vw[0], vw[1], r);
                acc += r[0];
            }
            sink = acc;
            ls_surface_free(s);
            ls_net_free(net);
        });
    };
    auto bfr_fresh = [&](size_t points, bool whole) {
        return median_seconds(3, [&] {
            osd::TopologyRefiner* refiner = osd_refiner(n);
            OpenSubdiv::Bfr::RefinerSurfaceFactory<> f(*refiner);
            double acc = 0;
            int current = -1;
            for (size_t i = 0; i < points; i++) {
                int t = whole ? int(i / 16) : order[i];
                const double* vw = whole ? &vw16[2 * i] : &vw1[2 * i];
                if (t != current) {
                    f.InitVertexSurface<double>(t, &surface);
                    patch.resize(3 * size_t(surface.GetNumPatchPoints()));
                    surface.PreparePatchPoints(n.xyz.data(), desc, patch.data(), desc);
                    current = t;
                }
                surface.Evaluate(vw, patch.data(), desc, d[0], d[1], d[2], d[3], d[4], d[5]);
                acc += d[0][0];
            }
            sink = acc;
            delete refiner;
        });
    };
    double first_ours = ours_fresh(first, false), first_bfr = bfr_fresh(first, false);
    double pass_ours = ours_fresh(16 * n.ntris(), true), pass_bfr = bfr_fresh(16 * n.ntris(), true);

    double ours_i = median_seconds(7, [&] {
        double acc = 0;
        for (size_t i = 0; i < n.ntris(); i++) {
            ls_evaluate(n.surface, order[i], vw1[2 * i], vw1[2 * i + 1], r);
            acc += r[0];
        }
        sink = acc;
    });
    double bfr_i = median_seconds(7, [&] {
        double acc = 0;
        for (size_t i = 0; i < n.ntris(); i++) {
            factory.InitVertexSurface<double>(order[i], &surface);
            patch.resize(3 * size_t(surface.GetNumPatchPoints()));
            surface.PreparePatchPoints(n.xyz.data(), desc, patch.data(), desc);
            surface.Evaluate(&vw1[2 * i], patch.data(), desc, d[0], d[1], d[2], d[3], d[4], d[5]);
            acc += d[0][0];
        }
        sink = acc;
    });
    double ours_ii = median_seconds(7, [&] {
        double acc = 0;
        for (size_t t = 0; t < n.ntris(); t++)
            for (size_t i = 16 * t; i < 16 * t + 16; i++) {
                ls_evaluate(n.surface, int32_t(t), vw16[2 * i], vw16[2 * i + 1], r);
                acc += r[0];
            }
        sink = acc;
    });
    double bfr_ii = median_seconds(7, [&] {
        double acc = 0;
        for (size_t t = 0; t < n.ntris(); t++) {
            factory.InitVertexSurface<double>(int(t), &surface);
            patch.resize(3 * size_t(surface.GetNumPatchPoints()));
            surface.PreparePatchPoints(n.xyz.data(), desc, patch.data(), desc);
            for (size_t i = 16 * t; i < 16 * t + 16; i++) {
                surface.Evaluate(&vw16[2 * i], patch.data(), desc, d[0], d[1], d[2], d[3], d[4], d[5]);
                acc += d[0][0];
            }
        }
        sink = acc;
    });
    // ls_evaluate_many on all threads, (ii) order.
    std::vector<int32_t> tri_many(16 * n.ntris());
    std::vector<double> out(18 * 16 * n.ntris());
    for (size_t i = 0; i < tri_many.size(); i++) tri_many[i] = int32_t(i / 16);
    double ours_many = median_seconds(7, [&] {
        ls_evaluate_many(n.surface, tri_many.size(), tri_many.data(), vw16.data(), out.data());
    });
    double m1 = n.ntris() / 1e6, m16 = 16 * n.ntris() / 1e6;
    std::printf("| %s (%zu triangles) | build: loopsurf %.2f ms, Bfr factory %.2f ms (%.2f× its time); + first %zu of (i): %.1f vs %.1f ms (%.2f×); + one pass of (ii): %.1f vs %.1f ms (%.2f×) | (i) 1 pt/tri random: %.2f vs %.2f M/s (%.1f×) | (ii) 16 pts/tri: %.2f vs %.2f M/s (%.1f×); all threads %.2f M/s |\n",
                name.c_str(), n.ntris(), 1e3 * build_ours, 1e3 * build_bfr, build_ours / build_bfr, first, 1e3 * first_ours,
                1e3 * first_bfr, first_ours / first_bfr, 1e3 * pass_ours, 1e3 * pass_bfr, pass_ours / pass_bfr, m1 / ours_i, m1 / bfr_i, bfr_i / ours_i,
                m16 / ours_ii, m16 / bfr_ii, bfr_ii / ours_ii, m16 / ours_many);
    delete base;
    ls_surface_free(n.surface);
}

typedef CGAL::Simple_cartesian<double> K;
typedef std::vector<K::Triangle_3>::const_iterator TriangleIterator;
typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_triangle_primitive<K, TriangleIterator>>> FlatTree;

// The generator and point sets of benches/snap.rs, so both runs see the
// same queries.
struct Lcg {
    uint64_t s;
    double next() {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        return double(s >> 11) / double(1ULL << 53);
    }
};

static void snapping(const std::string& name, const std::string& path) {
    Net n = load_net(path, -1);
    const size_t queries = 2000;
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (size_t i = 0; i < n.nverts(); i++)
        for (int k = 0; k < 3; k++) lo[k] = std::min(lo[k], n.xyz[3 * i + k]), hi[k] = std::max(hi[k], n.xyz[3 * i + k]);
    Lcg rng{3};
    std::vector<double> in_box(3 * queries), near(3 * queries);
    for (size_t i = 0; i < queries; i++)
        for (int k = 0; k < 3; k++) in_box[3 * i + k] = lo[k] + (hi[k] - lo[k]) * rng.next();
    for (size_t i = 0; i < queries; i++) {
        // Within 1% of the diagonal of a surface point, along its normal.
        int32_t t = int32_t(rng.next() * double(n.ntris()));
        double v = rng.next() * 0.5, w = rng.next() * 0.5, r[18];
        ls_evaluate(n.surface, t, v, w, r);
        double nx = r[4] * r[8] - r[5] * r[7], ny = r[5] * r[6] - r[3] * r[8], nz = r[3] * r[7] - r[4] * r[6];
        double len = std::sqrt(nx * nx + ny * ny + nz * nz), s = (rng.next() - 0.5) * 0.02 * n.diagonal / len;
        near[3 * i] = r[0] + s * nx, near[3 * i + 1] = r[1] + s * ny, near[3 * i + 2] = r[2] + s * nz;
    }
    std::vector<K::Triangle_3> flat;
    auto point = [&](int32_t v) { return K::Point_3(n.xyz[3 * v], n.xyz[3 * v + 1], n.xyz[3 * v + 2]); };
    for (size_t t = 0; t < n.ntris(); t++) flat.emplace_back(point(n.tris[3 * t]), point(n.tris[3 * t + 1]), point(n.tris[3 * t + 2]));
    FlatTree tree(flat.begin(), flat.end());
    tree.accelerate_distance_queries();
    int32_t tri;
    double vw[2], x[3], d;
    ls_snap(n.surface, in_box.data(), &tri, vw, x, &d);  // builds the snap index
    auto ours = [&](const std::vector<double>& p) {
        return median_seconds(7, [&] {
            double acc = 0;
            for (size_t i = 0; i < queries; i++) {
                ls_snap(n.surface, &p[3 * i], &tri, vw, x, &d);
                acc += d;
            }
            sink = acc;
        });
    };
    auto cgal = [&](const std::vector<double>& p) {
        return median_seconds(7, [&] {
            double acc = 0;
            for (size_t i = 0; i < queries; i++) acc += tree.closest_point(K::Point_3(p[3 * i], p[3 * i + 1], p[3 * i + 2])).x();
            sink = acc;
        });
    };
    double ours_a = ours(in_box), cgal_a = cgal(in_box), ours_b = ours(near), cgal_b = cgal(near);
    double k = queries / 1e3;
    std::printf("| snap %s | (a) in the box: loopsurf exact, certified %.0f k/s, CGAL AABB on the flat net %.0f k/s (%.2f×) | (b) within 1%%: %.0f vs %.0f k/s (%.2f×) |\n",
                name.c_str(), k / ours_a, k / cgal_a, cgal_a / ours_a, k / ours_b, k / cgal_b, cgal_b / ours_b);
    ls_surface_free(n.surface);
}

static void refinement(const std::string& path, int levels) {
    Net n = load_net(path, -1);
    double ours = median_seconds(7, [&] {
        size_t nv, nt;
        double* xyz;
        int32_t* tris;
        ls_refine(n.surface, levels, 0, &nv, &xyz, &nt, &tris);
        ls_free_array(xyz);
        ls_free_array(tris);
    });
    double openmesh = median_seconds(3, [&] {
        Mesh m;
        std::vector<Mesh::VertexHandle> vh;
        for (size_t i = 0; i < n.nverts(); i++) vh.push_back(m.add_vertex(Mesh::Point(n.xyz[3 * i], n.xyz[3 * i + 1], n.xyz[3 * i + 2])));
        for (size_t t = 0; t < n.ntris(); t++) m.add_face(vh[n.tris[3 * t]], vh[n.tris[3 * t + 1]], vh[n.tris[3 * t + 2]]);
        OpenMesh::Subdivider::Uniform::LoopT<Mesh, double> loop;
        loop.attach(m);
        loop(levels);
        loop.detach();
    });
    double far = median_seconds(7, [&] {
        std::vector<double> xyz;
        std::vector<int> tris;
        osd_refine(n, levels, xyz, tris);
    });
    double mt = double(n.ntris() << (2 * levels)) / 1e6;
    const char* threads = std::getenv("RAYON_NUM_THREADS");
    std::printf("| refine %s ×%d (%.2fM triangles out) | loopsurf %.3f s (%.1f M tri/s, %s threads) | OpenMesh LoopT %.3f s (%.1f M tri/s, %.1f× slower) | OpenSubdiv Far %.3f s (%.1f M tri/s, %.1f× slower) |\n",
                path.substr(path.rfind('/') + 1).c_str(), levels, mt, ours, mt / ours, threads ? threads : "all", openmesh,
                mt / openmesh, openmesh / ours, far, mt / far, far / ours);
    ls_surface_free(n.surface);
}

// Smallest angle of every triangle, in degrees, by one formula for every
// mesh compared: atan2(|u × v|, u · v) at each corner, accurate for
// slivers where acos of the cosine is not.
// With it, the spread of edge lengths as multiples of the target h: the
// 5th, 50th and 95th percentiles over edges (each edge once).
struct AngleStats {
    size_t triangles = 0;
    double min = 180, mean_min = 0;
    double edges[3] = {0, 0, 0};
};

static AngleStats angle_stats(const std::vector<double>& xyz, const std::vector<int32_t>& tris, double h) {
    AngleStats s;
    s.triangles = tris.size() / 3;
    std::vector<std::pair<int32_t, int32_t>> pairs;
    for (size_t t = 0; t < s.triangles; t++)
        for (int k = 0; k < 3; k++) {
            int32_t a = tris[3 * t + k], b = tris[3 * t + (k + 1) % 3];
            pairs.push_back({std::min(a, b), std::max(a, b)});
        }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    std::vector<double> lengths;
    for (auto [a, b] : pairs) {
        const double *p = &xyz[3 * size_t(a)], *q = &xyz[3 * size_t(b)];
        lengths.push_back(std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2])) / h);
    }
    std::sort(lengths.begin(), lengths.end());
    const double at[3] = {0.05, 0.5, 0.95};
    for (int k = 0; k < 3 && !lengths.empty(); k++) s.edges[k] = lengths[size_t(at[k] * double(lengths.size() - 1) + 0.5)];
    double sum = 0;
    for (size_t t = 0; t < s.triangles; t++) {
        const double* p[3] = {&xyz[3 * size_t(tris[3 * t])], &xyz[3 * size_t(tris[3 * t + 1])], &xyz[3 * size_t(tris[3 * t + 2])]};
        double smallest = 180;
        for (int k = 0; k < 3; k++) {
            const double *a = p[k], *b = p[(k + 1) % 3], *c = p[(k + 2) % 3];
            double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2], cz = u[0] * v[1] - u[1] * v[0];
            double angle = std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), u[0] * v[0] + u[1] * v[1] + u[2] * v[2]);
            smallest = std::min(smallest, angle * 180 / M_PI);
        }
        s.min = std::min(s.min, smallest);
        sum += smallest;
    }
    s.mean_min = s.triangles ? sum / double(s.triangles) : 0;
    return s;
}

static double median(std::vector<double> t) {
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

static void remesh_row(const std::string& label, const char* peer, const AngleStats& s, double seconds) {
    std::printf("| %s | %s | %zu | %.1f° | %.1f° | %.2f / %.2f / %.2f h | %.3f s | %.0f k/s |\n", label.c_str(), peer, s.triangles,
                s.min, s.mean_min, s.edges[0], s.edges[1], s.edges[2], seconds, double(s.triangles) / seconds / 1e3);
}

// One case: the control net with its edges above `angle` degrees sharp,
// remeshed at the target edge length `relative` × its diagonal by CGAL's
// isotropic remeshing (on the flat net) and by loopsurf's remesher (on the
// limit surface). Only the remeshing itself is timed.
// With `seams`, loopsurf's net has its concave corners seamed
// (ls_net_seam_concave_corners); CGAL gets the same net and sharp edges
// by angle, which the seams, flat, do not change.
static void remeshing(const std::string& name, const std::string& path, double angle, double relative, int reps, bool seams = false) {
    Net n = load_net(path, angle, seams);
    const double h = relative * n.diagonal;

    CgalRemeshing cgal = cgal_isotropic_remeshing(n.xyz, n.tris, angle, h, 3, reps);
    // Both sides should constrain the same edges (the same rule, boundary
    // edges included); say so if they do not. ls_net_hard_edges gives
    // pairs i < j, as CgalRemeshing::sharp.
    std::vector<std::array<int32_t, 2>> hard;
    for (size_t e = 0; e < n.hard.size() / 2; e++) hard.push_back({n.hard[2 * e], n.hard[2 * e + 1]});
    std::sort(hard.begin(), hard.end());
    if (hard != cgal.sharp && !seams)
        std::fprintf(stderr, "%s: %zu sharp edges for CGAL, %zu hard for loopsurf, not the same set\n", name.c_str(), cgal.sharp.size(),
                     hard.size());

    // loopsurf: the surface (tagged, built) is ready; only ls_remesh runs
    // on the clock, and its mesh is freed after. Whole and in 8 parts, on
    // one thread and on two.
    char label[96];
    std::snprintf(label, sizeof label, "%s, %g%%, %g°", name.c_str(), 100 * relative, angle);
    remesh_row(label, "CGAL isotropic_remeshing", angle_stats(cgal.xyz, cgal.tris, h), median(cgal.seconds));
    for (size_t parts : {1, 8}) {
        for (size_t threads : {1, 2}) {
            AngleStats loop;
            std::vector<double> loop_t;
            ls_remesh_options options;
            ls_remesh_options_default(&options);
            options.size = h;
            options.tolerance = 0;
            options.adapt_curvature = 0;
            options.parts = parts;
            options.threads = threads;
            for (int r = 0; r < reps; r++) {
                ls_trimesh* mesh = nullptr;
                auto a = std::chrono::steady_clock::now();
                if (ls_remesh(n.surface, &options, &mesh) != LS_OK) fail("ls_remesh");
                loop_t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
                size_t nv, nt, per;
                const double* xyz;
                const int32_t* tris;
                if (ls_trimesh_counts(mesh, &nv, &nt, &per) != LS_OK || ls_trimesh_xyz(mesh, &xyz) != LS_OK ||
                    ls_trimesh_elements(mesh, &tris) != LS_OK)
                    fail("ls_trimesh");
                if (r == 0) loop = angle_stats(std::vector<double>(xyz, xyz + 3 * nv), std::vector<int32_t>(tris, tris + 3 * nt), h);
                ls_trimesh_free(mesh);
            }
            char peer[64];
            if (parts == 1)
                std::snprintf(peer, sizeof peer, "loopsurf ls_remesh, %zu thread%s", threads, threads > 1 ? "s" : "");
            else
                std::snprintf(peer, sizeof peer, "loopsurf ls_remesh, %zu parts, %zu thread%s", parts, threads, threads > 1 ? "s" : "");
            remesh_row(label, peer, loop, median(loop_t));
        }
    }
    ls_surface_free(n.surface);
}

int main(int argc, char** argv) {
    std::string dir = ".", viking;
    std::set<std::string> sections;
    for (int i = 1; i < argc; i++) {
        std::string a = argv[i];
        if (a == "--viking" && i + 1 < argc)
            viking = argv[++i];
        else if (a == "eval" || a == "refine" || a == "snap" || a == "remesh")
            sections.insert(a);
        else if (i == 1)
            dir = a;
        else {
            std::fprintf(stderr, "usage: bench_peers DATA_DIR [--viking FILE] [eval|refine|snap|remesh ...]\n");
            return 2;
        }
    }
    auto run = [&](const char* section) { return sections.empty() || sections.count(section); };
    int major, minor, patch;
    ls_version(&major, &minor, &patch);
    std::printf("loopsurf %d.%d.%d vs OpenSubdiv 3.5 (Bfr defaults, Far), OpenMesh LoopT and CGAL %s, medians\n", major, minor, patch,
                CGAL_VERSION_STR);
    if (run("eval")) {
        evaluation("pig", dir + "/pig.off");
        evaluation("bunny00", dir + "/bunny00.off");
    }
    if (run("refine")) refinement(dir + "/bunny00.off", 3);
    if (run("snap")) {
        snapping("pig", dir + "/pig.off");
        snapping("bunny00", dir + "/bunny00.off");
    }
    if (run("remesh")) {
        const int reps = 5;
        std::printf("\nRemeshing, medians of %d runs (bunny00: 3): CGAL isotropic_remeshing of the control net (3 iterations,\n"
                    "sharp edges constrained, one thread), loopsurf's remesher of the limit surface, whole and in 8 parts,\n"
                    "on the threads each row names\n\n",
                    reps);
        std::printf("| case: h (of the diagonal), sharp edges | peer | triangles | min angle | mean-min | edges: 5%% / 50%% / 95%% | time | triangles/s |\n"
                    "|---|---|---|---|---|---|---|---|\n");
        if (!viking.empty())
            remeshing("Viking", viking, 30, 0.01, reps);
        else
            std::fprintf(stderr, "Viking skipped: no --viking FILE (see the usage at the top of bench_peers.cpp)\n");
        remeshing("fandisk", dir + "/fandisk.off", 30, 0.005, reps);
        remeshing("pig", dir + "/pig.off", 40, 0.005, reps);
        remeshing("anchor", dir + "/anchor.off", 30, 0.01, reps);
        remeshing("anchor, concave corners seamed", dir + "/anchor.off", 30, 0.01, reps, true);
        remeshing("bunny00", dir + "/bunny00.off", 180, 0.003, 3);
    }
    return 0;
}
