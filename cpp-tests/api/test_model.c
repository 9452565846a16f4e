/* The model through the C ABI, walked the way a mesh generator walks a CAD
 * model: corners, then curves (points at equal arc length, each found on
 * the faces on both sides and checked against the surface there), then
 * faces (triangles and closed loops of curves); the certified and local
 * projections onto a curve; every error path (bad ids, t out of range,
 * NaN, NULL pointers, outputs untouched on failure); and a cube built from
 * arrays, whose model is known by heart. Usage: test_model DATA_DIR */
#include <loopsurf.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

/* Whether the last error contains every one of up to three strings. */
static int error_says(const char* a, const char* b, const char* c) {
    const char* e = ls_last_error();
    return strstr(e, a) && (!b || strstr(e, b)) && (!c || strstr(e, c));
}

static double dist3(const double* a, const double* b) {
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

/* The bounding-box diagonal of the control net (the model size). */
static double model_size(const ls_surface* s) {
    size_t nv = 0, nt = 0;
    double* xyz = NULL;
    int32_t* tris = NULL;
    EXPECT(ls_refine(s, 0, 0, &nv, &xyz, &nt, &tris), LS_OK);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < nv; i++) {
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], xyz[3 * i + k]);
            hi[k] = fmax(hi[k], xyz[3 * i + k]);
        }
    }
    ls_free_array(xyz);
    ls_free_array(tris);
    return dist3(lo, hi);
}

/* One curve as a mesh generator keeps it. */
typedef struct {
    size_t n;
    int32_t corners[2], faces[2];
    int32_t* chain;
} curve_info;

/* The vertex where a curve run starts or ends, in the direction it is run. */
static int32_t run_start(const curve_info* c, int forward) { return forward ? c->chain[0] : c->chain[c->n]; }
static int32_t run_end(const curve_info* c, int forward) { return forward ? c->chain[c->n] : c->chain[0]; }

/* The walk on a surface with hard features. With `expect_boundary` 0 every
 * curve has a face on both sides. Returns the number of curves. */
