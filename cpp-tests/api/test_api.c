/* Every function of the C ABI, on its success path and on every error
 * path: NULL pointers, bad indices, parameters out of range, NaN, bad
 * files, damaged and truncated streams. Outputs must be untouched on
 * failure. Usage: test_api DATA_DIR */
#include <loopsurf.h>

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"

/* An octahedron: six valence-4 vertices, eight triangles. */
static const double OCTA_XYZ[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
static const int32_t OCTA_TRIS[] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4,
                                    2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};

/* Test files go into a directory of this run's own (test_api and
 * test_api_static run side by side), never into the working directory. */
static char scratch_dir[64];

static const char* scratch(const char* name) {
    static char path[128];
    snprintf(path, sizeof path, "%s/%s", scratch_dir, name);
    return path;
}

static const char* write_file(const char* name, const char* text) {
    const char* path = scratch(name);
    FILE* f = fopen(path, "w");
    CHECK(f != NULL);
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    return path;
}

static int compare_edges(const void* a, const void* b) {
    const int64_t x = *(const int64_t*)a, y = *(const int64_t*)b;
    return (x > y) - (x < y);
}

/* The number of edges of a triangle mesh, counted, or -1 unless every edge
 * has exactly two triangles (a closed manifold): what an Euler check must
 * rest on, rather than E = 3T/2. */
static long closed_edges(const int32_t* tris, size_t nt) {
    int64_t* keys = malloc(3 * nt * sizeof *keys);
    for (size_t t = 0; t < nt; t++) {
        for (int k = 0; k < 3; k++) {
            int64_t a = tris[3 * t + k], b = tris[3 * t + (k + 1) % 3];
            keys[3 * t + k] = a < b ? (a << 32) | b : (b << 32) | a;
        }
    }
    qsort(keys, 3 * nt, sizeof *keys, compare_edges);
    long edges = 0;
    for (size_t i = 0; i < 3 * nt;) {
        size_t j = i;
        while (j < 3 * nt && keys[j] == keys[i]) j++;
        if (j - i != 2) {
            free(keys);
            return -1;
        }
        edges++;
        i = j;
    }
    free(keys);
    return edges;
}

/* V - E + F of a closed mesh, or a value no sphere has (-99) if it is open. */
static long euler(size_t nv, const int32_t* tris, size_t nt) {
    long e = closed_edges(tris, nt);
    return e < 0 ? -99 : (long)nv - e + (long)nt;
}

static ls_surface* octahedron(ls_net** net_out) {
    ls_net* net = NULL;
    ls_surface* surface = NULL;
    EXPECT(ls_net_from_arrays(6, OCTA_XYZ, 8, OCTA_TRIS, &net), LS_OK);
    EXPECT(ls_surface_build(net, &surface), LS_OK);
    if (net_out) {
        *net_out = net;
    } else {
        ls_net_free(net);
    }
    return surface;
}

static void test_version_and_strings(void) {
    int major = -1, minor = -1, patch = -1;
    ls_version(&major, &minor, &patch);
    CHECK(major == 1 && minor == 0 && patch >= 0);
    ls_version(NULL, NULL, NULL); /* tolerated */
    const int codes[] = {LS_OK, LS_ERR_NULL_POINTER, LS_ERR_IO, LS_ERR_PARSE, LS_ERR_NON_MANIFOLD,
                         LS_ERR_DEGENERATE, LS_ERR_INDEX_OUT_OF_RANGE, LS_ERR_PARAMETER_OUT_OF_RANGE,
                         LS_ERR_NOT_FINITE, LS_ERR_UNSUPPORTED, LS_ERR_BAD_STREAM,
                         LS_ERR_INVALID_ARGUMENT, LS_ERR_INTERNAL};
    const char* names[] = {"LS_OK", "LS_ERR_NULL_POINTER", "LS_ERR_IO", "LS_ERR_PARSE",
                           "LS_ERR_NON_MANIFOLD", "LS_ERR_DEGENERATE", "LS_ERR_INDEX_OUT_OF_RANGE",
                           "LS_ERR_PARAMETER_OUT_OF_RANGE", "LS_ERR_NOT_FINITE", "LS_ERR_UNSUPPORTED",
                           "LS_ERR_BAD_STREAM", "LS_ERR_INVALID_ARGUMENT", "LS_ERR_INTERNAL"};
    for (int i = 0; i < 13; i++) {
        const char* s = ls_status_string(codes[i]);
        CHECK(s != NULL && strncmp(s, names[i], strlen(names[i])) == 0 && s[strlen(names[i])] == ':');
    }
    CHECK(strstr(ls_status_string(-99), "unknown") != NULL);
    CHECK(strstr(ls_status_string(7), "unknown") != NULL);
}

