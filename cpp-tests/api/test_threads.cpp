// A built surface queried from 8 threads at once gives bit-identical
// results to a serial run: evaluation, curvature, batches and snapping.
// Usage: test_threads MESH
#include <loopsurf.h>

#include <cstdio>
#include <cstring>
#include <random>
#include <thread>
#include <vector>

struct Results {
    std::vector<double> eval, curvature, snap;
};

static Results run(const ls_surface* s, const std::vector<int32_t>& tri, const std::vector<double>& vw,
                   const std::vector<double>& points, size_t begin, size_t end, bool& ok) {
    Results r;
    r.eval.resize(18 * tri.size());
    r.curvature.resize(8 * tri.size());
    r.snap.resize(7 * (points.size() / 3));
    for (size_t i = begin; i < end; i++) {
        ok &= ls_evaluate(s, tri[i], vw[2 * i], vw[2 * i + 1], &r.eval[18 * i]) == LS_OK;
        ok &= ls_curvature(s, tri[i], vw[2 * i], vw[2 * i + 1], &r.curvature[8 * i]) == LS_OK;
    }
    for (size_t i = begin * points.size() / 3 / tri.size(); i < end * points.size() / 3 / tri.size(); i++) {
        int32_t t;
        double* out = &r.snap[7 * i];
        ok &= ls_snap(s, &points[3 * i], &t, out + 1, out + 3, out + 6) == LS_OK;
        out[0] = t;
    }
    return r;
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
    std::vector<int32_t> tri(n);
    std::vector<double> vw(2 * n), points(3 * nsnap);
    for (size_t i = 0; i < n; i++) {
        tri[i] = int32_t(rng() % ntris);
        double v = u(rng), w = u(rng);
        if (v + w > 1) v = 1 - v, w = 1 - w;
        vw[2 * i] = v, vw[2 * i + 1] = w;
    }
    for (auto& x : points) x = 2 * u(rng) - 1;

    bool ok = true;
    Results serial = run(s, tri, vw, points, 0, n, ok);
    std::vector<double> batch(18 * n);
    ok &= ls_evaluate_many(s, n, tri.data(), vw.data(), batch.data()) == LS_OK;

    // 8 threads: each evaluates every query (all at once) and its own
    // share is compared; plus concurrent batches.
    const int nthreads = 8;
    std::vector<Results> parallel(nthreads);
    std::vector<std::vector<double>> batches(nthreads, std::vector<double>(18 * n));
    std::vector<char> oks(nthreads, 1);
    std::vector<std::thread> threads;
    for (int k = 0; k < nthreads; k++) {
        threads.emplace_back([&, k] {
            bool tok = true;
            parallel[k] = run(s, tri, vw, points, 0, n, tok);
            tok &= ls_evaluate_many(s, n, tri.data(), vw.data(), batches[k].data()) == LS_OK;
            oks[k] = tok;
        });
    }
    for (auto& t : threads) t.join();
    int failures = ok ? 0 : 1;
    for (int k = 0; k < nthreads; k++) {
        failures += !oks[k];
        failures += std::memcmp(parallel[k].eval.data(), serial.eval.data(), 8 * serial.eval.size()) != 0;
        failures += std::memcmp(parallel[k].curvature.data(), serial.curvature.data(),
                                8 * serial.curvature.size()) != 0;
        failures += std::memcmp(parallel[k].snap.data(), serial.snap.data(), 8 * serial.snap.size()) != 0;
        failures += std::memcmp(batches[k].data(), serial.eval.data(), 8 * serial.eval.size()) != 0;
    }
    failures += std::memcmp(batch.data(), serial.eval.data(), 8 * serial.eval.size()) != 0;
    ls_surface_free(s);
    ls_net_free(net);
    if (failures) {
        std::fprintf(stderr, "threads: %d mismatches\n", failures);
        return 1;
    }
    std::printf("threads: 8 x (%zu evaluations, curvatures, %zu snaps) bit-identical\n", n, nsnap);
    return 0;
}