static size_t walk(const ls_surface* s, int expect_boundary, size_t points_per_curve) {
    const double size = model_size(s), tol = 1e-12 * size;
    size_t nfaces = 0, ncurves = 0, ncorners = 0, ntris = 0;
    EXPECT(ls_model_counts(s, &nfaces, &ncurves, &ncorners), LS_OK);
    EXPECT(ls_surface_num_triangles(s, &ntris), LS_OK);
    CHECK(nfaces >= 1 && ntris >= nfaces);

    /* Corners: a control vertex each (ascending) and its limit point. */
    int32_t* corner_vertex = calloc(ncorners + 1, sizeof *corner_vertex);
    double* corner_xyz = calloc(3 * ncorners + 3, sizeof *corner_xyz);
    for (size_t k = 0; k < ncorners; k++) {
        EXPECT(ls_model_corner(s, (int32_t)k, &corner_vertex[k], &corner_xyz[3 * k]), LS_OK);
        CHECK(corner_vertex[k] >= 0);
        CHECK(k == 0 || corner_vertex[k] > corner_vertex[k - 1]);
    }

    /* Curves: chains that end at their corners, points at equal arc
     * length found on both faces, and the surface there equal to the curve. */
    curve_info* curves = calloc(ncurves + 1, sizeof *curves);
    double worst = 0.0;
    size_t checked_points = 0;
    for (size_t c = 0; c < ncurves; c++) {
        curve_info* ci = &curves[c];
        const int32_t id = (int32_t)c;
        EXPECT(ls_model_curve(s, id, &ci->n, ci->corners, ci->faces), LS_OK);
        CHECK(ci->n >= 1);
        ci->chain = malloc((ci->n + 1) * sizeof *ci->chain);
        EXPECT(ls_model_curve_chain(s, id, ci->chain), LS_OK);
        const double n = (double)ci->n;
        const int closed = ci->corners[0] < 0;
        CHECK(closed == (ci->corners[1] < 0));
        CHECK(closed == (ci->chain[0] == ci->chain[ci->n]));
        CHECK(ci->faces[0] >= 0 && ci->faces[0] < (int32_t)nfaces);
        CHECK(ci->faces[1] < (int32_t)nfaces);
        if (!expect_boundary) CHECK(ci->faces[1] >= 0);
        double r[18], e[9];
        if (!closed) {
            for (int end = 0; end < 2; end++) {
                const int32_t k = ci->corners[end];
                CHECK(k >= 0 && k < (int32_t)ncorners);
                if (k < 0 || k >= (int32_t)ncorners) continue;
                CHECK(ci->chain[end ? ci->n : 0] == corner_vertex[k]);
                EXPECT(ls_curve_evaluate(s, id, end ? n : 0.0, e), LS_OK);
                CHECK(dist3(e, &corner_xyz[3 * k]) <= tol);
            }
        }
        double length = -1.0;
        EXPECT(ls_curve_length(s, id, 0.0, n, &length), LS_OK);
        CHECK(length > 0.0);
        double back = 0.0;
        EXPECT(ls_curve_length(s, id, n, 0.0, &back), LS_OK);
        CHECK(fabs(back + length) <= 1e-13 * length);
        double previous = -1.0;
        for (size_t i = 0; i <= points_per_curve; i++) {
            const double arc = length * (double)i / (double)points_per_curve;
            double t = SENTINEL, x[9], partial = -1.0;
            EXPECT(ls_curve_param_at_length(s, id, arc, &t), LS_OK);
            CHECK(t >= 0.0 && t <= n && t > previous);
            previous = t;
            EXPECT(ls_curve_length(s, id, 0.0, t, &partial), LS_OK);
            CHECK(fabs(partial - arc) <= 1e-10 * length);
            EXPECT(ls_curve_evaluate(s, id, t, x), LS_OK);
            size_t sides = 0;
            int32_t faces[2] = {-7, -7}, tris[2] = {-7, -7};
            double vw[4];
            EXPECT(ls_curve_surface_points(s, id, t, &sides, faces, tris, vw), LS_OK);
            CHECK(sides == (ci->faces[1] >= 0 ? 2u : 1u));
            if (sides == 1) CHECK(faces[1] == -1 && tris[1] == -1 && isnan(vw[2]) && isnan(vw[3]));
            for (size_t j = 0; j < sides && j < 2; j++) {
                CHECK(faces[j] == ci->faces[j]);
                int32_t face = -1;
                EXPECT(ls_model_triangle_face(s, tris[j], &face), LS_OK);
                CHECK(face == faces[j]);
                CHECK(vw[2 * j] >= 0.0 && vw[2 * j + 1] >= 0.0 && vw[2 * j] + vw[2 * j + 1] <= 1.0);
                EXPECT(ls_evaluate(s, tris[j], vw[2 * j], vw[2 * j + 1], r), LS_OK);
                const double d = dist3(r, x);
                worst = fmax(worst, d);
                CHECK(d <= tol);
                checked_points++;
            }
        }
    }
    printf("  %zu faces, %zu curves, %zu corners; %zu curve points on their faces, worst %.2e of "
           "the model size\n",
           nfaces, ncurves, ncorners, checked_points, worst / size);

    /* Faces: every triangle in exactly one face; loops that close, with
     * the face on the side each run says; every curve used once per side. */
    int* owner = calloc(ntris + 1, sizeof *owner);
    int* uses = calloc(ncurves + 1, sizeof *uses);
    for (size_t f = 0; f < nfaces; f++) {
        size_t nt = 0, nl = 0;
        EXPECT(ls_model_face(s, (int32_t)f, &nt, &nl), LS_OK);
        CHECK(nt >= 1);
        int32_t* tris = malloc((nt + 1) * sizeof *tris);
        EXPECT(ls_model_face_triangles(s, (int32_t)f, tris), LS_OK);
        for (size_t i = 0; i < nt; i++) {
            CHECK(tris[i] >= 0 && (size_t)tris[i] < ntris);
            CHECK(i == 0 || tris[i] > tris[i - 1]);
            if (tris[i] < 0 || (size_t)tris[i] >= ntris) continue;
            owner[tris[i]]++;
            int32_t face = -1;
            EXPECT(ls_model_triangle_face(s, tris[i], &face), LS_OK);
            CHECK(face == (int32_t)f);
        }
        free(tris);
        for (size_t l = 0; l < nl; l++) {
            size_t len = 0;
            EXPECT(ls_model_face_loop(s, (int32_t)f, (int32_t)l, &len, NULL, NULL), LS_OK);
            CHECK(len >= 1);
            int32_t* ids = malloc((len + 1) * sizeof *ids);
            int32_t* forward = malloc((len + 1) * sizeof *forward);
            size_t len2 = 0;
            EXPECT(ls_model_face_loop(s, (int32_t)f, (int32_t)l, &len2, ids, forward), LS_OK);
            CHECK(len2 == len);
            for (size_t i = 0; i < len; i++) {
                CHECK(ids[i] >= 0 && (size_t)ids[i] < ncurves);
                CHECK(forward[i] == 0 || forward[i] == 1);
                if (ids[i] < 0 || (size_t)ids[i] >= ncurves) continue;
                const curve_info* a = &curves[ids[i]];
                uses[ids[i]]++;
                CHECK(a->faces[forward[i] ? 0 : 1] == (int32_t)f);
                const size_t next = (i + 1) % len;
                if (ids[next] < 0 || (size_t)ids[next] >= ncurves) continue;
                const curve_info* b = &curves[ids[next]];
                /* Closes by vertex, and by point (curve end = next start). */
                CHECK(run_end(a, forward[i]) == run_start(b, forward[next]));
                double ea[9], eb[9];
                EXPECT(ls_curve_evaluate(s, ids[i], forward[i] ? (double)a->n : 0.0, ea), LS_OK);
                EXPECT(ls_curve_evaluate(s, ids[next], forward[next] ? 0.0 : (double)b->n, eb), LS_OK);
                CHECK(dist3(ea, eb) <= tol);
            }
            free(ids);
            free(forward);
        }
    }
    for (size_t t = 0; t < ntris; t++) CHECK(owner[t] == 1);
    for (size_t c = 0; c < ncurves; c++) CHECK(uses[c] == (curves[c].faces[1] >= 0 ? 2 : 1));

    free(owner);
    free(uses);
    for (size_t c = 0; c < ncurves; c++) free(curves[c].chain);
    free(curves);
    free(corner_vertex);
    free(corner_xyz);
    return ncurves;
}