static void test_nets(const char* data_dir) {
    ls_net* net = (ls_net*)&SENTINEL; /* must stay untouched on failure */
    ls_net* const untouched = net;
    char path[4096];

    /* Loading: NULLs, a missing file, an unknown extension, a malformed
     * file, a non-manifold mesh, a degenerate triangle, a NaN. */
    EXPECT(ls_net_load(NULL, &net), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_load("x.off", NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_load("/nonexistent/mesh.off", &net), LS_ERR_IO);
    CHECK(strstr(ls_last_error(), "/nonexistent/mesh.off") != NULL);
    CHECK(strncmp(ls_last_error(), "ls_net_load:", 12) == 0);
    EXPECT(ls_net_load(write_file("api_test.xyz", "nothing"), &net), LS_ERR_IO);
    EXPECT(ls_net_load(write_file("api_test_bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 zero\n3 0 1 2\n"), &net),
           LS_ERR_PARSE);
    CHECK(strstr(ls_last_error(), "api_test_bad.off") != NULL && strstr(ls_last_error(), "5") != NULL);
    EXPECT(ls_net_load(write_file("api_test_trunc.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n"), &net), LS_ERR_PARSE);
    /* Three triangles on one edge. */
    EXPECT(ls_net_load(write_file("api_test_nm.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n"
                                                     "3 0 1 2\n3 1 0 3\n3 0 1 4\n"),
                       &net),
           LS_ERR_NON_MANIFOLD);
    CHECK(strstr(ls_last_error(), "non-manifold edge") != NULL);
    EXPECT(ls_net_load(write_file("api_test_flat.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n"), &net),
           LS_ERR_DEGENERATE);
    CHECK(strstr(ls_last_error(), "triangle 0") != NULL);
    CHECK(net == untouched);

    /* From arrays. */
    const double nan_xyz[] = {0, 0, 0, 1, 0, 0, 0, NAN, 0};
    const double tri_xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const int32_t one[] = {0, 1, 2}, bad_index[] = {0, 1, 3}, negative[] = {0, -1, 2}, repeated[] = {0, 1, 1};
    EXPECT(ls_net_from_arrays(3, NULL, 1, one, &net), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_from_arrays(3, tri_xyz, 1, NULL, &net), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_from_arrays(3, tri_xyz, 1, one, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_from_arrays(3, tri_xyz, 1, bad_index, &net), LS_ERR_INDEX_OUT_OF_RANGE);
    CHECK(strstr(ls_last_error(), "triangle 0") != NULL && strstr(ls_last_error(), "3") != NULL);
    EXPECT(ls_net_from_arrays(3, tri_xyz, 1, negative, &net), LS_ERR_INDEX_OUT_OF_RANGE);
    EXPECT(ls_net_from_arrays(3, tri_xyz, 1, repeated, &net), LS_ERR_DEGENERATE);
    EXPECT(ls_net_from_arrays(3, nan_xyz, 1, one, &net), LS_ERR_NOT_FINITE);
    CHECK(strstr(ls_last_error(), "vertex 2") != NULL);
    EXPECT(ls_net_from_arrays(0, tri_xyz, 0, one, &net), LS_ERR_DEGENERATE);
    EXPECT(ls_net_from_arrays(SIZE_MAX / 2, tri_xyz, 1, one, &net), LS_ERR_INVALID_ARGUMENT);
    CHECK(net == untouched);
    EXPECT(ls_net_from_arrays(3, tri_xyz, 1, one, &net), LS_OK);
    CHECK(net != untouched && net != NULL);
    ls_net_free(net);

    /* Tagging and counts on the octahedron. */
    EXPECT(ls_net_from_arrays(6, OCTA_XYZ, 8, OCTA_TRIS, &net), LS_OK);
    size_t nv = 7, nt = 7, nh = 7;
    EXPECT(ls_net_counts(NULL, &nv, &nt, &nh), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_counts(net, &nv, &nt, &nh), LS_OK);
    CHECK(nv == 6 && nt == 8 && nh == 0);
    EXPECT(ls_net_counts(net, NULL, NULL, NULL), LS_OK);
    EXPECT(ls_net_tag_edge(NULL, 0, 2), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_tag_edge(net, 0, 6), LS_ERR_INDEX_OUT_OF_RANGE);
    EXPECT(ls_net_tag_edge(net, -1, 2), LS_ERR_INDEX_OUT_OF_RANGE);
    EXPECT(ls_net_tag_edge(net, 0, 1), LS_ERR_INVALID_ARGUMENT); /* opposite vertices */
    CHECK(strstr(ls_last_error(), "(0, 1)") != NULL);
    EXPECT(ls_net_tag_edge(net, 0, 2), LS_OK);
    EXPECT(ls_net_tag_edge(net, 2, 0), LS_OK); /* already hard: fine */
    EXPECT(ls_net_tag_vertex(NULL, 0), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_tag_vertex(net, 6), LS_ERR_INDEX_OUT_OF_RANGE);
    EXPECT(ls_net_tag_vertex(net, 5), LS_OK);
    size_t ntagged = 77;
    EXPECT(ls_net_tag_by_angle(NULL, 30, &ntagged), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_tag_by_angle(net, NAN, &ntagged), LS_ERR_NOT_FINITE);
    EXPECT(ls_net_tag_by_angle(net, -5, &ntagged), LS_ERR_INVALID_ARGUMENT);
    CHECK(ntagged == 77);
    EXPECT(ls_net_tag_by_angle(net, 60, &ntagged), LS_OK); /* octahedron dihedral turn: 70.5° */
    CHECK(ntagged == 11);                                   /* 12 edges, one tagged already */
    EXPECT(ls_net_tag_by_angle(net, 60, NULL), LS_OK);
    EXPECT(ls_net_counts(net, &nv, &nt, &nh), LS_OK);
    CHECK(nh == 12);
    size_t npairs = 0;
    int32_t* pairs = NULL;
    EXPECT(ls_net_hard_edges(NULL, &npairs, &pairs), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_hard_edges(net, NULL, &pairs), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_hard_edges(net, &npairs, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_hard_edges(net, &npairs, &pairs), LS_OK);
    CHECK(npairs == 12);
    for (size_t i = 0; i < npairs; i++) CHECK(pairs[2 * i] < pairs[2 * i + 1] && pairs[2 * i + 1] < 6);
    ls_free_array(pairs);
    ls_net_free(net);
    ls_net_free(NULL);

    /* A real mesh with boundaries. */
    snprintf(path, sizeof path, "%s/pig.off", data_dir);
    EXPECT(ls_net_load(path, &net), LS_OK);
    EXPECT(ls_net_counts(net, &nv, &nt, &nh), LS_OK);
    CHECK(nv == 468 && nt == 891 && nh == 55); /* its 7 boundary loops are hard */
    /* Its net folds back at one edge: the needle 534 against 535. */
    size_t nfolds = 99;
    int32_t *fold_edges = NULL, *fold_tris = NULL;
    double* turns = NULL;
    EXPECT(ls_net_folds(NULL, 150, &nfolds, &fold_edges, &fold_tris, &turns), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_folds(net, 150, &nfolds, &fold_edges, NULL, &turns), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_folds(net, 181, &nfolds, &fold_edges, &fold_tris, &turns), LS_ERR_INVALID_ARGUMENT);
    EXPECT(ls_net_folds(net, 150, &nfolds, &fold_edges, &fold_tris, &turns), LS_OK);
    CHECK(nfolds == 1 && fold_edges[0] == 332 && fold_edges[1] == 343);
    CHECK(fold_tris[0] + fold_tris[1] == 534 + 535 && turns[0] > 178.7 && turns[0] < 178.9);
    ls_free_array(fold_edges);
    ls_free_array(fold_tris);
    ls_free_array(turns);
    /* Its limit surface folds over itself in two patches (tests/folds.rs
       checks them against the refined net). */
    ls_surface* surface = NULL;
    EXPECT(ls_surface_build(net, &surface), LS_OK);
    size_t nfolded = 99;
    int32_t* folded = NULL;
    EXPECT(ls_surface_folded_patches(NULL, &nfolded, &folded), LS_ERR_NULL_POINTER);
    EXPECT(ls_surface_folded_patches(surface, NULL, &folded), LS_ERR_NULL_POINTER);
    EXPECT(ls_surface_folded_patches(surface, &nfolded, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_surface_folded_patches(surface, &nfolded, &folded), LS_OK);
    CHECK(nfolded == 2 && folded[0] == 43 && folded[1] == 46);
    ls_free_array(folded);
    ls_surface_free(surface);
    ls_net_free(net);
}

/* Repairs of dirty files: refused plainly, loaded with the flag that names
   the problem, and every change reported. */
static void test_repairs(const char* data_dir) {
    ls_net* net = NULL;
    char path[4096], report[256];
    size_t nv, nt, needed = 0;

    /* The octahedron with two triangles turned. */
    const char* shuffled = write_file("api_shuffled.off",
                                      "OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n"
                                      "3 0 4 2\n3 2 1 4\n3 1 3 4\n3 3 0 4\n"
                                      "3 2 0 5\n3 2 1 5\n3 3 1 5\n3 0 3 5\n");
    EXPECT(ls_net_load(shuffled, &net), LS_ERR_NON_MANIFOLD);
    CHECK(strstr(ls_last_error(), "LS_LOAD_ORIENT") != NULL);
    EXPECT(ls_net_load_with(shuffled, 64, 0.0, &net), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "unknown bits 0x40") != NULL);
    EXPECT(ls_net_load_with(shuffled, LS_LOAD_WELD, -1.0, &net), LS_ERR_INVALID_ARGUMENT);
    EXPECT(ls_net_load_with(shuffled, LS_LOAD_ORIENT, 0.0, &net), LS_OK);
    EXPECT(ls_net_repair_report(net, NULL, 0, &needed), LS_OK);
    EXPECT(ls_net_repair_report(net, report, sizeof report, NULL), LS_OK);
    CHECK(needed == strlen(report) + 1);
    CHECK(strcmp(report,
                 "orient: flipped 2 of the 8 triangles of the piece of triangle 0 (closed: now facing outward)") == 0);
    /* Truncated to the buffer, still terminated. */
    EXPECT(ls_net_repair_report(net, report, 7, NULL), LS_OK);
    CHECK(strcmp(report, "orient") == 0);
    EXPECT(ls_net_repair_report(net, NULL, 7, NULL), LS_ERR_NULL_POINTER);
    /* The repaired octahedron is the outward one: its surface evaluates
       with outward normals. */
    ls_surface* surface = NULL;
    EXPECT(ls_surface_build(net, &surface), LS_OK);
    double n[3], r[18];
    for (int t = 0; t < 8; t++) {
        EXPECT(ls_evaluate(surface, t, 0.25, 0.25, r), LS_OK);
        EXPECT(ls_normal(surface, t, 0.25, 0.25, n), LS_OK);
        CHECK(n[0] * r[0] + n[1] * r[1] + n[2] * r[2] > 0);
    }
    ls_surface_free(surface);
    ls_net_free(net);

    /* A plain net reports nothing. */
    snprintf(path, sizeof path, "%s/pig.off", data_dir);
    EXPECT(ls_net_load_with(path, LS_LOAD_REPAIR, 0.0, &net), LS_OK);
    EXPECT(ls_net_repair_report(net, report, sizeof report, &needed), LS_OK);
    CHECK(needed == 1 && report[0] == '\0');
    ls_net_free(net);

    /* pig.stl joins two fans at vertex 90; the split appends a vertex. */
    snprintf(path, sizeof path, "%s/pig.stl", data_dir);
    EXPECT(ls_net_load(path, &net), LS_ERR_NON_MANIFOLD);
    CHECK(strstr(ls_last_error(), "vertex 90") != NULL);
    EXPECT(ls_net_load_with(path, LS_LOAD_SPLIT_NONMANIFOLD, 0.0, &net), LS_OK);
    EXPECT(ls_net_counts(net, &nv, &nt, NULL), LS_OK);
    CHECK(nt == 16848);
    EXPECT(ls_net_repair_report(net, report, sizeof report, NULL), LS_OK);
    CHECK(strncmp(report, "split-nonmanifold:", 18) == 0 && strstr(report, "90 ") != NULL);
    ls_net_free(net);

    /* CGAL's mpi.off has non-convex polygons: split by ear clipping. */
    snprintf(path, sizeof path, "%s/mpi.off", data_dir);
    EXPECT(ls_net_load(path, &net), LS_ERR_PARSE);
    EXPECT(ls_net_load_with(path, LS_LOAD_TRIANGULATE, 0.0, &net), LS_OK);
    EXPECT(ls_net_counts(net, &nv, &nt, NULL), LS_OK);
    CHECK(nv == 90 && nt == 180);
    ls_net_free(net);
}

static void test_queries(void) {
    ls_net* net = NULL;
    ls_surface* surface = octahedron(&net);
    double r[18], many[4 * 18], k[8], n[3];
    for (int i = 0; i < 18; i++) r[i] = SENTINEL;
    for (int i = 0; i < 8; i++) k[i] = SENTINEL;

    EXPECT(ls_surface_build(NULL, &surface), LS_ERR_NULL_POINTER);
    EXPECT(ls_surface_build(net, NULL), LS_ERR_NULL_POINTER);
    size_t nt = 0;
    EXPECT(ls_surface_num_triangles(NULL, &nt), LS_ERR_NULL_POINTER);
    EXPECT(ls_surface_num_triangles(surface, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_surface_num_triangles(surface, &nt), LS_OK);
    CHECK(nt == 8);

    /* Evaluation errors leave the result untouched. */
    EXPECT(ls_evaluate(NULL, 0, 0.1, 0.1, r), LS_ERR_NULL_POINTER);
    EXPECT(ls_evaluate(surface, 0, 0.1, 0.1, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_evaluate(surface, 8, 0.1, 0.1, r), LS_ERR_INDEX_OUT_OF_RANGE);
    CHECK(strstr(ls_last_error(), "triangle 8") != NULL);
    EXPECT(ls_evaluate(surface, -1, 0.1, 0.1, r), LS_ERR_INDEX_OUT_OF_RANGE);
    EXPECT(ls_evaluate(surface, 0, -0.01, 0.1, r), LS_ERR_PARAMETER_OUT_OF_RANGE);
    EXPECT(ls_evaluate(surface, 0, 0.1, -0.01, r), LS_ERR_PARAMETER_OUT_OF_RANGE);
    EXPECT(ls_evaluate(surface, 0, 0.6, 0.5, r), LS_ERR_PARAMETER_OUT_OF_RANGE);
    CHECK(strstr(ls_last_error(), "outside the triangle") != NULL);
    EXPECT(ls_evaluate(surface, 0, NAN, 0.1, r), LS_ERR_NOT_FINITE);
    EXPECT(ls_evaluate(surface, 0, 0.1, INFINITY, r), LS_ERR_NOT_FINITE);
    for (int i = 0; i < 18; i++) CHECK(r[i] == SENTINEL);
    EXPECT(ls_evaluate(surface, 0, -1e-14, 1.0 + 1e-14, r), LS_OK); /* round-off is clamped */

    /* Batch equals one by one, bit for bit; a bad query names its index. */
    const int32_t tris[4] = {0, 3, 5, 7};
    const double vw[8] = {0.1, 0.2, 0.3, 0.3, 0, 0, 0.5, 0.5};
    EXPECT(ls_evaluate_many(surface, 4, tris, vw, many), LS_OK);
    for (int i = 0; i < 4; i++) {
        EXPECT(ls_evaluate(surface, tris[i], vw[2 * i], vw[2 * i + 1], r), LS_OK);
        CHECK(memcmp(r, many + 18 * i, sizeof r) == 0);
    }
    EXPECT(ls_evaluate_many(surface, 0, NULL, NULL, NULL), LS_OK);
    EXPECT(ls_evaluate_many(NULL, 4, tris, vw, many), LS_ERR_NULL_POINTER);
    EXPECT(ls_evaluate_many(surface, 4, NULL, vw, many), LS_ERR_NULL_POINTER);
    EXPECT(ls_evaluate_many(surface, 4, tris, NULL, many), LS_ERR_NULL_POINTER);
    EXPECT(ls_evaluate_many(surface, 4, tris, vw, NULL), LS_ERR_NULL_POINTER);
    const int32_t bad_tris[4] = {0, 3, 99, 7};
    for (int i = 0; i < 4 * 18; i++) many[i] = SENTINEL;
    EXPECT(ls_evaluate_many(surface, 4, bad_tris, vw, many), LS_ERR_INDEX_OUT_OF_RANGE);
    CHECK(strstr(ls_last_error(), "query 2") != NULL);
    for (int i = 0; i < 4 * 18; i++) CHECK(many[i] == SENTINEL);

    /* Normal: unit, along Xv x Xw; curvature: convex surface, k1 >= k2 > 0. */
    EXPECT(ls_normal(NULL, 0, 0.2, 0.2, n), LS_ERR_NULL_POINTER);
    EXPECT(ls_normal(surface, 0, 0.2, 0.2, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_normal(surface, 9, 0.2, 0.2, n), LS_ERR_INDEX_OUT_OF_RANGE);
    EXPECT(ls_normal(surface, 0, 0.2, NAN, n), LS_ERR_NOT_FINITE);
    EXPECT(ls_normal(surface, 0, 0.2, 0.2, n), LS_OK);
    EXPECT(ls_evaluate(surface, 0, 0.2, 0.2, r), LS_OK);
    double c[3] = {r[4] * r[8] - r[5] * r[7], r[5] * r[6] - r[3] * r[8], r[3] * r[7] - r[4] * r[6]};
    double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    CHECK(fabs(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1) < 1e-14);
    for (int i = 0; i < 3; i++) CHECK(fabs(n[i] - c[i] / len) < 1e-14);
    CHECK(n[0] * r[0] + n[1] * r[1] + n[2] * r[2] > 0); /* outward */
    EXPECT(ls_normal(surface, 0, 0, 0, n), LS_OK);      /* exactly at a valence-4 vertex */
    EXPECT(ls_curvature(NULL, 0, 0.2, 0.2, k), LS_ERR_NULL_POINTER);
    EXPECT(ls_curvature(surface, 0, 0.2, 0.2, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_curvature(surface, 0, 0.7, 0.7, k), LS_ERR_PARAMETER_OUT_OF_RANGE);
    for (int i = 0; i < 8; i++) CHECK(k[i] == SENTINEL);
    EXPECT(ls_curvature(surface, 0, 0.2, 0.2, k), LS_OK);
    CHECK(k[0] >= k[4] && k[4] > 0);

    /* Snapping: a surface point snaps onto itself; a far point's answer is
     * consistent; a guess gives the same global answer. */
    int32_t tri = -7;
    double uv[2] = {SENTINEL, SENTINEL}, x[3], d = SENTINEL;
    const double p[3] = {r[0], r[1], r[2]};
    EXPECT(ls_snap(NULL, p, &tri, uv, x, &d), LS_ERR_NULL_POINTER);
    EXPECT(ls_snap(surface, NULL, &tri, uv, x, &d), LS_ERR_NULL_POINTER);
    EXPECT(ls_snap(surface, p, NULL, uv, x, &d), LS_ERR_NULL_POINTER);
    EXPECT(ls_snap(surface, p, &tri, NULL, x, &d), LS_ERR_NULL_POINTER);
    EXPECT(ls_snap(surface, p, &tri, uv, NULL, &d), LS_ERR_NULL_POINTER);
    EXPECT(ls_snap(surface, p, &tri, uv, x, NULL), LS_ERR_NULL_POINTER);
    const double nan_point[3] = {0, NAN, 0};
    EXPECT(ls_snap(surface, nan_point, &tri, uv, x, &d), LS_ERR_NOT_FINITE);
    CHECK(tri == -7 && uv[0] == SENTINEL && d == SENTINEL);
    EXPECT(ls_snap(surface, p, &tri, uv, x, &d), LS_OK);
    CHECK(d < 1e-14 && tri >= 0 && tri < 8);
    const double far[3] = {10, 20, 30};
    EXPECT(ls_snap(surface, far, &tri, uv, x, &d), LS_OK);
    EXPECT(ls_evaluate(surface, tri, uv[0], uv[1], r), LS_OK);
    CHECK(memcmp(r, x, sizeof x) == 0);
    CHECK(fabs(d - sqrt((x[0] - 10) * (x[0] - 10) + (x[1] - 20) * (x[1] - 20) + (x[2] - 30) * (x[2] - 30))) < 1e-12);
    int32_t tri2;
    double uv2[2], x2[3], d2;
    const double guess[2] = {0.3, 0.3};
    EXPECT(ls_snap_guess(surface, far, 2, guess, &tri2, uv2, x2, &d2), LS_OK);
    CHECK(fabs(d2 - d) < 1e-12);
    EXPECT(ls_snap_guess(NULL, far, 2, guess, &tri2, uv2, x2, &d2), LS_ERR_NULL_POINTER);
    EXPECT(ls_snap_guess(surface, far, 2, NULL, &tri2, uv2, x2, &d2), LS_ERR_NULL_POINTER);
    EXPECT(ls_snap_guess(surface, far, 8, guess, &tri2, uv2, x2, &d2), LS_ERR_INDEX_OUT_OF_RANGE);
    const double bad_guess[2] = {0.9, 0.9};
    EXPECT(ls_snap_guess(surface, far, 2, bad_guess, &tri2, uv2, x2, &d2), LS_ERR_PARAMETER_OUT_OF_RANGE);

    /* The certified snap: the same answer as ls_snap with its certificate;
     * a looser tolerance is honoured; options may be NULL; a bad tolerance
     * or a struct from an older caller is refused, the result untouched. */
    ls_snap_options opts;
    EXPECT(ls_snap_options_default(NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_snap_options_default(&opts), LS_OK);
    CHECK(opts.struct_size == sizeof opts && opts.tolerance == 1e-12);
    ls_snap_result res;
    memset(&res, 0, sizeof res);
    res.struct_size = sizeof res;
    EXPECT(ls_snap_certified(surface, far, &opts, &res), LS_OK);
    CHECK(res.tri == tri && res.vw[0] == uv[0] && res.vw[1] == uv[1] && res.distance == d);
    CHECK(memcmp(res.xyz, x, sizeof x) == 0);
    CHECK(res.lower_bound <= res.distance && res.distance - res.lower_bound <= 1e-12 * 4); /* diagonal < 4 */
    EXPECT(ls_snap_certified(surface, far, NULL, &res), LS_OK);
    CHECK(res.distance == d && res.distance - res.lower_bound <= 1e-12 * 4);
    opts.tolerance = 1e-6;
    EXPECT(ls_snap_certified(surface, far, &opts, &res), LS_OK);
    CHECK(res.lower_bound <= d + 1e-15 && res.distance - res.lower_bound <= 1e-6 * 4);
    const double bad_tolerances[4] = {0, -1, 1, NAN};
    for (int i = 0; i < 4; i++) {
        opts.tolerance = bad_tolerances[i];
        res.distance = SENTINEL;
        EXPECT(ls_snap_certified(surface, far, &opts, &res), LS_ERR_INVALID_ARGUMENT);
        CHECK(res.distance == SENTINEL && strstr(ls_last_error(), "tolerance") != NULL);
    }
    EXPECT(ls_snap_options_default(&opts), LS_OK);
    opts.struct_size = 4;
    EXPECT(ls_snap_certified(surface, far, &opts, &res), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "struct_size") != NULL && res.distance == SENTINEL);
    EXPECT(ls_snap_options_default(&opts), LS_OK);
    res.struct_size = 8;
    EXPECT(ls_snap_certified(surface, far, &opts, &res), LS_ERR_INVALID_ARGUMENT);
    res.struct_size = sizeof res;
    EXPECT(ls_snap_certified(NULL, far, &opts, &res), LS_ERR_NULL_POINTER);
    EXPECT(ls_snap_certified(surface, NULL, &opts, &res), LS_ERR_NULL_POINTER);
    EXPECT(ls_snap_certified(surface, far, &opts, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_snap_certified(surface, nan_point, &opts, &res), LS_ERR_NOT_FINITE);
    CHECK(res.distance == SENTINEL);

    /* Local projection: a point near the surface from a nearby guess lands
     * on the same point as the global snap; bad input is refused and the
     * outputs stay untouched. */
    const double near_point[3] = {x[0] * 1.001, x[1] * 1.001, x[2] * 1.001};
    int32_t ptri = -7;
    double pvw[2] = {SENTINEL, SENTINEL}, px[3], pd = SENTINEL;
    EXPECT(ls_snap(surface, near_point, &tri2, uv2, x2, &d2), LS_OK);
    EXPECT(ls_project(surface, near_point, tri, uv, &ptri, pvw, px, &pd), LS_OK);
    CHECK(fabs(pd - d2) < 1e-13);
    EXPECT(ls_evaluate(surface, ptri, pvw[0], pvw[1], r), LS_OK);
    CHECK(memcmp(r, px, sizeof px) == 0);
    ptri = -7;
    pd = SENTINEL;
    pvw[0] = pvw[1] = px[0] = px[1] = px[2] = SENTINEL;
    EXPECT(ls_project(NULL, near_point, tri, uv, &ptri, pvw, px, &pd), LS_ERR_NULL_POINTER);
    EXPECT(ls_project(surface, NULL, tri, uv, &ptri, pvw, px, &pd), LS_ERR_NULL_POINTER);
    EXPECT(ls_project(surface, near_point, tri, NULL, &ptri, pvw, px, &pd), LS_ERR_NULL_POINTER);
    EXPECT(ls_project(surface, near_point, tri, uv, NULL, pvw, px, &pd), LS_ERR_NULL_POINTER);
    EXPECT(ls_project(surface, near_point, tri, uv, &ptri, pvw, px, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_project(surface, near_point, 8, uv, &ptri, pvw, px, &pd), LS_ERR_INDEX_OUT_OF_RANGE);
    EXPECT(ls_project(surface, near_point, -1, uv, &ptri, pvw, px, &pd), LS_ERR_INDEX_OUT_OF_RANGE);
    EXPECT(ls_project(surface, near_point, tri, bad_guess, &ptri, pvw, px, &pd), LS_ERR_PARAMETER_OUT_OF_RANGE);
    EXPECT(ls_project(surface, nan_point, tri, uv, &ptri, pvw, px, &pd), LS_ERR_NOT_FINITE);
    CHECK(strstr(ls_last_error(), "ls_project") != NULL);
    CHECK(ptri == -7 && pd == SENTINEL && pvw[0] == SENTINEL && pvw[1] == SENTINEL);
    CHECK(px[0] == SENTINEL && px[1] == SENTINEL && px[2] == SENTINEL);

    /* Interpolating surfaces pass through the original points. */
    ls_surface* through = NULL;
    EXPECT(ls_surface_build_interpolating(NULL, LS_INTERPOLATE_SOLVE, &through), LS_ERR_NULL_POINTER);
    EXPECT(ls_surface_build_interpolating(net, LS_INTERPOLATE_SOLVE, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_surface_build_interpolating(net, 0, &through), LS_ERR_INVALID_ARGUMENT);
    CHECK(through == NULL);
    for (int mode = LS_INTERPOLATE_SOLVE; mode <= LS_INTERPOLATE_DISPLACEMENT; mode++) {
        EXPECT(ls_surface_build_interpolating(net, mode, &through), LS_OK);
        EXPECT(ls_evaluate(through, 0, 0, 0, r), LS_OK); /* corner 0 of triangle 0 is vertex 0 */
        for (int i = 0; i < 3; i++) CHECK(fabs(r[i] - OCTA_XYZ[i]) < 1e-14);
        ls_surface_free(through);
    }
    ls_surface_free(surface);
    ls_surface_free(NULL);
    ls_net_free(net);
}

static void test_refine(void) {
    ls_surface* surface = octahedron(NULL);
    size_t nv = 0, nt = 0;
    double* xyz = (double*)&SENTINEL;
    int32_t* tris = NULL;
    EXPECT(ls_refine(NULL, 1, 0, &nv, &xyz, &nt, &tris), LS_ERR_NULL_POINTER);
    EXPECT(ls_refine(surface, 1, 0, NULL, &xyz, &nt, &tris), LS_ERR_NULL_POINTER);
    EXPECT(ls_refine(surface, 1, 0, &nv, NULL, &nt, &tris), LS_ERR_NULL_POINTER);
    EXPECT(ls_refine(surface, 1, 0, &nv, &xyz, NULL, &tris), LS_ERR_NULL_POINTER);
    EXPECT(ls_refine(surface, 1, 0, &nv, &xyz, &nt, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_refine(surface, -1, 0, &nv, &xyz, &nt, &tris), LS_ERR_INVALID_ARGUMENT);
    EXPECT(ls_refine(surface, 13, 0, &nv, &xyz, &nt, &tris), LS_ERR_INVALID_ARGUMENT);
    CHECK(xyz == (double*)&SENTINEL && nv == 0);
    EXPECT(ls_refine(surface, 2, 0, &nv, &xyz, &nt, &tris), LS_OK);
    CHECK(nt == 8 * 16 && nv == 66 && euler(nv, tris, nt) == 2); /* closed, genus 0 */
    for (size_t i = 0; i < 3 * nt; i++) CHECK(tris[i] >= 0 && (size_t)tris[i] < nv);
    /* Level 0 is the net itself, bit for bit and in file order. */
    double* net_xyz = NULL;
    int32_t* net_tris = NULL;
    size_t nv0 = 0, nt0 = 0;
    EXPECT(ls_refine(surface, 0, 0, &nv0, &net_xyz, &nt0, &net_tris), LS_OK);
    CHECK(nv0 == 6 && nt0 == 8 && memcmp(net_xyz, OCTA_XYZ, sizeof OCTA_XYZ) == 0 &&
          memcmp(net_tris, OCTA_TRIS, sizeof OCTA_TRIS) == 0);
    ls_free_array(net_xyz);
    ls_free_array(net_tris);
    /* The limit push moves every vertex inwards. */
    double* limit = NULL;
    int32_t* limit_tris = NULL;
    size_t lnv = 0, lnt = 0;
    EXPECT(ls_refine(surface, 2, 1, &lnv, &limit, &lnt, &limit_tris), LS_OK);
    CHECK(lnv == nv && lnt == nt && memcmp(tris, limit_tris, 3 * nt * sizeof(int32_t)) == 0);
    for (size_t i = 0; i < nv; i++) {
        double a = sqrt(xyz[3 * i] * xyz[3 * i] + xyz[3 * i + 1] * xyz[3 * i + 1] + xyz[3 * i + 2] * xyz[3 * i + 2]);
        double b = sqrt(limit[3 * i] * limit[3 * i] + limit[3 * i + 1] * limit[3 * i + 1] +
                        limit[3 * i + 2] * limit[3 * i + 2]);
        CHECK(b < a);
    }
    /* A limit point is the surface: vertex 0 is corner 0 of triangle 0. */
    double r[18];
    EXPECT(ls_evaluate(surface, 0, 0, 0, r), LS_OK);
    for (int i = 0; i < 3; i++) CHECK(fabs(r[i] - limit[i]) < 1e-15);
    /* Origins: refined vertex i is the surface at (tri[i], vw[i]). */
    size_t no = 0;
    int32_t* otri = NULL;
    double* ovw = NULL;
    EXPECT(ls_refine_origins(NULL, 2, &no, &otri, &ovw), LS_ERR_NULL_POINTER);
    EXPECT(ls_refine_origins(surface, 2, NULL, &otri, &ovw), LS_ERR_NULL_POINTER);
    EXPECT(ls_refine_origins(surface, 2, &no, NULL, &ovw), LS_ERR_NULL_POINTER);
    EXPECT(ls_refine_origins(surface, 2, &no, &otri, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_refine_origins(surface, -2, &no, &otri, &ovw), LS_ERR_INVALID_ARGUMENT);
    EXPECT(ls_refine_origins(surface, 2, &no, &otri, &ovw), LS_OK);
    CHECK(no == nv);
    for (size_t i = 0; i < no; i++) {
        EXPECT(ls_evaluate(surface, otri[i], ovw[2 * i], ovw[2 * i + 1], r), LS_OK);
        for (int k = 0; k < 3; k++) CHECK(fabs(r[k] - limit[3 * i + k]) < 1e-14);
    }
    ls_free_array(otri);
    ls_free_array(ovw);
    ls_free_array(xyz);
    ls_free_array(tris);
    ls_free_array(limit);
    ls_free_array(limit_tris);
    ls_free_array(NULL);
    ls_surface_free(surface);
}

/* A straight mesh's arrays, borrowed from its ls_trimesh (valid until
 * ls_trimesh_free). */
typedef struct {
    size_t nv, nt;
    const double *xyz, *vw;
    const int32_t *tris, *vtri;
} mesh_view;

static mesh_view view(const ls_trimesh* mesh) {
    mesh_view m = {0, 0, NULL, NULL, NULL, NULL};
    size_t per = 0;
    EXPECT(ls_trimesh_counts(mesh, &m.nv, &m.nt, &per), LS_OK);
    CHECK(per == 3);
    EXPECT(ls_trimesh_xyz(mesh, &m.xyz), LS_OK);
    EXPECT(ls_trimesh_elements(mesh, &m.tris), LS_OK);
    EXPECT(ls_trimesh_node_params(mesh, &m.vtri, &m.vw), LS_OK);
    return m;
}

/* ls_mesh: every vertex is the surface at its parameters, every triangle's
 * corners are the surface at their chart parameters, the closed octahedron
 * gives a closed mesh (V - E + F = 2), and bad options fail cleanly, each
 * naming its field, with the output untouched. */
static void test_mesh(void) {
    ls_surface* surface = octahedron(NULL);
    double r[18];
    ls_mesh_options o;
    EXPECT(ls_mesh_options_default(&o), LS_OK);
    CHECK(o.struct_size == sizeof o && o.uniform == 0 && o.size == 0 && o.tolerance == 1e-3 && o.adapt_curvature == 1);
    CHECK(o.max_triangles == 200000000);
    o.uniform = 3;
    o.tolerance = 0;
    o.adapt_curvature = 0;
    ls_trimesh* mesh = NULL;
    EXPECT(ls_mesh(surface, &o, &mesh), LS_OK);
    mesh_view m = view(mesh);
    CHECK(m.nt == 8 * 9);
    CHECK(m.nv == 6 + 12 * 2 + 8 * 1);
    CHECK(euler(m.nv, m.tris, m.nt) == 2);
    for (size_t i = 0; i < m.nv; i++) {
        EXPECT(ls_evaluate(surface, m.vtri[i], m.vw[2 * i], m.vw[2 * i + 1], r), LS_OK);
        for (int k = 0; k < 3; k++) CHECK(fabs(r[k] - m.xyz[3 * i + k]) < 1e-13);
    }
    const int32_t *chart = NULL, *face = NULL;
    const double* tvw = NULL;
    EXPECT(ls_trimesh_element_charts(mesh, &chart, &tvw), LS_OK);
    EXPECT(ls_trimesh_element_faces(mesh, &face), LS_OK);
    for (size_t t = 0; t < m.nt; t++) {
        CHECK(face[t] == 0); /* one face: no hard edges */
        for (int c = 0; c < 3; c++) {
            int32_t v = m.tris[3 * t + c];
            EXPECT(ls_evaluate(surface, chart[t], tvw[6 * t + 2 * c], tvw[6 * t + 2 * c + 1], r), LS_OK);
            for (int k = 0; k < 3; k++) CHECK(fabs(r[k] - m.xyz[3 * v + k]) < 1e-13);
        }
    }
    /* Measures the chart mesher does not take are refused by name. */
    double dev = SENTINEL;
    EXPECT(ls_trimesh_deviation(mesh, &dev), LS_ERR_UNSUPPORTED);
    CHECK(strstr(ls_last_error(), "ls_trimesh_deviation") != NULL && dev == SENTINEL);
    EXPECT(ls_trimesh_largest_move(mesh, &dev), LS_ERR_UNSUPPORTED);
    EXPECT(ls_trimesh_min_scaled_jacobian(mesh, &dev), LS_ERR_UNSUPPORTED);
    CHECK(dev == SENTINEL);
    EXPECT(ls_trimesh_xyz(NULL, &m.xyz), LS_ERR_NULL_POINTER);
    EXPECT(ls_trimesh_xyz(mesh, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_trimesh_counts(mesh, &m.nv, NULL, &m.nt), LS_ERR_NULL_POINTER);
    ls_trimesh_free(mesh);
    ls_trimesh_free(NULL);

    /* NULL options: the defaults, tolerance-driven and adaptive. */
    mesh = NULL;
    EXPECT(ls_mesh(surface, NULL, &mesh), LS_OK);
    m = view(mesh);
    CHECK(m.nt > 8 && euler(m.nv, m.tris, m.nt) == 2);
    ls_trimesh_free(mesh);

    /* Refusals, each naming its field; the output untouched. */
    ls_trimesh* const untouched = (ls_trimesh*)&SENTINEL;
    mesh = untouched;
    ls_mesh_options bad;
    EXPECT(ls_mesh(NULL, &o, &mesh), LS_ERR_NULL_POINTER);
    EXPECT(ls_mesh(surface, &o, NULL), LS_ERR_NULL_POINTER);
    struct {
        int uniform;
        double size, tolerance;
        int adapt;
        size_t max_triangles;
        int status;
        const char* name;
    } cases[] = {
        {-1, 0, 0, 0, 100, LS_ERR_INVALID_ARGUMENT, "uniform"},
        {2, 0.1, 0, 0, 100, LS_ERR_INVALID_ARGUMENT, "size"},
        {0, 0, 2.0, 0, 100, LS_ERR_INVALID_ARGUMENT, "tolerance"},
        {0, 0, NAN, 0, 100, LS_ERR_INVALID_ARGUMENT, "tolerance"},
        {0, 0, 0, 0, 100, LS_ERR_INVALID_ARGUMENT, "tolerance"},
        {2, 0, 0, 2, 100, LS_ERR_INVALID_ARGUMENT, "adapt_curvature"},
        {2, 0, 0, 0, 0, LS_ERR_INVALID_ARGUMENT, "max_triangles"},
        /* 8 * 10^2 triangles over a budget of 100: refused before meshing. */
        {10, 0, 0, 0, 100, LS_ERR_OVER_BUDGET, "over the limit of 100"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        EXPECT(ls_mesh_options_default(&bad), LS_OK);
        bad.uniform = cases[i].uniform;
        bad.size = cases[i].size;
        bad.tolerance = cases[i].tolerance;
        bad.adapt_curvature = cases[i].adapt;
        bad.max_triangles = cases[i].max_triangles;
        EXPECT(ls_mesh(surface, &bad, &mesh), cases[i].status);
        CHECK(strstr(ls_last_error(), "ls_mesh: ") == ls_last_error());
        CHECK(strstr(ls_last_error(), cases[i].name) != NULL);
    }
    /* A struct_size no version of the struct had. */
    EXPECT(ls_mesh_options_default(&bad), LS_OK);
    bad.struct_size = sizeof(size_t);
    EXPECT(ls_mesh(surface, &bad, &mesh), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "struct_size") != NULL);
    EXPECT(ls_mesh_options_default(NULL), LS_ERR_NULL_POINTER);
    CHECK(mesh == untouched); /* outputs untouched on failure */
    ls_surface_free(surface);
}

/* The model labels of a mesh (ls_mesh_face_labels, ls_mesh_hard_edges) on
 * fandisk tagged at 30° (12 faces, 34 curves, 722 hard control edges):
 * every output triangle has the face of its chart; the hard output edges
 * are mesh edges, two per hard control edge at uniform 2, with curve ids in
 * range, every curve present, each curve's edges a chain in increasing t
 * from t = 0; two triangles of different faces meet only across a hard
 * edge; bad arguments fail cleanly with the outputs untouched. */
static int compare_i64(const void* a, const void* b) { return compare_edges(a, b); }

static int compare_triples(const void* a, const void* b) {
    const int64_t *x = a, *y = b;
    for (int k = 0; k < 3; k++)
        if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
    return 0;
}

/* n triangles, each rotated to start at its lowest node (its orientation
 * kept), then sorted: two lists of the same triangles become equal. */
static void canonical_triangles(int64_t* tris, size_t n) {
    for (size_t e = 0; e < n; e++) {
        int64_t* t = &tris[3 * e];
        while (t[0] > t[1] || t[0] > t[2]) {
            int64_t first = t[0];
            t[0] = t[1];
            t[1] = t[2];
            t[2] = first;
        }
    }
    qsort(tris, n, 3 * sizeof *tris, compare_triples);
}

static int64_t edge_key(int32_t a, int32_t b) {
    return a < b ? (int64_t)a << 32 | (uint32_t)b : (int64_t)b << 32 | (uint32_t)a;
}

static void test_mesh_labels(const char* data_dir) {
    char path[4096];
    snprintf(path, sizeof path, "%s/fandisk.off", data_dir);
    ls_net* net = NULL;
    ls_surface* surface = NULL;
    EXPECT(ls_net_load(path, &net), LS_OK);
    if (!net) return;
    EXPECT(ls_net_tag_by_angle(net, 30, NULL), LS_OK);
    size_t ncv = 0, nct = 0, nch = 0;
    EXPECT(ls_net_counts(net, &ncv, &nct, &nch), LS_OK);
    CHECK(nch == 722);
    EXPECT(ls_surface_build(net, &surface), LS_OK);

    /* The faces of the control triangles themselves: ids 0..11, each used. */
    int32_t* ident = malloc(nct * sizeof *ident);
    int32_t* ctrl_face = malloc(nct * sizeof *ctrl_face);
    for (size_t t = 0; t < nct; t++) ident[t] = (int32_t)t;
    EXPECT(ls_mesh_face_labels(surface, nct, ident, ctrl_face), LS_OK);
    int seen_face[12] = {0};
    for (size_t t = 0; t < nct; t++) {
        CHECK(ctrl_face[t] >= 0 && ctrl_face[t] < 12);
        if (ctrl_face[t] >= 0 && ctrl_face[t] < 12) seen_face[ctrl_face[t]] = 1;
    }
    for (int f = 0; f < 12; f++) CHECK(seen_face[f]);

    ls_mesh_options o;
    EXPECT(ls_mesh_options_default(&o), LS_OK);
    o.uniform = 2;
    o.tolerance = 0;
    o.adapt_curvature = 0;
    ls_trimesh* mesh = NULL;
    EXPECT(ls_mesh(surface, &o, &mesh), LS_OK);
    const mesh_view m = view(mesh);
    const size_t nv = m.nv, nt = m.nt;
    const double *vw = m.vw, *tvw = NULL;
    const int32_t *tris = m.tris, *vtri = m.vtri, *chart = NULL, *mesh_face = NULL;
    EXPECT(ls_trimesh_element_charts(mesh, &chart, &tvw), LS_OK);
    EXPECT(ls_trimesh_element_faces(mesh, &mesh_face), LS_OK);
    CHECK(nt == 4 * nct);
    int32_t* face = malloc(nt * sizeof *face);
    EXPECT(ls_mesh_face_labels(surface, nt, chart, face), LS_OK);
    for (size_t t = 0; t < nt; t++) CHECK(face[t] == ctrl_face[chart[t]] && mesh_face[t] == face[t]);

    size_t nh = 0;
    int32_t *pairs = NULL, *curves = NULL;
    double* ct = NULL;
    EXPECT(ls_mesh_hard_edges(surface, nv, vtri, vw, nt, tris, &nh, &pairs, &curves, &ct), LS_OK);
    CHECK(nh == 2 * nch);
    /* Mesh edges, with the face on each side, sorted by key. */
    int64_t* sides = malloc(3 * nt * sizeof *sides);
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) sides[3 * t + k] = edge_key(tris[3 * t + k], tris[3 * t + (k + 1) % 3]);
    int64_t* keys = malloc(3 * nt * sizeof *keys);
    memcpy(keys, sides, 3 * nt * sizeof *keys);
    qsort(keys, 3 * nt, sizeof *keys, compare_i64);
    int64_t* hard = malloc((nh ? nh : 1) * sizeof *hard);
    int seen_curve[34] = {0};
    for (size_t i = 0; i < nh; i++) {
        int32_t a = pairs[2 * i], b = pairs[2 * i + 1], c = curves[i];
        CHECK(a >= 0 && (size_t)a < nv && b >= 0 && (size_t)b < nv && a != b);
        hard[i] = edge_key(a, b);
        CHECK(bsearch(&hard[i], keys, 3 * nt, sizeof *keys, compare_i64) != NULL);
        CHECK(c >= 0 && c < 34);
        if (c < 0 || c >= 34) continue;
        CHECK(ct[2 * i] < ct[2 * i + 1] && ct[2 * i] >= 0);
        if (!seen_curve[c]) CHECK(ct[2 * i] == 0.0); /* a curve starts at t = 0 */
        seen_curve[c] = 1;
        if (i > 0) CHECK(curves[i - 1] <= c); /* ordered by curve */
        if (i > 0 && curves[i - 1] == c) {
            CHECK(pairs[2 * i - 1] == a); /* a chain along the curve */
            CHECK(ct[2 * i - 1] == ct[2 * i]);
        }
    }
    for (int c = 0; c < 34; c++) CHECK(seen_curve[c]);
    /* Across every soft mesh edge the face is the same on both sides. */
    qsort(hard, nh, sizeof *hard, compare_i64);
    int64_t* keyed = malloc(3 * nt * 2 * sizeof *keyed); /* (key, face) pairs */
    for (size_t i = 0; i < 3 * nt; i++) {
        keyed[2 * i] = sides[i];
        keyed[2 * i + 1] = face[i / 3];
    }
    qsort(keyed, 3 * nt, 2 * sizeof *keyed, compare_i64); /* by key only */
    size_t crossings = 0;
    for (size_t i = 0; i + 1 < 3 * nt; i++) {
        if (keyed[2 * i] != keyed[2 * i + 2] || keyed[2 * i + 1] == keyed[2 * i + 3]) continue;
        crossings++;
        CHECK(bsearch(&keyed[2 * i], hard, nh, sizeof *hard, compare_i64) != NULL);
    }
    CHECK(crossings > 0 && crossings <= nh);
    /* curve_t may be skipped. */
    size_t nh2 = 0;
    int32_t *pairs2 = NULL, *curves2 = NULL;
    EXPECT(ls_mesh_hard_edges(surface, nv, vtri, vw, nt, tris, &nh2, &pairs2, &curves2, NULL), LS_OK);
    CHECK(nh2 == nh && memcmp(pairs2, pairs, 2 * nh * sizeof *pairs) == 0);
    ls_free_array(pairs2);
    ls_free_array(curves2);
    /* An empty mesh has no hard edge. */
    EXPECT(ls_mesh_hard_edges(surface, 0, NULL, NULL, 0, NULL, &nh2, &pairs2, &curves2, NULL), LS_OK);
    CHECK(nh2 == 0);
    ls_free_array(pairs2);
    ls_free_array(curves2);
    EXPECT(ls_mesh_face_labels(surface, 0, NULL, NULL), LS_OK);

    /* Failures leave every output untouched. */
    int32_t* const untouched = (int32_t*)&SENTINEL;
    pairs2 = untouched;
    nh2 = 77;
    int32_t labels[2] = {-5, -5};
    const int32_t bad_chart[2] = {0, (int32_t)nct}, negative_chart[2] = {-1, 0};
    EXPECT(ls_mesh_face_labels(NULL, 2, ident, labels), LS_ERR_NULL_POINTER);
    EXPECT(ls_mesh_face_labels(surface, 2, NULL, labels), LS_ERR_NULL_POINTER);
    EXPECT(ls_mesh_face_labels(surface, 2, ident, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_mesh_face_labels(surface, 2, bad_chart, labels), LS_ERR_INDEX_OUT_OF_RANGE);
    CHECK(strstr(ls_last_error(), "ls_mesh_face_labels") != NULL && strstr(ls_last_error(), "triangle 1") != NULL);
    EXPECT(ls_mesh_face_labels(surface, 2, negative_chart, labels), LS_ERR_INDEX_OUT_OF_RANGE);
    CHECK(labels[0] == -5 && labels[1] == -5);
    EXPECT(ls_mesh_hard_edges(NULL, nv, vtri, vw, nt, tris, &nh2, &pairs2, &curves2, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_mesh_hard_edges(surface, nv, NULL, vw, nt, tris, &nh2, &pairs2, &curves2, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_mesh_hard_edges(surface, nv, vtri, vw, nt, NULL, &nh2, &pairs2, &curves2, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_mesh_hard_edges(surface, nv, vtri, vw, nt, tris, NULL, &pairs2, &curves2, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_mesh_hard_edges(surface, nv, vtri, vw, nt, tris, &nh2, &pairs2, NULL, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_mesh_hard_edges(surface, SIZE_MAX / 2, vtri, vw, nt, tris, &nh2, &pairs2, &curves2, NULL),
           LS_ERR_INVALID_ARGUMENT);
    const int32_t one_tri[1] = {0}, far_tri[1] = {(int32_t)nct}, bad_tris[3] = {0, 0, 1};
    const double inside[2] = {0.25, 0.25}, outside[2] = {0.8, 0.7}, nan_vw[2] = {NAN, 0};
    EXPECT(ls_mesh_hard_edges(surface, 1, far_tri, inside, 0, NULL, &nh2, &pairs2, &curves2, NULL),
           LS_ERR_INDEX_OUT_OF_RANGE);
    CHECK(strstr(ls_last_error(), "vertex 0") != NULL);
    EXPECT(ls_mesh_hard_edges(surface, 1, one_tri, outside, 0, NULL, &nh2, &pairs2, &curves2, NULL),
           LS_ERR_PARAMETER_OUT_OF_RANGE);
    EXPECT(ls_mesh_hard_edges(surface, 1, one_tri, nan_vw, 0, NULL, &nh2, &pairs2, &curves2, NULL),
           LS_ERR_NOT_FINITE);
    EXPECT(ls_mesh_hard_edges(surface, 1, one_tri, inside, 1, bad_tris, &nh2, &pairs2, &curves2, NULL),
           LS_ERR_INDEX_OUT_OF_RANGE);
    CHECK(strstr(ls_last_error(), "triangle 0") != NULL);
    CHECK(pairs2 == untouched && nh2 == 77);

    free(keyed);
    free(hard);
    free(keys);
    free(sides);
    ls_free_array(pairs);
    ls_free_array(curves);
    ls_free_array(ct);
    free(face);
    ls_trimesh_free(mesh);
    free(ctrl_face);
    free(ident);
    ls_surface_free(surface);
    ls_net_free(net);
}

/* 1 when every directed edge of the mesh is used once and its reverse
 * once too: each undirected edge has exactly two triangles, consistently
 * oriented (a closed, oriented manifold). */
static int closed_oriented(const int32_t* tris, size_t nt) {
    int64_t* keys = malloc((3 * nt + 1) * sizeof *keys);
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++)
            keys[3 * t + k] = (int64_t)tris[3 * t + k] << 32 | (uint32_t)tris[3 * t + (k + 1) % 3];
    qsort(keys, 3 * nt, sizeof *keys, compare_i64);
    int ok = nt > 0;
    for (size_t i = 0; ok && i < 3 * nt; i++) {
        int64_t reverse = (keys[i] & 0xffffffff) << 32 | (keys[i] >> 32);
        if ((i + 1 < 3 * nt && keys[i + 1] == keys[i]) ||
            !bsearch(&reverse, keys, 3 * nt, sizeof *keys, compare_i64))
            ok = 0;
    }
    free(keys);
    return ok;
}

/* The smallest corner angle of a mesh, in degrees. */
static double smallest_angle(const double* xyz, const int32_t* tris, size_t nt) {
    double smallest = 180;
    for (size_t t = 0; t < nt; t++) {
        for (int k = 0; k < 3; k++) {
            const double* a = xyz + 3 * tris[3 * t + k];
            const double* b = xyz + 3 * tris[3 * t + (k + 1) % 3];
            const double* c = xyz + 3 * tris[3 * t + (k + 2) % 3];
            double u[3], v[3], uv = 0, uu = 0, vv = 0;
            for (int i = 0; i < 3; i++) {
                u[i] = b[i] - a[i];
                v[i] = c[i] - a[i];
                uv += u[i] * v[i];
                uu += u[i] * u[i];
                vv += v[i] * v[i];
            }
            double cosine = uv / sqrt(uu * vv);
            double angle = acos(cosine > 1 ? 1 : cosine < -1 ? -1 : cosine) * 180 / acos(-1.0);
            if (!(angle >= smallest)) smallest = angle; /* NaN (a zero edge) counts as 0 */
        }
    }
    return smallest;
}

/* The bounding-box diagonal of n points. */
static double diagonal(const double* xyz, size_t n) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, d = 0;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], xyz[3 * i + k]);
            hi[k] = fmax(hi[k], xyz[3 * i + k]);
        }
    for (int k = 0; k < 3; k++) d += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    return sqrt(d);
}

/* ls_remesh on a closed net at size h: every vertex is the surface at its
 * (tri, v, w) to 1e-12 of the diagonal, the mesh is closed and oriented,
 * no angle is below 20°, and every face id is one of the model's. */
static void check_remesh(ls_surface* surface, double h, double diag) {
    size_t nfaces = 0, ncurves = 0, ncorners = 0;
    EXPECT(ls_model_counts(surface, &nfaces, &ncurves, &ncorners), LS_OK);
    double r[18], dev = SENTINEL;
    ls_remesh_options o;
    EXPECT(ls_remesh_options_default(&o), LS_OK);
    o.size = h;
    o.tolerance = 0;
    o.adapt_curvature = 0;
    ls_trimesh* mesh = NULL;
    EXPECT(ls_remesh(surface, &o, &mesh), LS_OK);
    const mesh_view m = view(mesh);
    const size_t nv = m.nv, nt = m.nt;
    const double *xyz = m.xyz, *vw = m.vw;
    const int32_t *tris = m.tris, *vtri = m.vtri, *face = NULL;
    EXPECT(ls_trimesh_element_faces(mesh, &face), LS_OK);
    /* No tolerance: nothing measured; no charts: triangles span several. */
    EXPECT(ls_trimesh_deviation(mesh, &dev), LS_ERR_UNSUPPORTED);
    const int32_t* chart = NULL;
    const double* chart_vw = NULL;
    EXPECT(ls_trimesh_element_charts(mesh, &chart, &chart_vw), LS_ERR_UNSUPPORTED);
    CHECK(nv > 0 && nt > 0 && dev == SENTINEL && chart == NULL);
    size_t ntri = 0;
    EXPECT(ls_surface_num_triangles(surface, &ntri), LS_OK);
    double worst = 0;
    for (size_t i = 0; i < nv; i++) {
        CHECK(vtri[i] >= 0 && (size_t)vtri[i] < ntri);
        EXPECT(ls_evaluate(surface, vtri[i], vw[2 * i], vw[2 * i + 1], r), LS_OK);
        for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(r[k] - xyz[3 * i + k]));
    }
    CHECK(worst <= 1e-12 * diag);
    int in_range = 1;
    for (size_t t = 0; t < nt; t++) {
        for (int c = 0; c < 3; c++) in_range &= tris[3 * t + c] >= 0 && (size_t)tris[3 * t + c] < nv;
        in_range &= face[t] >= 0 && (size_t)face[t] < nfaces;
    }
    CHECK(in_range);
    if (in_range) {
        CHECK(closed_oriented(tris, nt));
        double smallest = smallest_angle(xyz, tris, nt);
        if (!(smallest > 20)) fprintf(stderr, "smallest angle %.2f° at size %g\n", smallest, h);
        CHECK(smallest > 20);
    }
    /* The hard edges, from the parameters alone: mesh edges, every curve
       present, each end the curve at its parameter. */
    size_t nh = 0;
    int32_t *pairs = NULL, *curves = NULL;
    double* ct = NULL;
    EXPECT(ls_mesh_hard_edges(surface, nv, vtri, vw, nt, tris, &nh, &pairs, &curves, &ct), LS_OK);
    CHECK(ncurves == 0 || nh >= ncurves);
    double off_curve = 0;
    for (size_t i = 0; i < nh; i++) {
        for (int e = 0; e < 2; e++) {
            double x[9];
            EXPECT(ls_curve_evaluate(surface, curves[i], ct[2 * i + e], x), LS_OK);
            for (int k = 0; k < 3; k++) off_curve = fmax(off_curve, fabs(x[k] - xyz[3 * pairs[2 * i + e] + k]));
        }
    }
    CHECK(off_curve <= 1e-9 * diag);
    ls_free_array(pairs);
    ls_free_array(curves);
    ls_free_array(ct);
    ls_trimesh_free(mesh);
}

/* ls_remesh: the checks above on the octahedron and on fandisk tagged at
 * 30° (12 faces); the chord error measured under a tolerance; optional
 * outputs skipped; refusals that name the argument, outputs untouched. */
static void test_remesh(const char* data_dir) {
    ls_surface* surface = octahedron(NULL);
    const double octa_diag = 2 * sqrt(3.0);
    check_remesh(surface, 0.3, octa_diag);

    /* Adaptive under a tolerance: the chord error measured, within it here. */
    ls_remesh_options o;
    EXPECT(ls_remesh_options_default(&o), LS_OK);
    CHECK(o.struct_size == sizeof o && o.size == 0 && o.tolerance == 1e-3 && o.adapt_curvature == 1);
    CHECK(o.gradation == 1.3 && o.max_triangles == 20000000 && o.parts == 1 && o.threads == 0);
    o.size = 0.3;
    o.tolerance = 1e-2;
    o.gradation = 1.5;
    ls_trimesh* mesh = NULL;
    double dev = -5;
    EXPECT(ls_remesh(surface, &o, &mesh), LS_OK);
    mesh_view m = view(mesh);
    EXPECT(ls_trimesh_deviation(mesh, &dev), LS_OK);
    CHECK(m.nt > 8 && closed_edges(m.tris, m.nt) > 0);
    CHECK(dev >= 0 && dev <= 1e-2);
    ls_trimesh_free(mesh);
    /* NULL options: the defaults (curvature under 1e-3). */
    EXPECT(ls_remesh(surface, NULL, &mesh), LS_OK);
    m = view(mesh);
    CHECK(euler(m.nv, m.tris, m.nt) == 2);
    EXPECT(ls_trimesh_deviation(mesh, &dev), LS_OK);
    CHECK(dev >= 0 && dev <= 1e-3);
    ls_trimesh_free(mesh);

    /* In parts: one closed mesh on the surface, the same on one thread
       and on two. */
    ls_remesh_options in_parts = o;
    in_parts.parts = 3;
    in_parts.threads = 1;
    EXPECT(ls_remesh(surface, &in_parts, &mesh), LS_OK);
    m = view(mesh);
    CHECK(m.nt > 8 && euler(m.nv, m.tris, m.nt) == 2 && closed_edges(m.tris, m.nt) > 0);
    in_parts.threads = 2;
    ls_trimesh* two = NULL;
    EXPECT(ls_remesh(surface, &in_parts, &two), LS_OK);
    mesh_view m2 = view(two);
    CHECK(m2.nv == m.nv && m2.nt == m.nt);
    CHECK(memcmp(m2.tris, m.tris, 3 * m.nt * sizeof *m.tris) == 0);
    CHECK(memcmp(m2.xyz, m.xyz, 3 * m.nv * sizeof *m.xyz) == 0);
    ls_trimesh_free(two);
    ls_trimesh_free(mesh);
    /* The parts worth remeshing in: whole here, at any size, for the
       octahedron's 8 control triangles (each part takes 16 at least). */
    size_t suggested = 99;
    EXPECT(ls_remesh_suggested_parts(surface, NULL, &suggested), LS_OK);
    CHECK(suggested == 1);
    ls_remesh_options fine;
    EXPECT(ls_remesh_options_default(&fine), LS_OK);
    fine.tolerance = 0;
    fine.adapt_curvature = 0;
    fine.size = 0.004;
    suggested = 99;
    EXPECT(ls_remesh_suggested_parts(surface, &fine, &suggested), LS_OK);
    CHECK(suggested == 1);
    /* A caller compiled before `parts` existed: the struct ends at
       max_triangles, and it gets one part. */
    ls_remesh_options older = o;
    older.struct_size = offsetof(ls_remesh_options, parts);
    older.parts = 0;
    EXPECT(ls_remesh(surface, &older, &mesh), LS_OK);
    ls_trimesh_free(mesh);

    /* Refusals, each naming its field; the output untouched. */
    ls_trimesh* const untouched = (ls_trimesh*)&SENTINEL;
    mesh = untouched;
    struct {
        double size, tolerance;
        int adapt;
        double gradation;
        size_t max_triangles;
        const char* name;
    } bad[] = {
        {-1, 0, 0, 1.3, 100, "size"},
        {NAN, 0, 0, 1.3, 100, "size"},
        {INFINITY, 0, 0, 1.3, 100, "size"},
        {0.3, -1e-3, 0, 1.3, 100, "tolerance"},
        {0.3, NAN, 0, 1.3, 100, "tolerance"},
        {0.3, 1.0, 0, 1.3, 100, "tolerance"},
        {0.3, 0, 2, 1.3, 100, "adapt_curvature"},
        {0.3, 0, -1, 1.3, 100, "adapt_curvature"},
        {0.3, 0, 1, 0.5, 100, "gradation"},
        {0.3, 0, 1, 1.0, 100, "gradation"},
        {0.3, 0, 1, -2, 100, "gradation"},
        {0.3, 0, 1, NAN, 100, "gradation"},
        {0.3, 0, 1, 0, 100, "gradation"},
        {0.3, 0, 0, 1.3, 0, "max_triangles"},
    };
    ls_remesh_options b;
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        EXPECT(ls_remesh_options_default(&b), LS_OK);
        b.size = bad[i].size;
        b.tolerance = bad[i].tolerance;
        b.adapt_curvature = bad[i].adapt;
        b.gradation = bad[i].gradation;
        b.max_triangles = bad[i].max_triangles;
        EXPECT(ls_remesh(surface, &b, &mesh), LS_ERR_INVALID_ARGUMENT);
        CHECK(strstr(ls_last_error(), "ls_remesh: ") == ls_last_error());
        CHECK(strstr(ls_last_error(), bad[i].name) != NULL);
    }
    EXPECT(ls_remesh_options_default(&b), LS_OK);
    b.parts = 0;
    EXPECT(ls_remesh(surface, &b, &mesh), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "parts") != NULL);
    /* No density at all. */
    EXPECT(ls_remesh_options_default(&b), LS_OK);
    b.tolerance = 0;
    b.adapt_curvature = 0;
    EXPECT(ls_remesh(surface, &b, &mesh), LS_ERR_INVALID_ARGUMENT);
    /* Over the default budget of 20 million triangles: refused before
       meshing, with its own status and the count. */
    b.size = 1e-4;
    EXPECT(ls_remesh(surface, &b, &mesh), LS_ERR_OVER_BUDGET);
    CHECK(strstr(ls_last_error(), "over the budget of 20000000") != NULL);
    /* A budget the caller sets. */
    b.size = 0.05;
    b.max_triangles = 1000;
    EXPECT(ls_remesh(surface, &b, &mesh), LS_ERR_OVER_BUDGET);
    CHECK(strstr(ls_last_error(), "over the budget of 1000") != NULL);
    b.max_triangles = 100000;
    ls_trimesh* fits = NULL;
    EXPECT(ls_remesh(surface, &b, &fits), LS_OK);
    ls_trimesh_free(fits);
    EXPECT(ls_remesh(NULL, &o, &mesh), LS_ERR_NULL_POINTER);
    EXPECT(ls_remesh(surface, &o, NULL), LS_ERR_NULL_POINTER);
    CHECK(strstr(ls_last_error(), "mesh") != NULL);
    CHECK(mesh == untouched);
    ls_surface_free(surface);

    /* fandisk, hard edges by angle: 12 faces, the model's. */
    char path[4096];
    snprintf(path, sizeof path, "%s/fandisk.off", data_dir);
    ls_net* net = NULL;
    EXPECT(ls_net_load(path, &net), LS_OK);
    if (!net) return;
    EXPECT(ls_net_tag_by_angle(net, 30, NULL), LS_OK);
    EXPECT(ls_surface_build(net, &surface), LS_OK);
    size_t nfaces = 0, ncurves = 0, ncorners = 0;
    EXPECT(ls_model_counts(surface, &nfaces, &ncurves, &ncorners), LS_OK);
    CHECK(nfaces == 12);
    size_t ncv = 0, nct = 0;
    double* points = NULL;
    int32_t* control = NULL;
    EXPECT(ls_refine(surface, 0, 0, &ncv, &points, &nct, &control), LS_OK); /* the net itself */
    double diag = diagonal(points, ncv);
    CHECK(diag > 0);
    check_remesh(surface, 0.03 * diag, diag);
    /* fandisk's parts: whole by default, more for a fine size (one per
       30 000 triangles: 0.2% asks for about 1.3 million), never fewer
       for a finer one; `parts` in the options ignored; the output
       untouched on a refusal. */
    size_t parts = 99, finer = 99, kept = 99;
    EXPECT(ls_remesh_suggested_parts(surface, NULL, &parts), LS_OK);
    CHECK(parts == 1);
    EXPECT(ls_remesh_options_default(&fine), LS_OK);
    fine.tolerance = 0;
    fine.adapt_curvature = 0;
    fine.size = 0.004 * diag;
    fine.parts = 0;
    EXPECT(ls_remesh_suggested_parts(surface, &fine, &parts), LS_OK);
    CHECK(parts >= 4 && parts <= 64);
    fine.size = 0.002 * diag;
    EXPECT(ls_remesh_suggested_parts(surface, &fine, &finer), LS_OK);
    CHECK(finer > parts && finer <= 64);
    fine.size = -1;
    EXPECT(ls_remesh_suggested_parts(surface, &fine, &kept), LS_ERR_INVALID_ARGUMENT);
    CHECK(kept == 99);
    EXPECT(ls_remesh_suggested_parts(surface, NULL, NULL), LS_ERR_NULL_POINTER);
    ls_free_array(points);
    ls_free_array(control);
    ls_surface_free(surface);
    ls_net_free(net);
}

/* Remeshing in parts shared between two ranks, driven here in one
   thread: each stage both jobs run their tasks, and each advances with
   both ranks' bytes, as MPI_Allgatherv would give them. The mesh is
   ls_remesh's in the same number of parts, bit for bit; the two pieces
   hold every triangle once, their nodes the whole's by global id. */
static void test_remesh_job(void) {
    ls_surface* surface = octahedron(NULL);
    ls_remesh_options o;
    EXPECT(ls_remesh_options_default(&o), LS_OK);
    o.size = 0.3;
    o.tolerance = 1e-2;
    o.parts = 3;
    ls_trimesh* threaded = NULL;
    EXPECT(ls_remesh(surface, &o, &threaded), LS_OK);
    if (!threaded) return;
    mesh_view t = view(threaded);

    ls_remesh_job* const untouched = (ls_remesh_job*)&SENTINEL;
    ls_remesh_job* jobs[2] = {untouched, untouched};
    EXPECT(ls_remesh_job_new(surface, &o, 2, 2, &jobs[0]), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "rank 2 of 2") != NULL && jobs[0] == untouched);
    EXPECT(ls_remesh_job_new(NULL, &o, 0, 2, &jobs[0]), LS_ERR_NULL_POINTER);
    ls_remesh_options b = o;
    b.size = -1;
    EXPECT(ls_remesh_job_new(surface, &b, 0, 2, &jobs[0]), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "size") != NULL && jobs[0] == untouched);
    for (int r = 0; r < 2; r++) EXPECT(ls_remesh_job_new(surface, &o, r, 2, &jobs[r]), LS_OK);
    if (jobs[0] == untouched || jobs[1] == untouched) return;

    /* Nothing to hand over before the job is done, nor to advance with
       before this rank has run its tasks. */
    ls_trimesh* mesh = (ls_trimesh*)&SENTINEL;
    EXPECT(ls_remesh_job_mesh(jobs[0], &mesh), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "sizes stage") != NULL && mesh == (ls_trimesh*)&SENTINEL);
    size_t counts[2] = {0, 0};
    EXPECT(ls_remesh_job_advance(jobs[0], NULL, counts), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "ls_remesh_job_run") != NULL);

    int stages = 0, done = 0, damaged_once = 0;
    const char* stage = NULL;
    EXPECT(ls_remesh_job_done(jobs[0], &done, &stage), LS_OK);
    CHECK(done == 0 && stage && strcmp(stage, "sizes") == 0);
    while (!done && stages < 10) {
        const uint8_t* bytes[2] = {NULL, NULL};
        size_t n[2] = {0, 0};
        for (int r = 0; r < 2; r++) EXPECT(ls_remesh_job_run(jobs[r], &bytes[r], &n[r]), LS_OK);
        uint8_t* all = malloc(n[0] + n[1]);
        memcpy(all, bytes[0], n[0]);
        memcpy(all + n[0], bytes[1], n[1]);
        if (!damaged_once && n[1] > 40) {
            /* Rank 1's bytes damaged on the way: refused, rank 0 as it was. */
            all[n[0] + n[1] - 9] ^= 1;
            EXPECT(ls_remesh_job_advance(jobs[0], all, n), LS_ERR_BAD_STREAM);
            CHECK(strstr(ls_last_error(), "rank 1") != NULL);
            all[n[0] + n[1] - 9] ^= 1;
            damaged_once = 1;
        }
        for (int r = 0; r < 2; r++) EXPECT(ls_remesh_job_advance(jobs[r], all, n), LS_OK);
        free(all);
        stages++;
        int other = -1;
        EXPECT(ls_remesh_job_done(jobs[0], &done, &stage), LS_OK);
        EXPECT(ls_remesh_job_done(jobs[1], &other, NULL), LS_OK);
        CHECK(other == done);
    }
    CHECK(done == 1 && damaged_once && stages >= 3 && strcmp(stage, "done") == 0);
    const uint8_t* more = NULL;
    size_t nmore = 0;
    EXPECT(ls_remesh_job_run(jobs[0], &more, &nmore), LS_ERR_INVALID_ARGUMENT);

    /* No rank of two holds the whole mesh: each holds its piece. */
    for (int r = 0; r < 2; r++) {
        EXPECT(ls_remesh_job_mesh(jobs[r], &mesh), LS_ERR_INVALID_ARGUMENT);
        CHECK(strstr(ls_last_error(), "this rank's piece") != NULL);
        CHECK(mesh == (ls_trimesh*)&SENTINEL);
    }
    /* The pieces on their global ids are the threaded mesh: each node
       where its id says, each triangle (as global ids, rotated to start
       at its lowest) in one piece. */
    size_t held = 0;
    int ids_ok = 1;
    int64_t* pieces_tris = malloc(3 * t.nt * sizeof *pieces_tris);
    int64_t* whole_tris = malloc(3 * t.nt * sizeof *whole_tris);
    for (int r = 0; r < 2; r++) {
        ls_trimesh* piece = NULL;
        int64_t* ids = NULL;
        EXPECT(ls_remesh_job_piece(jobs[r], &piece, &ids), LS_OK);
        if (!piece) continue;
        mesh_view p = view(piece);
        for (size_t i = 0; i < p.nv; i++)
            ids_ok &= ids[i] >= 0 && (size_t)ids[i] < t.nv &&
                      memcmp(&p.xyz[3 * i], &t.xyz[3 * ids[i]], 3 * sizeof(double)) == 0;
        for (size_t e = 0; e < p.nt; e++, held++)
            if (held < t.nt)
                for (int k = 0; k < 3; k++) pieces_tris[3 * held + k] = ids[p.tris[3 * e + k]];
        ls_free_array(ids);
        ls_trimesh_free(piece);
    }
    CHECK(held == t.nt && ids_ok);
    if (held == t.nt) {
        for (size_t e = 0; e < t.nt; e++)
            for (int k = 0; k < 3; k++) whole_tris[3 * e + k] = t.tris[3 * e + k];
        canonical_triangles(pieces_tris, t.nt);
        canonical_triangles(whole_tris, t.nt);
        CHECK(memcmp(pieces_tris, whole_tris, 3 * t.nt * sizeof *whole_tris) == 0);
    }
    free(pieces_tris);
    free(whole_tris);
    ls_remesh_job_free(jobs[0]);
    ls_remesh_job_free(jobs[1]);
    ls_remesh_job_free(NULL);
    ls_trimesh_free(threaded);
    ls_surface_free(surface);
}

/* The first `n` bytes of a file as text ("" when it cannot be read). */
static const char* head(const char* path, size_t n) {
    static char text[256];
    text[0] = '\0';
    FILE* f = fopen(path, "rb");
    if (!f) return text;
    size_t got = fread(text, 1, n < sizeof text ? n : sizeof text - 1, f);
    text[got] = '\0';
    fclose(f);
    return text;
}

/* The four numbers after a line `section` of a text .msh (for $Nodes
 * and $Elements: blocks, count, smallest and largest tag); 0 when the
 * file has no such section. */
static int section_header(const char* path, const char* section, long long v[4]) {
    char line[512];
    int found = 0;
    FILE* f = fopen(path, "r");
    if (!f) return 0;
    while (!found && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = '\0';
        if (strcmp(line, section) == 0 && fgets(line, sizeof line, f))
            found = sscanf(line, "%lld %lld %lld %lld", &v[0], &v[1], &v[2], &v[3]) == 4;
    }
    fclose(f);
    return found;
}

/* The remesher's mesh of a surface at size 0.4, without a tolerance. */
static ls_trimesh* uniform_remesh(const ls_surface* surface) {
    ls_remesh_options ro;
    EXPECT(ls_remesh_options_default(&ro), LS_OK);
    ro.size = 0.4;
    ro.tolerance = 0;
    ro.adapt_curvature = 0;
    ls_trimesh* mesh = NULL;
    EXPECT(ls_remesh(surface, &ro, &mesh), LS_OK);
    return mesh;
}

/* Whether a text file has a line `line`. */
static int has_line(const char* path, const char* line) {
    char buffer[512];
    int found = 0;
    FILE* f = fopen(path, "r");
    if (!f) return 0;
    while (!found && fgets(buffer, sizeof buffer, f)) {
        buffer[strcspn(buffer, "\n")] = '\0';
        found = strcmp(buffer, line) == 0;
    }
    fclose(f);
    return found;
}

/* ls_trimesh_write: .msh and .vtu, ASCII and binary, whole or as a piece
 * with global ids; refusals leave no file behind. */
static void test_trimesh_write(void) {
    ls_surface* surface = octahedron(NULL);
    ls_trimesh* mesh = uniform_remesh(surface);
    if (!mesh) return;
    const mesh_view m = view(mesh);
    ls_trimesh_write_options o;
    EXPECT(ls_trimesh_write_options_default(&o), LS_OK);
    CHECK(o.struct_size == sizeof o && o.binary == 0 && o.global_ids == NULL && o.first_element_tag == 1);

    EXPECT(ls_trimesh_write(mesh, surface, scratch("w.msh"), NULL), LS_OK);
    CHECK(strncmp(head(scratch("w.msh"), 23), "$MeshFormat\n4.1 0 8\n", 20) == 0);
    o.binary = 1;
    EXPECT(ls_trimesh_write(mesh, surface, scratch("wb.msh"), &o), LS_OK);
    CHECK(strncmp(head(scratch("wb.msh"), 20), "$MeshFormat\n4.1 1 8\n", 20) == 0);
    EXPECT(ls_trimesh_write(mesh, surface, scratch("wb.vtu"), &o), LS_OK);
    CHECK(strstr(head(scratch("wb.vtu"), 200), "<VTKFile") != NULL);

    /* A piece: node i tagged ids[i] + 1, elements from 1000. The $Nodes
       header names the smallest and largest tag. */
    int64_t* ids = malloc(m.nv * sizeof *ids);
    for (size_t i = 0; i < m.nv; i++) ids[i] = 10 * (int64_t)i + 40;
    o.binary = 0;
    o.global_ids = ids;
    o.first_element_tag = 1000;
    EXPECT(ls_trimesh_write(mesh, surface, scratch("piece.msh"), &o), LS_OK);
    long long nodes[4] = {0}, elements[4] = {0};
    CHECK(section_header(scratch("piece.msh"), "$Nodes", nodes));
    CHECK(nodes[1] == (long long)m.nv && nodes[2] == 41 && nodes[3] == 10 * (long long)(m.nv - 1) + 41);
    CHECK(section_header(scratch("piece.msh"), "$Elements", elements));
    CHECK(elements[1] >= (long long)m.nt && elements[2] == 1000 && elements[3] == 1000 + elements[1] - 1);
    EXPECT(ls_trimesh_write(mesh, surface, scratch("piece.vtu"), &o), LS_OK);
    CHECK(strstr(head(scratch("piece.vtu"), 255), "<VTKFile") != NULL);

    /* Refusals, each naming what is wrong; no file is made. */
    ids[2] = ids[1];
    EXPECT(ls_trimesh_write(mesh, surface, scratch("bad.msh"), &o), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "global_ids[1] and global_ids[2]") != NULL);
    ids[2] = -5;
    EXPECT(ls_trimesh_write(mesh, surface, scratch("bad.msh"), &o), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "negative") != NULL);
    o.global_ids = NULL;
    o.first_element_tag = 0;
    EXPECT(ls_trimesh_write(mesh, surface, scratch("bad.msh"), &o), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "first_element_tag") != NULL);
    EXPECT(ls_trimesh_write(mesh, surface, scratch("bad.obj"), NULL), LS_ERR_UNSUPPORTED);
    CHECK(strstr(ls_last_error(), ".msh or .vtu") != NULL);
    EXPECT(ls_trimesh_write(mesh, surface, "/nonexistent-dir/x.msh", NULL), LS_ERR_IO);
    CHECK(strstr(ls_last_error(), "/nonexistent-dir/x.msh") != NULL);
    EXPECT(ls_trimesh_write(mesh, surface, NULL, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_trimesh_write(NULL, surface, scratch("bad.msh"), NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_trimesh_write(mesh, NULL, scratch("bad.msh"), NULL), LS_ERR_NULL_POINTER);
    ls_trimesh_write_options small = o;
    small.struct_size = 3;
    EXPECT(ls_trimesh_write(mesh, surface, scratch("bad.msh"), &small), LS_ERR_INVALID_ARGUMENT);
    CHECK(fopen(scratch("bad.msh"), "r") == NULL && fopen(scratch("bad.obj"), "r") == NULL);

    /* ls_adapt's mesh has no faces to write. */
    ls_adapt_options ao;
    EXPECT(ls_adapt_options_default(&ao), LS_OK);
    ls_trimesh* adapted = NULL;
    EXPECT(ls_adapt(surface, &ao, &adapted), LS_OK);
    EXPECT(ls_trimesh_write(adapted, surface, scratch("bad.msh"), NULL), LS_ERR_UNSUPPORTED);
    CHECK(strstr(ls_last_error(), "element faces") != NULL);

    const char* written[] = {"w.msh", "wb.msh", "wb.vtu", "piece.msh", "piece.vtu"};
    for (size_t i = 0; i < sizeof written / sizeof *written; i++) CHECK(remove(scratch(written[i])) == 0);
    free(ids);
    ls_trimesh_free(adapted);
    ls_trimesh_free(mesh);
    ls_surface_free(surface);
}

/* One ls_adapt call with the given options; its mesh, or NULL. */
static ls_trimesh* adapt(ls_surface* surface, double angle, double tolerance, int levels, int to_limit, int status) {
    ls_adapt_options o;
    EXPECT(ls_adapt_options_default(&o), LS_OK);
    o.angle = angle;
    o.tolerance = tolerance;
    o.levels = levels;
    o.to_limit = to_limit;
    ls_trimesh* mesh = NULL;
    EXPECT(ls_adapt(surface, &o, &mesh), status);
    return mesh;
}

static void test_adapt(void) {
    ls_surface* surface = octahedron(NULL);
    double r[18];
    ls_adapt_options o;
    EXPECT(ls_adapt_options_default(&o), LS_OK);
    CHECK(o.struct_size == sizeof o && o.angle == 10 && o.tolerance == 0 && o.levels == 3 && o.to_limit == 0);
    /* Angle 0 is uniform Loop: 8 * 4^2 triangles, closed. */
    ls_trimesh* mesh = adapt(surface, 0.0, 0.0, 2, 0, LS_OK);
    mesh_view m = view(mesh);
    CHECK(m.nt == 128 && euler(m.nv, m.tris, m.nt) == 2);
    const int32_t* face = NULL;
    EXPECT(ls_trimesh_element_faces(mesh, &face), LS_ERR_UNSUPPORTED);
    ls_trimesh_free(mesh);
    /* Adaptive, pushed to the limit: fewer triangles, still closed, every
       vertex the surface at its parameters. */
    mesh = adapt(surface, 20.0, 0.0, 4, 1, LS_OK);
    m = view(mesh);
    CHECK(m.nt < 8 * 256 && m.nt > 8 && euler(m.nv, m.tris, m.nt) == 2);
    for (size_t i = 0; i < m.nv; i++) {
        EXPECT(ls_evaluate(surface, m.vtri[i], m.vw[2 * i], m.vw[2 * i + 1], r), LS_OK);
        for (int k = 0; k < 3; k++) CHECK(r[k] == m.xyz[3 * i + k]);
    }
    ls_trimesh_free(mesh);
    /* Tolerance only. */
    mesh = adapt(surface, -1.0, 1e-2, 5, 0, LS_OK);
    m = view(mesh);
    CHECK(m.nt < 8 * 1024 && m.nv - (3 * m.nt) / 2 + m.nt == 2);
    ls_trimesh_free(mesh);
    /* NULL options: the defaults. */
    EXPECT(ls_adapt(surface, NULL, &mesh), LS_OK);
    m = view(mesh);
    CHECK(m.nt > 8 && m.nt <= 8 * 64 && euler(m.nv, m.tris, m.nt) == 2);
    ls_trimesh_free(mesh);

    ls_trimesh* const untouched = (ls_trimesh*)&SENTINEL;
    mesh = untouched;
    EXPECT(ls_adapt(NULL, &o, &mesh), LS_ERR_NULL_POINTER);
    EXPECT(ls_adapt(surface, &o, NULL), LS_ERR_NULL_POINTER);
    adapt(surface, 5.0, 0.0, 11, 0, LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "ls_adapt") != NULL);
    CHECK(strstr(ls_last_error(), "levels 11") != NULL);
    adapt(surface, 5.0, 0.0, -1, 0, LS_ERR_INVALID_ARGUMENT);
    adapt(surface, 200.0, 0.0, 2, 0, LS_ERR_INVALID_ARGUMENT);
    adapt(surface, -1.0, 0.0, 2, 0, LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "no criterion") != NULL);
    adapt(surface, -1.0, 2.0, 2, 0, LS_ERR_INVALID_ARGUMENT);
    adapt(surface, NAN, 0.0, 2, 0, LS_ERR_INVALID_ARGUMENT);
    adapt(surface, 5.0, 0.0, 2, 2, LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "to_limit") != NULL);
    /* A budget: the third level of uniform subdivision would reach 512. */
    o.angle = 0;
    o.max_triangles = 500;
    EXPECT(ls_adapt(surface, &o, &mesh), LS_ERR_OVER_BUDGET);
    CHECK(strstr(ls_last_error(), "over the limit of 500") != NULL);
    CHECK(mesh == untouched); /* outputs untouched on failure */
    ls_surface_free(surface);
}

static void test_streams(void) {
    ls_net* net = NULL;
    ls_surface* surface = NULL;
    EXPECT(ls_net_from_arrays(6, OCTA_XYZ, 8, OCTA_TRIS, &net), LS_OK);
    EXPECT(ls_net_tag_edge(net, 0, 2), LS_OK);
    EXPECT(ls_net_tag_vertex(net, 4), LS_OK);
    EXPECT(ls_surface_build(net, &surface), LS_OK);
    uint8_t* bytes = NULL;
    size_t n = 0;
    EXPECT(ls_surface_save(NULL, &bytes, &n), LS_ERR_NULL_POINTER);
    EXPECT(ls_surface_save(surface, NULL, &n), LS_ERR_NULL_POINTER);
    EXPECT(ls_surface_save(surface, &bytes, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_surface_save(surface, &bytes, &n), LS_OK);
    CHECK(bytes != NULL && n > 48);

    ls_surface* loaded = NULL;
    EXPECT(ls_surface_load(NULL, n, &loaded), LS_ERR_NULL_POINTER);
    EXPECT(ls_surface_load(bytes, n, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_surface_load(bytes, n, &loaded), LS_OK);
    double a[18], b[18];
    for (int t = 0; t < 8; t++) {
        EXPECT(ls_evaluate(surface, t, 0.3, 0.4, a), LS_OK);
        EXPECT(ls_evaluate(loaded, t, 0.3, 0.4, b), LS_OK);
        CHECK(memcmp(a, b, sizeof a) == 0);
    }
    ls_surface_free(loaded);

    /* Every truncation and every flipped byte is a clean error. */
    ls_surface* never = (ls_surface*)&SENTINEL;
    int clean = 1;
    for (size_t len = 0; len < n; len++) {
        if (ls_surface_load(bytes, len, &never) != LS_ERR_BAD_STREAM) clean = 0;
    }
    CHECK(clean);
    uint8_t* damaged = malloc(n);
    for (size_t i = 0; i < n; i++) {
        memcpy(damaged, bytes, n);
        damaged[i] ^= 0x20;
        if (ls_surface_load(damaged, n, &never) != LS_ERR_BAD_STREAM) clean = 0;
    }
    CHECK(clean);
    CHECK(never == (ls_surface*)&SENTINEL);
    EXPECT(ls_surface_load(damaged, 0, &never), LS_ERR_BAD_STREAM);
    CHECK(strstr(ls_last_error(), "ls_surface_load") != NULL);
    free(damaged);
    ls_free_bytes(bytes, n);
    ls_free_bytes(NULL, 0);
    ls_surface_free(surface);
    ls_net_free(net);
}

/* ls_mesh_curve: a mesh made by ls_remesh on the octahedron, curved to P2
   and P3: the vertices stay (they move by round-off at most), every node
   is ls_evaluate of its (tri, v, w), each edge's inner nodes are shared by
   its two triangles, and bad arguments are refused by name with the
   output untouched. */
static void test_mesh_curve(void) {
    ls_surface* surface = octahedron(NULL);
    ls_trimesh* linear = uniform_remesh(surface);
    const mesh_view m = view(linear);
    const size_t nv = m.nv, nt = m.nt;
    /* Another tool's mesh: arrays the caller owns. */
    double* xyz = malloc(3 * nv * sizeof *xyz);
    int32_t* tris = malloc(3 * nt * sizeof *tris);
    memcpy(xyz, m.xyz, 3 * nv * sizeof *xyz);
    memcpy(tris, m.tris, 3 * nt * sizeof *tris);
    ls_trimesh_free(linear);
    ls_mesh_curve_options o;
    EXPECT(ls_mesh_curve_options_default(&o), LS_OK);
    CHECK(o.struct_size == sizeof o && o.order == 2 && o.max_move == 0.01);
    for (int order = 2; order <= 3; order++) {
        o.order = order;
        ls_trimesh* mesh = NULL;
        EXPECT(ls_mesh_curve(surface, nv, xyz, nt, tris, &o, &mesh), LS_OK);
        size_t nn = 0, ne = 0, per = 0;
        double moved = -1, jac = -5;
        const double *nodes = NULL, *nvw = NULL;
        const int32_t *ntri = NULL, *elems = NULL, *face = NULL;
        EXPECT(ls_trimesh_counts(mesh, &nn, &ne, &per), LS_OK);
        EXPECT(ls_trimesh_xyz(mesh, &nodes), LS_OK);
        EXPECT(ls_trimesh_elements(mesh, &elems), LS_OK);
        EXPECT(ls_trimesh_node_params(mesh, &ntri, &nvw), LS_OK);
        EXPECT(ls_trimesh_element_faces(mesh, &face), LS_OK);
        EXPECT(ls_trimesh_largest_move(mesh, &moved), LS_OK);
        EXPECT(ls_trimesh_min_scaled_jacobian(mesh, &jac), LS_OK);
        CHECK(per == (size_t)(order + 1) * (order + 2) / 2 && ne == nt);
        CHECK(nn > nv && moved >= 0 && moved < 1e-12 && jac > 0 && jac <= 1);
        /* The vertices come first, snapped (here they were on the surface). */
        for (size_t i = 0; i < nv; i++)
            for (int d = 0; d < 3; d++) CHECK(fabs(nodes[3 * i + d] - xyz[3 * i + d]) < 1e-12);
        for (size_t i = 0; i < nn; i++) {
            double r[18];
            EXPECT(ls_evaluate(surface, ntri[i], nvw[2 * i], nvw[2 * i + 1], r), LS_OK);
            for (int d = 0; d < 3; d++) CHECK(fabs(r[d] - nodes[3 * i + d]) < 1e-12);
        }
        /* Edge k of a triangle joins its vertices k and k+1; its inner
           nodes follow the vertices. Both triangles of an edge list the
           same nodes, in opposite orders. */
        size_t inner = (size_t)order - 1, shared = 0;
        for (size_t t = 0; t < nt; t++)
            for (size_t u = t + 1; u < nt; u++)
                for (int k = 0; k < 3; k++)
                    for (int q = 0; q < 3; q++) {
                        const int32_t* a = elems + per * t;
                        const int32_t* b = elems + per * u;
                        if (a[k] != b[(q + 1) % 3] || a[(k + 1) % 3] != b[q]) continue;
                        shared++;
                        for (size_t j = 0; j < inner; j++)
                            CHECK(a[3 + k * inner + j] == b[3 + q * inner + inner - 1 - j]);
                    }
        CHECK(shared == 3 * nt / 2);
        for (size_t t = 0; t < nt; t++) CHECK(face[t] == 0);
        /* Curved meshes are written as Lagrange elements: gmsh's type 9
           (6-node triangle) or 21 (10-node), one block for the one face. */
        EXPECT(ls_trimesh_write(mesh, surface, scratch("curved.msh"), NULL), LS_OK);
        long long blocks[4] = {0};
        CHECK(section_header(scratch("curved.msh"), "$Elements", blocks) && blocks[1] == (long long)ne);
        char block[64];
        snprintf(block, sizeof block, "2 1 %d %zu", order == 2 ? 9 : 21, ne);
        CHECK(has_line(scratch("curved.msh"), block));
        CHECK(remove(scratch("curved.msh")) == 0);
        ls_trimesh_free(mesh);
    }
    ls_trimesh* const untouched = (ls_trimesh*)&SENTINEL;
    ls_trimesh* mesh = untouched;
    o.order = 5;
    EXPECT(ls_mesh_curve(surface, nv, xyz, nt, tris, &o, &mesh), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "order") != NULL);
    o.order = 2;
    o.max_move = 0;
    EXPECT(ls_mesh_curve(surface, nv, xyz, nt, tris, &o, &mesh), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "max_move") != NULL);
    o.max_move = 0.01;
    tris[4] = (int32_t)nv;
    EXPECT(ls_mesh_curve(surface, nv, xyz, nt, tris, &o, &mesh), LS_ERR_INDEX_OUT_OF_RANGE);
    CHECK(strstr(ls_last_error(), "triangle 1") != NULL);
    tris[4] = 0;
    xyz[0] += 10;
    EXPECT(ls_mesh_curve(surface, nv, xyz, nt, tris, NULL, &mesh), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "vertex 0") != NULL);
    EXPECT(ls_mesh_curve(NULL, nv, xyz, nt, tris, &o, &mesh), LS_ERR_NULL_POINTER);
    EXPECT(ls_mesh_curve(surface, nv, NULL, nt, tris, &o, &mesh), LS_ERR_NULL_POINTER);
    CHECK(mesh == untouched);
    free(xyz);
    free(tris);
    ls_surface_free(surface);
}

/* Partitioning the pig (891 triangles) into 7 parts: every triangle in a
   part, balanced, the cut counted here from the triangles, the same parts
   twice; bad K and NULL pointers refused with the outputs untouched. */
static void test_partition(const char* data_dir) {
    char path[1024];
    snprintf(path, sizeof path, "%s/pig.off", data_dir);
    ls_net* net = NULL;
    EXPECT(ls_net_load(path, &net), LS_OK);
    size_t nv, nt, nh;
    EXPECT(ls_net_counts(net, &nv, &nt, &nh), LS_OK);
    double* xyz = NULL;
    int32_t* tris = NULL;
    size_t rv, rt;
    ls_surface* surface = NULL;
    EXPECT(ls_surface_build(net, &surface), LS_OK);
    EXPECT(ls_refine(surface, 0, 0, &rv, &xyz, &rt, &tris), LS_OK); /* the net's own triangles */
    CHECK(rt == nt);

    ls_partition_options o;
    memset(&o, 0xff, sizeof o);
    EXPECT(ls_partition_options_default(&o), LS_OK);
    CHECK(o.struct_size == sizeof o && o.parts == 1 && o.seed == 1);
    o.parts = 7;
    size_t ntris = 0, cut = 0;
    int32_t* part = NULL;
    EXPECT(ls_net_partition(net, &o, &ntris, &part, &cut), LS_OK);
    CHECK(ntris == nt && part != NULL);
    size_t sizes[7] = {0};
    for (size_t t = 0; t < ntris; t++) {
        CHECK(part[t] >= 0 && part[t] < 7);
        if (part[t] >= 0 && part[t] < 7) sizes[part[t]]++;
    }
    for (int p = 0; p < 7; p++) CHECK(sizes[p] > 0 && sizes[p] <= (size_t)(1.05 * nt / 7));
    /* Control edges between parts: each edge a -> b of one triangle meets
       b -> a of its neighbour. */
    size_t counted = 0;
    for (size_t t = 0; t < nt; t++)
        for (size_t s = t + 1; s < nt; s++) {
            if (part[t] == part[s]) continue;
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    if (tris[3 * t + i] == tris[3 * s + (j + 1) % 3] &&
                        tris[3 * t + (i + 1) % 3] == tris[3 * s + j])
                        counted++;
        }
    CHECK(cut == counted && cut > 0);
    /* The same parts again. */
    size_t ntris2 = 0, cut2 = 0;
    int32_t* again = NULL;
    EXPECT(ls_net_partition(net, &o, &ntris2, &again, &cut2), LS_OK);
    CHECK(ntris2 == ntris && cut2 == cut && memcmp(part, again, ntris * sizeof *part) == 0);
    ls_free_array(again);

    /* NULL options: K = 1, everything in part 0. */
    EXPECT(ls_net_partition(net, NULL, &ntris2, &again, &cut2), LS_OK);
    CHECK(ntris2 == nt && cut2 == 0);
    for (size_t t = 0; t < ntris2; t++) CHECK(again[t] == 0);
    ls_free_array(again);

    /* Refusals leave the outputs as they were. */
    int32_t* untouched = (int32_t*)&o;
    size_t n_out = 12345, cut_out = 6789;
    int32_t* part_out = untouched;
    int bad_k[] = {0, -3, (int)nt + 1};
    for (int i = 0; i < 3; i++) {
        o.parts = bad_k[i];
        EXPECT(ls_net_partition(net, &o, &n_out, &part_out, &cut_out), LS_ERR_INVALID_ARGUMENT);
        char k_text[32];
        snprintf(k_text, sizeof k_text, "K = %d", bad_k[i]);
        CHECK(strstr(ls_last_error(), k_text) != NULL);
        CHECK(strncmp(ls_last_error(), "ls_net_partition:", 17) == 0);
    }
    o.parts = 7;
    EXPECT(ls_net_partition(NULL, &o, &n_out, &part_out, &cut_out), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_partition(net, &o, NULL, &part_out, &cut_out), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_partition(net, &o, &n_out, NULL, &cut_out), LS_ERR_NULL_POINTER);
    EXPECT(ls_net_partition(net, &o, &n_out, &part_out, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_partition_options_default(NULL), LS_ERR_NULL_POINTER);
    o.struct_size = 4;
    EXPECT(ls_net_partition(net, &o, &n_out, &part_out, &cut_out), LS_ERR_INVALID_ARGUMENT);
    CHECK(n_out == 12345 && cut_out == 6789 && part_out == untouched);

    ls_free_array(part);
    ls_free_array(xyz);
    ls_free_array(tris);
    ls_surface_free(surface);
    ls_net_free(net);
}

/* The pig tagged at 40°, its whole surface, and partition options for 5
 * parts: what the part tests compare against. */
static ls_net* pig_in_five(const char* data_dir, ls_surface** whole, ls_partition_options* po) {
    char path[1024];
    snprintf(path, sizeof path, "%s/pig.off", data_dir);
    ls_net* net = NULL;
    EXPECT(ls_net_load(path, &net), LS_OK);
    EXPECT(ls_net_tag_by_angle(net, 40, NULL), LS_OK);
    EXPECT(ls_surface_build(net, whole), LS_OK);
    EXPECT(ls_partition_options_default(po), LS_OK);
    po->parts = 5;
    return net;
}

/* ls_net_part: a part's maps agree with ls_net_partition, its surface
   evaluates its owned triangles as the whole's, its stream round-trips,
   and bad requests and damaged streams write nothing. */
static void test_part(const char* data_dir) {
    ls_surface* whole = NULL;
    ls_partition_options po;
    ls_net* net = pig_in_five(data_dir, &whole, &po);
    size_t nt = 0, cut = 0;
    int32_t* owner = NULL;
    EXPECT(ls_net_partition(net, &po, &nt, &owner, &cut), LS_OK);

    ls_part_options o;
    memset(&o, 0xff, sizeof o);
    EXPECT(ls_part_options_default(&o), LS_OK);
    CHECK(o.struct_size == sizeof o && o.parts == 1 && o.part == 0 && o.seed == 1);
    o.parts = 5;
    o.part = 3;
    ls_part* part = NULL;
    EXPECT(ls_net_part(net, &o, &part), LS_OK);
    size_t owned_n = 0, halo = 0, nv = 0, ntris = 0, nverts = 0;
    EXPECT(ls_part_counts(part, &owned_n, &halo, &nv), LS_OK);
    int32_t *global = NULL, *owned = NULL, *gverts = NULL;
    EXPECT(ls_part_triangles(part, &ntris, &global, &owned), LS_OK);
    EXPECT(ls_part_vertices(part, &nverts, &gverts), LS_OK);
    CHECK(ntris == owned_n + halo && nverts == nv && halo > 0);
    size_t mine = 0;
    for (size_t t = 0; t < nt; t++) mine += owner[t] == 3;
    CHECK(mine == owned_n);
    ls_net* sub = NULL;
    ls_surface* surface = NULL;
    EXPECT(ls_part_net(part, &sub), LS_OK);
    EXPECT(ls_surface_build(sub, &surface), LS_OK);
    for (size_t t = 0; t < ntris; t++) {
        CHECK(owner[global[t]] == 3 ? owned[t] == 1 : owned[t] == 0);
        if (!owned[t]) continue;
        double a[18], b[18];
        EXPECT(ls_evaluate(surface, (int32_t)t, 0.2, 0.3, a), LS_OK);
        EXPECT(ls_evaluate(whole, global[t], 0.2, 0.3, b), LS_OK);
        CHECK(memcmp(a, b, sizeof a) == 0);
    }

    /* The stream round-trips; a damaged one writes nothing. */
    uint8_t* bytes = NULL;
    size_t len = 0;
    EXPECT(ls_part_save(part, &bytes, &len), LS_OK);
    ls_part* back = NULL;
    EXPECT(ls_part_load(bytes, len, &back), LS_OK);
    uint8_t* again = NULL;
    size_t len2 = 0;
    EXPECT(ls_part_save(back, &again, &len2), LS_OK);
    CHECK(len2 == len && memcmp(bytes, again, len) == 0);
    ls_free_bytes(again, len2);
    ls_part_free(back);
    ls_part* untouched = (ls_part*)&o;
    ls_part* out = untouched;
    bytes[len / 2] ^= 0x5a;
    EXPECT(ls_part_load(bytes, len, &out), LS_ERR_BAD_STREAM);
    CHECK(strstr(ls_last_error(), "part stream") != NULL && out == untouched);
    EXPECT(ls_part_load(bytes, len / 3, &out), LS_ERR_BAD_STREAM);
    CHECK(out == untouched);
    ls_free_bytes(bytes, len);

    /* Bad K or part: one message, nothing written. */
    int bad[][2] = {{0, 0}, {(int)nt + 1, 0}, {5, 5}, {5, -1}};
    for (int i = 0; i < 4; i++) {
        o.parts = bad[i][0];
        o.part = bad[i][1];
        EXPECT(ls_net_part(net, &o, &out), LS_ERR_INVALID_ARGUMENT);
        CHECK(strncmp(ls_last_error(), "ls_net_part:", 12) == 0 && out == untouched);
    }
    EXPECT(ls_net_part(NULL, &o, &out), LS_ERR_NULL_POINTER);
    EXPECT(ls_part_counts(NULL, &owned_n, &halo, &nv), LS_ERR_NULL_POINTER);
    EXPECT(ls_part_options_default(NULL), LS_ERR_NULL_POINTER);

    ls_free_array(global);
    ls_free_array(owned);
    ls_free_array(gverts);
    ls_free_array(owner);
    ls_surface_free(surface);
    ls_surface_free(whole);
    ls_net_free(sub);
    ls_part_free(part);
    ls_net_free(net);
}

/* The walks of a part against the whole's: the same bits wherever the walk
 * never asked for a triangle the part does not own, and that triangle named
 * otherwise. */
static void check_part_walks(const ls_surface* whole, const ls_part_surface* ps,
                             const int32_t* owner, size_t nt, int me) {
    size_t same = 0, left = 0;
    for (size_t t = 0; t < nt; t++) {
        if (owner[t] != me) continue;
        double target[18], guess[2] = {0.3, 0.3};
        EXPECT(ls_evaluate(whole, (int32_t)((t * 7 + 3) % nt), 0.2, 0.3, target), LS_OK);
        for (int i = 0; i < 3; i++) target[i] += 0.01 * (i + 1);
        int32_t wt, pt, left_at = -7;
        double wvw[2], wx[3], wd, pvw[2], px[3], pd;
        EXPECT(ls_project(whole, target, (int32_t)t, guess, &wt, wvw, wx, &wd), LS_OK);
        EXPECT(ls_part_project(ps, target, (int32_t)t, guess, &pt, pvw, px, &pd, &left_at), LS_OK);
        CHECK(pt >= 0 && (size_t)pt < nt && owner[pt] == me);
        if (left_at == -1) {
            same++;
            CHECK(pt == wt && memcmp(pvw, wvw, sizeof pvw) == 0);
            CHECK(memcmp(px, wx, sizeof px) == 0 && memcmp(&pd, &wd, sizeof pd) == 0);
        } else {
            left++;
            CHECK(left_at >= 0 && (size_t)left_at < nt && owner[left_at] != me);
        }
    }
    CHECK(same > 10 && left > 10);
}

/* Closest points over every part: the nearest of the parts' answers is the
 * whole's, and a part whose answer is farther names a nearer part. */
static void check_part_closest(const ls_surface* whole, ls_part_surface* const* parts,
                               int k, size_t nt, double tol) {
    for (size_t i = 0; i < 30; i++) {
        double p[18];
        EXPECT(ls_evaluate(whole, (int32_t)(i * 29 % nt), 0.25, 0.5, p), LS_OK);
        p[0] += 0.05 * (double)(i % 3);
        p[2] -= 0.04 * (double)(i % 5);
        int32_t wt;
        double wvw[2], wx[3], wd, best = INFINITY;
        EXPECT(ls_snap(whole, p, &wt, wvw, wx, &wd), LS_OK);
        double d[8];
        size_t count[8];
        int32_t nearer[8][8];
        for (int q = 0; q < k; q++) {
            int32_t t;
            double vw[2], x[3];
            EXPECT(ls_part_closest_point(parts[q], p, &t, vw, x, &d[q], 8, nearer[q], &count[q]),
                   LS_OK);
            CHECK(d[q] >= wd - tol && count[q] < (size_t)k);
            best = d[q] < best ? d[q] : best;
            size_t only_count = 99;
            EXPECT(ls_part_closest_point(parts[q], p, &t, vw, x, &d[q], 0, NULL, &only_count),
                   LS_OK);
            CHECK(only_count == count[q]);
        }
        CHECK(fabs(best - wd) <= tol);
        for (int q = 0; q < k; q++) {
            if (d[q] <= wd + tol) continue;
            int named = 0; /* a part holding the whole's answer is named */
            for (size_t j = 0; j < count[q]; j++) {
                CHECK(nearer[q][j] != q && (j == 0 || nearer[q][j] > nearer[q][j - 1]));
                named |= d[nearer[q][j]] <= wd + tol;
            }
            CHECK(named);
        }
    }
}

/* ls_part_surface: walks and closest points of the parts of the pig in 5,
 * against the whole surface; refusals write nothing. */
static void test_part_surface(const char* data_dir) {
    ls_surface* whole = NULL;
    ls_partition_options po;
    ls_net* net = pig_in_five(data_dir, &whole, &po);
    size_t nt = 0, cut = 0, k = 0;
    int32_t* owner = NULL;
    double* bounds = NULL;
    EXPECT(ls_net_partition(net, &po, &nt, &owner, &cut), LS_OK);
    EXPECT(ls_net_part_bounds(net, &po, &k, &bounds), LS_OK);
    CHECK(k == 5);
    double diag = 0; /* every limit point lies in its owner's box */
    for (size_t t = 0; t < nt; t++) {
        double x[18];
        EXPECT(ls_evaluate(whole, (int32_t)t, 0.3, 0.3, x), LS_OK);
        const double* b = bounds + 6 * owner[t];
        for (int i = 0; i < 3; i++) CHECK(b[i] <= x[i] && x[i] <= b[3 + i]);
    }
    for (int i = 0; i < 3; i++) diag += (bounds[3 + i] - bounds[i]) * (bounds[3 + i] - bounds[i]);

    ls_part_options o;
    EXPECT(ls_part_options_default(&o), LS_OK);
    o.parts = 5;
    ls_part_surface* parts[5] = {NULL};
    for (int q = 0; q < 5; q++) {
        ls_part* part = NULL;
        o.part = q;
        EXPECT(ls_net_part(net, &o, &part), LS_OK);
        EXPECT(ls_part_surface_build(part, q, k, bounds, &parts[q]), LS_OK);
        ls_part_free(part);
    }
    check_part_walks(whole, parts[3], owner, nt, 3);
    size_t before = 0, after = 0;
    EXPECT(ls_part_surface_bytes(parts[3], &before), LS_OK);
    check_part_closest(whole, parts, 5, nt, 1e-10 * sqrt(diag) * 5);
    EXPECT(ls_part_surface_bytes(parts[3], &after), LS_OK);
    CHECK(before > 0 && after > before); /* the snap index is made */

    /* Refusals: nothing written. */
    int32_t t = -5, left_at = -5, other = 0;
    while (owner[other] == 3) other++;
    double x[3] = {0, 0, 0}, vw[2] = {0.3, 0.3}, xo[3], d = SENTINEL;
    EXPECT(ls_part_project(parts[3], x, other, vw, &t, vw, xo, &d, &left_at),
           LS_ERR_INVALID_ARGUMENT);
    CHECK(strncmp(ls_last_error(), "ls_part_project:", 16) == 0);
    EXPECT(ls_part_project(parts[3], x, -1, vw, &t, vw, xo, &d, &left_at), LS_ERR_INVALID_ARGUMENT);
    EXPECT(ls_part_project(parts[3], x, 0, vw, &t, vw, xo, &d, NULL), LS_ERR_NULL_POINTER);
    size_t n = 77;
    EXPECT(ls_part_closest_point(parts[3], x, &t, vw, xo, &d, 2, NULL, &n), LS_ERR_NULL_POINTER);
    x[0] = NAN;
    EXPECT(ls_part_closest_point(parts[3], x, &t, vw, xo, &d, 0, NULL, &n), LS_ERR_NOT_FINITE);
    CHECK(t == -5 && left_at == -5 && d == SENTINEL && n == 77);
    ls_part_surface* out = (ls_part_surface*)&o;
    ls_part* part = NULL;
    EXPECT(ls_net_part(net, &o, &part), LS_OK);
    EXPECT(ls_part_surface_build(part, 5, k, bounds, &out), LS_ERR_INVALID_ARGUMENT);
    EXPECT(ls_part_surface_build(part, -1, k, bounds, &out), LS_ERR_INVALID_ARGUMENT);
    EXPECT(ls_part_surface_build(part, 0, k, NULL, &out), LS_ERR_NULL_POINTER);
    CHECK(out == (ls_part_surface*)&o);
    EXPECT(ls_net_part_bounds(net, &po, &k, NULL), LS_ERR_NULL_POINTER);
    EXPECT(ls_part_surface_bytes(NULL, &n), LS_ERR_NULL_POINTER);
    ls_part_surface_free(NULL);

    ls_part_free(part);
    for (int q = 0; q < 5; q++) ls_part_surface_free(parts[q]);
    ls_free_array(bounds);
    ls_free_array(owner);
    ls_surface_free(whole);
    ls_net_free(net);
}

/* ls_net_fit: a new net whose limit passes within the tolerance of every
 * vertex; the defaults as documented; refusals name their field and leave
 * the output untouched. */
static void test_fit(void) {
    ls_net* net = NULL;
    ls_surface* s = octahedron(&net);
    ls_surface_free(s);
    EXPECT(ls_net_tag_by_angle(net, 30, NULL), LS_OK);
    ls_fit_options o;
    EXPECT(ls_fit_options_default(&o), LS_OK);
    CHECK(o.struct_size == sizeof o && o.resolution == 0.01 && o.tolerance == 1e-4);
    ls_net* fitted = NULL;
    EXPECT(ls_net_fit(net, NULL, &fitted), LS_OK);
    size_t nv = 0, nt = 0, nh = 0;
    EXPECT(ls_net_counts(fitted, &nv, &nt, &nh), LS_OK);
    CHECK(nv > 100 && nt == 2 * nv - 4 && nh >= 12);
    /* Every octahedron vertex is a corner of the fitted surface: on it. */
    ls_surface* surface = NULL;
    EXPECT(ls_surface_build(fitted, &surface), LS_OK);
    for (int i = 0; i < 6; i++) {
        ls_snap_result r;
        r.struct_size = sizeof r;
        EXPECT(ls_snap_certified(surface, OCTA_XYZ + 3 * i, NULL, &r), LS_OK);
        CHECK(r.distance <= 1e-4 * 2 * sqrt(3.0));
    }
    ls_surface_free(surface);
    ls_net_free(fitted);

    ls_net* const untouched = (ls_net*)&SENTINEL;
    fitted = untouched;
    o.resolution = 2;
    EXPECT(ls_net_fit(net, &o, &fitted), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "resolution") != NULL && fitted == untouched);
    o.resolution = 0.03;
    o.tolerance = -1;
    EXPECT(ls_net_fit(net, &o, &fitted), LS_ERR_INVALID_ARGUMENT);
    CHECK(strstr(ls_last_error(), "tolerance") != NULL && fitted == untouched);
    EXPECT(ls_net_fit(NULL, &o, &fitted), LS_ERR_NULL_POINTER);
    CHECK(fitted == untouched);
    ls_net_free(net);
}

int main(int argc, char** argv) {
    const char* data_dir = argc > 1 ? argv[1] : ".";
    CHECK(strcmp(ls_last_error(), "") == 0); /* nothing failed yet on this thread */
    const char* tmp = getenv("TMPDIR");
    snprintf(scratch_dir, sizeof scratch_dir, "%s/loopsurf-api-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(scratch_dir)) {
        fprintf(stderr, "cannot make a scratch directory %s\n", scratch_dir);
        return 1;
    }
    test_version_and_strings();
    test_nets(data_dir);
    test_repairs(data_dir);
    test_partition(data_dir);
    test_part(data_dir);
    test_part_surface(data_dir);
    test_queries();
    test_refine();
    test_mesh();
    test_mesh_labels(data_dir);
    test_remesh(data_dir);
    test_remesh_job();
    test_mesh_curve();
    test_trimesh_write();
    test_adapt();
    test_streams();
    test_fit();
    const char* names[] = {"api_test.xyz", "api_test_bad.off", "api_test_trunc.off", "api_test_nm.off",
                           "api_test_flat.off", "api_shuffled.off"};
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) remove(scratch(names[i]));
    CHECK(rmdir(scratch_dir) == 0);
    if (failures) {
        fprintf(stderr, "%d checks failed\n", failures);
        return 1;
    }
    printf("C API: all checks passed\n");
    return 0;
}
