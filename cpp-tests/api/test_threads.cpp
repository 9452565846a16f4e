// A built surface queried from 8 threads at once gives bit-identical
// results to a serial run: evaluation, curvature, batches and snapping.
// Twice: on the surface the serial run warmed (every lazy patch and the
// snap index built), and on a fresh surface of the same net that the 8
// threads hit first, all released together, half of them snapping before
// they evaluate, so the first uses race.
// Usage: test_threads MESH
#include <loopsurf.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <random>
#include <thread>
#include <vector>

struct Results {
    std::vector<double> eval, curvature, snap;
};

struct Queries {
    std::vector<int32_t> tri;
    std::vector<double> vw, points;
};

static void evaluate(const ls_surface* s, const Queries& q, Results& r, bool& ok) {
    for (size_t i = 0; i < q.tri.size(); i++) {
        ok &= ls_evaluate(s, q.tri[i], q.vw[2 * i], q.vw[2 * i + 1], &r.eval[18 * i]) == LS_OK;
        ok &= ls_curvature(s, q.tri[i], q.vw[2 * i], q.vw[2 * i + 1], &r.curvature[8 * i]) == LS_OK;
    }
}

static void snap(const ls_surface* s, const Queries& q, Results& r, bool& ok) {
    for (size_t i = 0; i < q.points.size() / 3; i++) {
        int32_t t;
        double* out = &r.snap[7 * i];
        ok &= ls_snap(s, &q.points[3 * i], &t, out + 1, out + 3, out + 6) == LS_OK;
        out[0] = t;
    }
}

// Every query on `s`: evaluations and curvatures, and snaps (first when
// `snap_first`).
static Results run(const ls_surface* s, const Queries& q, bool snap_first, bool& ok) {
    Results r;
    r.eval.resize(18 * q.tri.size());
    r.curvature.resize(8 * q.tri.size());
    r.snap.resize(7 * (q.points.size() / 3));
    if (snap_first) snap(s, q, r, ok);
    evaluate(s, q, r, ok);
    if (!snap_first) snap(s, q, r, ok);
    return r;
}

// 8 threads released together on `s`, each running every query (odd ones
// snapping first) and a batch: the number of results that differ from
// `serial` by a bit, or failed.
static int parallel_mismatches(const ls_surface* s, const Queries& q, const Results& serial) {
    const int nthreads = 8;
    const size_t n = q.tri.size();
    std::vector<Results> parallel(nthreads);
    std::vector<std::vector<double>> batches(nthreads, std::vector<double>(18 * n));
    std::vector<char> oks(nthreads, 1);
    std::vector<std::thread> threads;
    std::atomic<int> ready{0};
    for (int k = 0; k < nthreads; k++) {
        threads.emplace_back([&, k] {
            ready.fetch_add(1);
            while (ready.load() < nthreads) std::this_thread::yield();
            bool tok = true;
            parallel[k] = run(s, q, k % 2 == 1, tok);
            tok &= ls_evaluate_many(s, n, q.tri.data(), q.vw.data(), batches[k].data()) == LS_OK;
            oks[k] = tok;
        });
    }
    for (auto& t : threads) t.join();
    auto differ = [](const std::vector<double>& a, const std::vector<double>& b) {
        return int(a.size() != b.size() || std::memcmp(a.data(), b.data(), 8 * a.size()) != 0);
    };
    int failures = 0;
    for (int k = 0; k < nthreads; k++) {
        failures += !oks[k];
        failures += differ(parallel[k].eval, serial.eval) + differ(parallel[k].curvature, serial.curvature);
        failures += differ(parallel[k].snap, serial.snap) + differ(batches[k], serial.eval);
    }
    return failures;
}

int main(int argc, char** argv) {
    if (argc < 2) return 2;
    ls_net* net = nullptr;
    ls_surface* s = nullptr;
    if (ls_net_load(argv[1], &net) != LS_OK || ls_net_tag_by_angle(net, 30, nullptr) != LS_OK ||
        ls_surface_build(net, &s) != LS_OK) {
        std::fprintf(stderr, "setup failed: %s\n", ls_last_error());
        return 1;
    }
    size_t ntris = 0;
    ls_surface_num_triangles(s, &ntris);
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(0, 1);
    const size_t n = 40000, nsnap = 800;
    Queries q{std::vector<int32_t>(n), std::vector<double>(2 * n), std::vector<double>(3 * nsnap)};
    for (size_t i = 0; i < n; i++) {
        q.tri[i] = int32_t(rng() % ntris);
        double v = u(rng), w = u(rng);
        if (v + w > 1) v = 1 - v, w = 1 - w;
        q.vw[2 * i] = v, q.vw[2 * i + 1] = w;
    }
    for (auto& x : q.points) x = 2 * u(rng) - 1;

    bool ok = true;
    Results serial = run(s, q, false, ok);
    std::vector<double> batch(18 * n);
    ok &= ls_evaluate_many(s, n, q.tri.data(), q.vw.data(), batch.data()) == LS_OK;
    int failures = ok ? 0 : 1;
    failures += std::memcmp(batch.data(), serial.eval.data(), 8 * serial.eval.size()) != 0;
    failures += parallel_mismatches(s, q, serial);
    int warm = failures;
    ls_surface* fresh = nullptr;
    if (ls_surface_build(net, &fresh) != LS_OK) {
        std::fprintf(stderr, "fresh surface: %s\n", ls_last_error());
        return 1;
    }
    failures += parallel_mismatches(fresh, q, serial);
    ls_surface_free(fresh);
    ls_surface_free(s);
    ls_net_free(net);
    if (failures) {
        std::fprintf(stderr, "threads: %d mismatches (%d on the warm surface, %d on the fresh one)\n", failures,
                     warm, failures - warm);
        return 1;
    }
    std::printf("threads: 8 x (%zu evaluations, curvatures, %zu snaps) bit-identical, warm and fresh\n", n, nsnap);
    return 0;
}