/* Every error path, on curve `c` of n edges: statuses, messages naming the
 * index and the count, and outputs left untouched. */
static void errors(const ls_surface* s) {
    size_t nfaces = 0, ncurves = 0, ncorners = 0, ntris = 0, n = 0, nt = 0, nl = 0;
    EXPECT(ls_model_counts(s, &nfaces, &ncurves, &ncorners), LS_OK);
    EXPECT(ls_model_counts(s, NULL, NULL, NULL), LS_OK); /* outputs may be NULL */
    EXPECT(ls_surface_num_triangles(s, &ntris), LS_OK);
    int32_t corners[2], faces[2];
    EXPECT(ls_model_curve(s, 0, &n, corners, faces), LS_OK);
    EXPECT(ls_model_face(s, 0, &nt, &nl), LS_OK);
    const double len = (double)n;
    char count[64];

    /* Curve ids -1 and ncurves, in every curve function. */
    double out[9] = {SENTINEL}, value = SENTINEL, xyz[3] = {0, 0, 0}, x3[3] = {SENTINEL};
    const int32_t bad_curves[2] = {-1, (int32_t)ncurves};
    snprintf(count, sizeof count, "(the model has %zu curves)", ncurves);
    for (int i = 0; i < 2; i++) {
        char name[32];
        snprintf(name, sizeof name, "curve %d:", bad_curves[i]);
        const int32_t c = bad_curves[i];
        size_t nn = 99;
        int32_t ii[2] = {-7, -7}, jj[2] = {-7, -7}, chain[4] = {-7};
        double vw[4] = {SENTINEL};
        EXPECT(ls_curve_evaluate(s, c, 0.0, out), LS_ERR_INDEX_OUT_OF_RANGE);
        CHECK(error_says("ls_curve_evaluate", name, count));
        EXPECT(ls_model_curve(s, c, &nn, ii, jj), LS_ERR_INDEX_OUT_OF_RANGE);
        CHECK(error_says("ls_model_curve", name, count));
        EXPECT(ls_model_curve_chain(s, c, chain), LS_ERR_INDEX_OUT_OF_RANGE);
        EXPECT(ls_curve_length(s, c, 0.0, 0.5, &value), LS_ERR_INDEX_OUT_OF_RANGE);
        EXPECT(ls_curve_param_at_length(s, c, 0.0, &value), LS_ERR_INDEX_OUT_OF_RANGE);
        EXPECT(ls_curve_surface_points(s, c, 0.0, &nn, ii, jj, vw), LS_ERR_INDEX_OUT_OF_RANGE);
        EXPECT(ls_curve_project(s, c, xyz, 0.0, &value, x3, &value), LS_ERR_INDEX_OUT_OF_RANGE);
        EXPECT(ls_curve_snap(s, c, xyz, 0.0, &value, x3, &value, &value), LS_ERR_INDEX_OUT_OF_RANGE);
        CHECK(error_says("ls_curve_snap", name, count));
        CHECK(nn == 99 && ii[0] == -7 && jj[0] == -7 && chain[0] == -7 && vw[0] == SENTINEL);
    }
    CHECK(out[0] == SENTINEL && value == SENTINEL && x3[0] == SENTINEL);

    /* Face, corner, loop and triangle ids. */
    size_t a = 99, b = 99;
    int32_t v = -7, buf[2] = {-7, -7};
    snprintf(count, sizeof count, "(the model has %zu faces)", nfaces);
    EXPECT(ls_model_face(s, -1, &a, &b), LS_ERR_INDEX_OUT_OF_RANGE);
    CHECK(error_says("ls_model_face", "face -1:", count));
    EXPECT(ls_model_face(s, (int32_t)nfaces, &a, &b), LS_ERR_INDEX_OUT_OF_RANGE);
    EXPECT(ls_model_face_triangles(s, (int32_t)nfaces, buf), LS_ERR_INDEX_OUT_OF_RANGE);
    EXPECT(ls_model_face_loop(s, -1, 0, &a, NULL, NULL), LS_ERR_INDEX_OUT_OF_RANGE);
    snprintf(count, sizeof count, "(face 0 has %zu loops)", nl);
    EXPECT(ls_model_face_loop(s, 0, (int32_t)nl, &a, NULL, NULL), LS_ERR_INDEX_OUT_OF_RANGE);
    CHECK(error_says("ls_model_face_loop", "loop ", count));
    EXPECT(ls_model_face_loop(s, 0, -1, &a, NULL, NULL), LS_ERR_INDEX_OUT_OF_RANGE);
    snprintf(count, sizeof count, "(the model has %zu corners)", ncorners);
    EXPECT(ls_model_corner(s, (int32_t)ncorners, &v, x3), LS_ERR_INDEX_OUT_OF_RANGE);
    CHECK(error_says("ls_model_corner", "corner ", count));
    EXPECT(ls_model_corner(s, -1, &v, x3), LS_ERR_INDEX_OUT_OF_RANGE);
    snprintf(count, sizeof count, "(the net has %zu triangles)", ntris);
    EXPECT(ls_model_triangle_face(s, (int32_t)ntris, &v), LS_ERR_INDEX_OUT_OF_RANGE);
    CHECK(error_says("ls_model_triangle_face", "triangle ", count));
    CHECK(a == 99 && b == 99 && v == -7 && buf[0] == -7 && x3[0] == SENTINEL);

    /* Parameters outside [0, n], arc lengths outside [0, length], NaN. */
    size_t sides = 99;
    int32_t f2[2], t2[2];
    double vw[4];
    EXPECT(ls_curve_evaluate(s, 0, -0.5, out), LS_ERR_PARAMETER_OUT_OF_RANGE);
    CHECK(error_says("ls_curve_evaluate", "t = -0.5", "outside [0, "));
    EXPECT(ls_curve_evaluate(s, 0, len + 0.5, out), LS_ERR_PARAMETER_OUT_OF_RANGE);
    EXPECT(ls_curve_evaluate(s, 0, len * (1 + 1e-14), out), LS_OK); /* round-off is tolerated */
    out[0] = SENTINEL;
    EXPECT(ls_curve_evaluate(s, 0, NAN, out), LS_ERR_NOT_FINITE);
    EXPECT(ls_curve_evaluate(s, 0, INFINITY, out), LS_ERR_NOT_FINITE);
    EXPECT(ls_curve_length(s, 0, 0.0, len + 1.0, &value), LS_ERR_PARAMETER_OUT_OF_RANGE);
    CHECK(error_says("ls_curve_length", "t1 = ", NULL));
    EXPECT(ls_curve_length(s, 0, NAN, 0.0, &value), LS_ERR_NOT_FINITE);
    EXPECT(ls_curve_surface_points(s, 0, -1.0, &sides, f2, t2, vw), LS_ERR_PARAMETER_OUT_OF_RANGE);
    EXPECT(ls_curve_project(s, 0, xyz, len + 1.0, &value, x3, &value), LS_ERR_PARAMETER_OUT_OF_RANGE);
    CHECK(error_says("ls_curve_project", "t_guess = ", NULL));
    double total = 0.0;
    EXPECT(ls_curve_length(s, 0, 0.0, len, &total), LS_OK);
    EXPECT(ls_curve_param_at_length(s, 0, 1.01 * total, &value), LS_ERR_PARAMETER_OUT_OF_RANGE);
    CHECK(error_says("ls_curve_param_at_length", "arc length", NULL));
    EXPECT(ls_curve_param_at_length(s, 0, -0.01 * total, &value), LS_ERR_PARAMETER_OUT_OF_RANGE);
    EXPECT(ls_curve_param_at_length(s, 0, NAN, &value), LS_ERR_NOT_FINITE);
    const double nan_xyz[3] = {0.0, NAN, 0.0};
    EXPECT(ls_curve_project(s, 0, nan_xyz, 0.0, &value, x3, &value), LS_ERR_NOT_FINITE);
    EXPECT(ls_curve_snap(s, 0, nan_xyz, 0.0, &value, x3, &value, &value), LS_ERR_NOT_FINITE);
    EXPECT(ls_curve_snap(s, 0, xyz, -1e-6, &value, x3, &value, &value), LS_ERR_INVALID_ARGUMENT);
    EXPECT(ls_curve_snap(s, 0, xyz, NAN, &value, x3, &value, &value), LS_ERR_NOT_FINITE);
    CHECK(out[0] == SENTINEL && value == SENTINEL && x3[0] == SENTINEL && sides == 99);

    /* NULL pointers: the surface and every required output. */
    EXPECT(ls_model_counts(NULL, &a, &b, &a), LS_ERR_NULL_POINTER);
    CHECK(error_says("ls_model_counts", "surface is NULL", NULL));
    EXPECT(ls_model_corner(NULL, 0, &v, x3), LS_ERR_NULL_POINTER);
    EXPECT(ls_model_corner(s, 0, NULL, x3), LS_ERR_NULL_POINTER);
    EXPECT(ls_model_corner(s, 0, &v, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_model_curve(s, 0, NULL, f2, t2), LS_ERR_NULL_POINTER);
    EXPECT(ls_model_curve(s, 0, &a, NULL, t2), LS_ERR_NULL_POINTER);
    EXPECT(ls_model_curve(s, 0, &a, f2, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_model_curve_chain(s, 0, NULL), LS_ERR_NULL_POINTER);
    CHECK(error_says("ls_model_curve_chain", "chain is NULL", NULL));
    EXPECT(ls_model_face(s, 0, NULL, &b), LS_ERR_NULL_POINTER);
    EXPECT(ls_model_face(s, 0, &a, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_model_face_triangles(s, 0, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_model_face_loop(s, 0, 0, NULL, NULL, NULL), LS_ERR_NULL_POINTER);
    if (nl > 0) {
        int32_t one[64];
        EXPECT(ls_model_face_loop(s, 0, 0, &a, one, NULL), LS_ERR_NULL_POINTER);
        CHECK(error_says("ls_model_face_loop", "forward is NULL", NULL));
        EXPECT(ls_model_face_loop(s, 0, 0, &a, NULL, one), LS_ERR_NULL_POINTER);
        CHECK(error_says("ls_model_face_loop", "curves is NULL", NULL));
    }
    EXPECT(ls_model_triangle_face(s, 0, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_curve_evaluate(NULL, 0, 0.0, out), LS_ERR_NULL_POINTER);
    EXPECT(ls_curve_evaluate(s, 0, 0.0, NULL), LS_ERR_NULL_POINTER);
    CHECK(error_says("ls_curve_evaluate", "result is NULL", NULL));
    EXPECT(ls_curve_length(s, 0, 0.0, 1.0, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_curve_param_at_length(s, 0, 0.0, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_curve_surface_points(s, 0, 0.0, NULL, f2, t2, vw), LS_ERR_NULL_POINTER);
    EXPECT(ls_curve_surface_points(s, 0, 0.0, &a, NULL, t2, vw), LS_ERR_NULL_POINTER);
    EXPECT(ls_curve_surface_points(s, 0, 0.0, &a, f2, NULL, vw), LS_ERR_NULL_POINTER);
    EXPECT(ls_curve_surface_points(s, 0, 0.0, &a, f2, t2, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_curve_project(s, 0, NULL, 0.0, &value, x3, &value), LS_ERR_NULL_POINTER);
    EXPECT(ls_curve_project(s, 0, xyz, 0.0, NULL, x3, &value), LS_ERR_NULL_POINTER);
    EXPECT(ls_curve_project(s, 0, xyz, 0.0, &value, NULL, &value), LS_ERR_NULL_POINTER);
    EXPECT(ls_curve_project(s, 0, xyz, 0.0, &value, x3, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_curve_snap(s, 0, NULL, 0.0, &value, x3, &value, &value), LS_ERR_NULL_POINTER);
    EXPECT(ls_curve_snap(s, 0, xyz, 0.0, &value, x3, &value, NULL), LS_ERR_NULL_POINTER);
    CHECK(error_says("ls_curve_snap", "lower_bound is NULL", NULL));
    CHECK(a == 99 && b == 99 && v == -7 && value == SENTINEL && x3[0] == SENTINEL && out[0] == SENTINEL);
}

/* Snap a point offset from curve c by `offset` across the curve: the
 * certified snap finds the curve point it came from, with a certificate;
 * the local projection from a nearby guess agrees. */
static void snap_offset(const ls_surface* s, int32_t c, double offset) {
    const double size = model_size(s);
    size_t n = 0;
    int32_t corners[2], faces[2];
    EXPECT(ls_model_curve(s, c, &n, corners, faces), LS_OK);
    double total = 0.0, t0 = 0.0, e[9];
    EXPECT(ls_curve_length(s, c, 0.0, (double)n, &total), LS_OK);
    EXPECT(ls_curve_param_at_length(s, c, 0.37 * total, &t0), LS_OK);
    EXPECT(ls_curve_evaluate(s, c, t0, e), LS_OK);
    /* A direction across the curve: the tangent crossed with the axis it
     * is least aligned with. */
    const double* d = &e[3];
    int axis = 0;
    for (int k = 1; k < 3; k++) {
        if (fabs(d[k]) < fabs(d[axis])) axis = k;
    }
    double u[3] = {0, 0, 0}, ax[3] = {0, 0, 0};
    ax[axis] = 1.0;
    u[0] = d[1] * ax[2] - d[2] * ax[1];
    u[1] = d[2] * ax[0] - d[0] * ax[2];
    u[2] = d[0] * ax[1] - d[1] * ax[0];
    const double un = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    double p[3];
    for (int k = 0; k < 3; k++) p[k] = e[k] + offset * size * u[k] / un;

    double t = -1.0, x[3], distance = -1.0, lower = -1.0, r[9];
    EXPECT(ls_curve_snap(s, c, p, 0.0, &t, x, &distance, &lower), LS_OK);
    CHECK(fabs(t - t0) <= 1e-6 * (double)n);
    CHECK(fabs(distance - offset * size) <= 1e-12 * size);
    CHECK(lower <= distance && distance - lower <= 1e-12 * size);
    EXPECT(ls_curve_evaluate(s, c, t, r), LS_OK);
    CHECK(memcmp(r, x, sizeof x) == 0); /* the curve at t, bit for bit */
    CHECK(fabs(dist3(x, p) - distance) <= 1e-15 * size);
    printf("  snap at %.0e of the size from curve %d: distance - lower bound = %.1e of the size\n", offset,
           c, (distance - lower) / size);

    /* A loose certificate is faster and still a bound. */
    double t_loose, x_loose[3], d_loose, lower_loose;
    EXPECT(ls_curve_snap(s, c, p, 1e-6, &t_loose, x_loose, &d_loose, &lower_loose), LS_OK);
    CHECK(lower_loose <= d_loose && d_loose - lower_loose <= 1e-6 * size && d_loose >= distance - 1e-12 * size);

    /* Local projection from a guess a little off. */
    double tp = -1.0, xp[3], dp = -1.0;
    const double guess = t0 + (t0 + 0.2 <= (double)n ? 0.2 : -0.2);
    EXPECT(ls_curve_project(s, c, p, guess, &tp, xp, &dp), LS_OK);
    CHECK(fabs(tp - t) <= 1e-6 * (double)n && fabs(dp - distance) <= 1e-12 * size);
    EXPECT(ls_curve_evaluate(s, c, tp, r), LS_OK);
    CHECK(memcmp(r, xp, sizeof xp) == 0);
}

static void test_fandisk(const char* data_dir) {
    char path[1024];
    snprintf(path, sizeof path, "%s/fandisk.off", data_dir);
    ls_net* net = NULL;
    ls_surface* s = NULL;
    size_t tagged = 0;
    EXPECT(ls_net_load(path, &net), LS_OK);
    if (!net) return;
    EXPECT(ls_net_tag_by_angle(net, 30.0, &tagged), LS_OK);
    CHECK(tagged > 0);
    EXPECT(ls_surface_build(net, &s), LS_OK);
    ls_net_free(net);
    if (!s) return;
    printf("fandisk at 30 degrees (%zu hard edges):\n", tagged);
    const size_t ncurves = walk(s, 0, 8);
    CHECK(ncurves > 10);
    errors(s);
    for (int32_t c = 0; c < (int32_t)ncurves; c += 7) snap_offset(s, c, 1e-3);
    ls_surface_free(s);
}

/* The unit cube from arrays, every edge of the cube hard (90 degrees), the
 * face diagonals soft (flat): 6 faces of 2 triangles with one loop of 4
 * curves, 12 straight curves of one control edge, 8 fixed corners. */
static void test_cube(void) {
    static const double xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
    static const int32_t tris[] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                   1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
    ls_net* net = NULL;
    ls_surface* s = NULL;
    size_t tagged = 0;
    EXPECT(ls_net_from_arrays(8, xyz, 12, tris, &net), LS_OK);
    if (!net) return;
    EXPECT(ls_net_tag_by_angle(net, 30.0, &tagged), LS_OK);
    CHECK(tagged == 12);
    EXPECT(ls_surface_build(net, &s), LS_OK);
    ls_net_free(net);
    if (!s) return;
    size_t nf = 0, nc = 0, nk = 0;
    EXPECT(ls_model_counts(s, &nf, &nc, &nk), LS_OK);
    CHECK(nf == 6 && nc == 12 && nk == 8);
    printf("cube from arrays:\n");
    walk(s, 0, 4);
    for (int32_t k = 0; k < 8; k++) {
        int32_t v = -1;
        double p[3];
        EXPECT(ls_model_corner(s, k, &v, p), LS_OK);
        CHECK(v == k && dist3(p, &xyz[3 * k]) <= 1e-15); /* corners are fixed */
    }
    for (int32_t c = 0; c < 12; c++) {
        size_t n = 0;
        int32_t corners[2], faces[2], chain[2];
        EXPECT(ls_model_curve(s, c, &n, corners, faces), LS_OK);
        EXPECT(ls_model_curve_chain(s, c, chain), LS_OK);
        CHECK(n == 1 && corners[0] == chain[0] && corners[1] == chain[1]);
        CHECK(faces[0] >= 0 && faces[1] >= 0 && faces[0] != faces[1]);
        /* Between two fixed corners the crease is the straight edge. */
        double e[9], mid[3], length = 0.0;
        EXPECT(ls_curve_evaluate(s, c, 0.5, e), LS_OK);
        for (int k = 0; k < 3; k++) mid[k] = 0.5 * (xyz[3 * chain[0] + k] + xyz[3 * chain[1] + k]);
        CHECK(dist3(e, mid) <= 1e-15);
        EXPECT(ls_curve_length(s, c, 0.0, 1.0, &length), LS_OK);
        CHECK(fabs(length - 1.0) <= 1e-14);
    }
    for (int32_t f = 0; f < 6; f++) {
        size_t nt = 0, nl = 0, len = 0;
        EXPECT(ls_model_face(s, f, &nt, &nl), LS_OK);
        CHECK(nt == 2 && nl == 1);
        EXPECT(ls_model_face_loop(s, f, 0, &len, NULL, NULL), LS_OK);
        CHECK(len == 4);
    }
    errors(s);
    snap_offset(s, 5, 0.1);
    ls_surface_free(s);
}

/* A smooth closed surface: one face, no loop, no curve, no corner. */
static void test_smooth(void) {
    static const double xyz[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    static const int32_t tris[] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    ls_net* net = NULL;
    ls_surface* s = NULL;
    EXPECT(ls_net_from_arrays(6, xyz, 8, tris, &net), LS_OK);
    EXPECT(ls_surface_build(net, &s), LS_OK);
    ls_net_free(net);
    size_t nf = 9, nc = 9, nk = 9, nt = 0, nl = 9;
    EXPECT(ls_model_counts(s, &nf, &nc, &nk), LS_OK);
    CHECK(nf == 1 && nc == 0 && nk == 0);
    EXPECT(ls_model_face(s, 0, &nt, &nl), LS_OK);
    CHECK(nt == 8 && nl == 0);
    double r[9];
    EXPECT(ls_curve_evaluate(s, 0, 0.0, r), LS_ERR_INDEX_OUT_OF_RANGE);
    CHECK(error_says("curve 0:", "(the model has 0 curves)", NULL));
    ls_surface_free(s);
}

int main(int argc, char** argv) {
    const char* data_dir = argc > 1 ? argv[1] : ".";
    test_cube();
    test_smooth();
    test_fandisk(data_dir);
    if (failures) {
        fprintf(stderr, "%d checks failed\n", failures);
        return 1;
    }
    printf("C model API: all checks passed\n");
    return 0;
}
