/* The partitioned MPI patterns. "scatter": rank 0 reads the mesh,
 * partitions it and sends each rank only its part's stream (in pieces of
 * at most INT_MAX bytes, as a part of 2 GiB and more needs) with every
 * part's box. "read": every rank reads the mesh and builds only its own
 * part. Each rank then builds the surface of its part alone, evaluates
 * its owned triangles, projects and snaps a point near each of them, and
 * prints the bytes its part's surface holds. On rank 0 the gathered
 * evaluations equal the whole surface's bit for bit, every triangle once;
 * a projection equals the whole's ls_project bit for bit where its walk
 * stayed on the part's triangles and names a triangle of another part
 * otherwise; a closest point is the whole's ls_snap distance (to the
 * certificate's tolerance) or names the parts that may hold a nearer one.
 * Usage: test_mpi_parts MESH scatter|read */
#include <loopsurf.h>
#include <mpi.h>

#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Where each owned triangle is evaluated: corners, an edge, inside. */
static const double PARAMS[][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0.5}, {0.2, 0.3}, {0.125, 0.625}};
#define NP (int)(sizeof PARAMS / sizeof PARAMS[0])
/* A triangle's record: NP evaluations of 18 doubles, then a projection
 * and a closest point of 8 doubles each (tri, v, w, x, y, z, distance,
 * and left_at or the count of nearer parts). */
#define EVALS (NP * 18)
#define WIDTH (EVALS + 16)
/* The point near triangle g: its limit point at PARAMS[4], moved by this. */
static const double OFFSET[3] = {0.02, -0.03, 0.05};
static const double GUESS[2] = {0.3, 0.3};

static void fail(const char* what, int rank) {
    fprintf(stderr, "rank %d: %s failed: %s\n", rank, what, ls_last_error());
    MPI_Abort(MPI_COMM_WORLD, 1);
}

/* Sends or receives n bytes in pieces an int count can hold. */
static void transfer(uint8_t* bytes, unsigned long long n, int peer, int sending) {
    for (unsigned long long at = 0; at < n; at += INT_MAX) {
        int piece = (int)(n - at < (unsigned long long)INT_MAX ? n - at : INT_MAX);
        if (sending)
            MPI_Send(bytes + at, piece, MPI_BYTE, peer, 0, MPI_COMM_WORLD);
        else
            MPI_Recv(bytes + at, piece, MPI_BYTE, peer, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    }
}

static ls_net* load(const char* path, int rank) {
    ls_net* net = NULL;
    if (ls_net_load(path, &net) != LS_OK || ls_net_tag_by_angle(net, 30, NULL) != LS_OK) fail("loading", rank);
    return net;
}

/* Part `index` of `parts` of the net. */
static ls_part* part_of(const ls_net* net, int parts, int index, int rank) {
    ls_part_options o;
    ls_part_options_default(&o);
    o.parts = parts;
    o.part = index;
    ls_part* part = NULL;
    if (ls_net_part(net, &o, &part) != LS_OK) fail("partition", rank);
    return part;
}

/* Rank 0: sends each other rank its part's stream. */
static void scatter_parts(const ls_net* net, int size) {
    for (int r = 1; r < size; r++) {
        ls_part* part = part_of(net, size, r, 0);
        uint8_t* bytes = NULL;
        size_t len = 0;
        if (ls_part_save(part, &bytes, &len) != LS_OK) fail("saving a part", 0);
        ls_part_free(part);
        unsigned long long n = len;
        MPI_Send(&n, 1, MPI_UNSIGNED_LONG_LONG, r, 0, MPI_COMM_WORLD);
        transfer(bytes, n, r, 1);
        ls_free_bytes(bytes, len);
    }
}

/* A rank other than 0: its part, from rank 0's stream. */
static ls_part* receive_part(int rank) {
    unsigned long long n = 0;
    MPI_Recv(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    uint8_t* stream = malloc(n ? n : 1);
    transfer(stream, n, 0, 0);
    ls_part* part = NULL;
    if (ls_part_load(stream, (size_t)n, &part) != LS_OK) fail("loading the part's stream", rank);
    printf("rank %d: received a part stream of %llu bytes\n", rank, n);
    free(stream);
    return part;
}

/* Every part's box (6 doubles a part): computed where the net is, sent
 * to the others in the scatter pattern. */
static double* part_bounds(const ls_net* net, int size, int rank, int broadcast) {
    ls_partition_options o;
    ls_partition_options_default(&o);
    o.parts = size;
    size_t k = (size_t)size;
    double* bounds = NULL;
    if (net && ls_net_part_bounds(net, &o, &k, &bounds) != LS_OK) fail("bounds", rank);
    if (!net) bounds = malloc(6 * k * sizeof *bounds);
    if (broadcast) MPI_Bcast(bounds, 6 * size, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    return bounds;
}

/* Projects and snaps the point near global triangle g on the part's
 * surface: writes 16 doubles at out. */
static int query(const ls_part_surface* ps, int g, const double* x, double* out) {
    double p[3];
    for (int i = 0; i < 3; i++) p[i] = x[i] + OFFSET[i];
    int32_t tri = -1, left_at = -1;
    size_t nearer = 0;
    int failed = ls_part_project(ps, p, g, GUESS, &tri, out + 1, out + 3, out + 6, &left_at) != LS_OK;
    out[0] = tri;
    out[7] = left_at;
    failed |= ls_part_closest_point(ps, p, &tri, out + 9, out + 11, out + 14, 0, NULL, &nearer) != LS_OK;
    out[8] = tri;
    out[15] = (double)nearer;
    return failed;
}

/* This rank's part alone: evaluates its owned triangles at PARAMS and
 * queries a point near each; writes their global ids and records, returns
 * how many. */
static int evaluate_own(const ls_part* part, const ls_part_surface* ps, int rank, int** ids, double** records,
                        int* failed) {
    ls_net* net = NULL;
    ls_surface* surface = NULL;
    if (ls_part_net(part, &net) != LS_OK || ls_surface_build(net, &surface) != LS_OK) fail("building the part", rank);
    size_t ntris = 0, owned_count = 0, halo = 0, nverts = 0;
    int32_t *global = NULL, *owned = NULL;
    if (ls_part_triangles(part, &ntris, &global, &owned) != LS_OK ||
        ls_part_counts(part, &owned_count, &halo, &nverts) != LS_OK)
        fail("reading the part", rank);
    int mine = 0;
    *ids = malloc((owned_count ? owned_count : 1) * sizeof **ids);
    *records = malloc((owned_count ? owned_count : 1) * WIDTH * sizeof **records);
    for (size_t t = 0; t < ntris; t++) {
        if (!owned[t]) continue;
        double* r = *records + (size_t)mine * WIDTH;
        for (int k = 0; k < NP; k++)
            *failed |= ls_evaluate(surface, (int)t, PARAMS[k][0], PARAMS[k][1], r + k * 18) != LS_OK;
        *failed |= query(ps, global[t], r + 4 * 18, r + EVALS);
        (*ids)[mine++] = global[t];
    }
    *failed |= (size_t)mine != owned_count;
    size_t bytes = 0;
    *failed |= ls_part_surface_bytes(ps, &bytes) != LS_OK;
    printf("rank %d: part of %zu owned and %zu halo triangles, its surface holds %zu bytes\n", rank, owned_count,
           halo, bytes);
    ls_free_array(global);
    ls_free_array(owned);
    ls_surface_free(surface);
    ls_net_free(net);
    return mine;
}

/* The bytes the whole surface holds, as a part of one, with every patch
 * and its snap index made. */
static size_t whole_bytes(const ls_net* net) {
    ls_part* all = part_of(net, 1, 0, 0);
    double* bounds = part_bounds(net, 1, 0, 0);
    ls_part_surface* ps = NULL;
    size_t bytes = 0, n = 0;
    int32_t tri;
    double p[3] = {0, 0, 0}, vw[2], x[3], d;
    if (ls_part_surface_build(all, 0, 1, bounds, &ps) != LS_OK ||
        ls_part_closest_point(ps, p, &tri, vw, x, &d, 0, NULL, &n) != LS_OK ||
        ls_part_surface_bytes(ps, &bytes) != LS_OK)
        fail("the whole's bytes", 0);
    ls_part_surface_free(ps);
    ls_free_array(bounds);
    ls_part_free(all);
    return bytes;
}

/* What rank 0 checks the gathered records against. */
typedef struct {
    ls_surface* whole;
    int32_t* owner; /* each triangle's part */
    size_t n;
    double tol; /* the closest points' certificate, with room */
    int same, left, alone, nearer; /* projections and closest points counted */
} Serial;

/* Rank 0: the answers near triangle g against the whole surface's. */
static int check_queries(Serial* s, int g, const double* got) {
    double x[18], p[3], vw[2], xyz[3], d;
    int32_t tri;
    int failed = ls_evaluate(s->whole, g, PARAMS[4][0], PARAMS[4][1], x) != LS_OK;
    for (int i = 0; i < 3; i++) p[i] = x[i] + OFFSET[i];
    failed |= ls_project(s->whole, p, g, GUESS, &tri, vw, xyz, &d) != LS_OK;
    const double expected[7] = {tri, vw[0], vw[1], xyz[0], xyz[1], xyz[2], d};
    int left_at = (int)got[7], at = (int)got[0];
    failed |= at < 0 || (size_t)at >= s->n || s->owner[at] != s->owner[g];
    if (left_at == -1) {
        s->same++;
        failed |= memcmp(expected, got, sizeof expected) != 0;
    } else {
        s->left++;
        failed |= left_at < 0 || (size_t)left_at >= s->n || s->owner[left_at] == s->owner[g];
    }
    failed |= ls_snap(s->whole, p, &tri, vw, xyz, &d) != LS_OK;
    failed |= got[14] < d - s->tol;
    if (got[15] == 0) {
        s->alone++;
        failed |= got[14] > d + s->tol;
    } else {
        s->nearer++;
    }
    return failed;
}

/* Rank 0: every triangle gathered once, each record the whole surface's. */
static int check_gathered(Serial* s, int total, const int* ids, const double* all) {
    int failed = (size_t)total != s->n;
    char* seen = calloc(s->n, 1);
    double serial[18];
    for (int i = 0; i < total; i++) {
        int g = ids[i];
        if (g < 0 || (size_t)g >= s->n || seen[g]) {
            failed = 1;
            continue;
        }
        seen[g] = 1;
        const double* r = all + (size_t)i * WIDTH;
        for (int k = 0; k < NP; k++) {
            failed |= ls_evaluate(s->whole, g, PARAMS[k][0], PARAMS[k][1], serial) != LS_OK;
            failed |= memcmp(serial, r + k * 18, sizeof serial) != 0;
        }
        failed |= check_queries(s, g, r + EVALS);
    }
    failed |= s->same == 0 || s->left == 0 || s->alone == 0;
    printf("MPI parts: %d triangles, %d evaluations; projections: %d the whole's, %d left their part; "
           "closest points: %d the whole's, %d name nearer parts: %s\n",
           total, total * NP, s->same, s->left, s->alone, s->nearer,
           failed ? "DIFFER" : "bit-identical to the whole surface");
    free(seen);
    return failed;
}

/* Rank 0: the whole surface, the partition, and the tolerance. */
static int check_on_rank_0(ls_net* net, int size, int total, const int* ids, const double* all) {
    Serial s = {0};
    ls_partition_options o;
    ls_partition_options_default(&o);
    o.parts = size;
    size_t cut = 0;
    double* box = part_bounds(net, 1, 0, 0);
    if (ls_surface_build(net, &s.whole) != LS_OK || ls_net_partition(net, &o, &s.n, &s.owner, &cut) != LS_OK)
        fail("the whole", 0);
    double diag = 0;
    for (int i = 0; i < 3; i++) diag += (box[3 + i] - box[i]) * (box[3 + i] - box[i]);
    s.tol = 1e-10 * sqrt(diag);
    int failed = check_gathered(&s, total, ids, all);
    printf("rank 0: the whole surface holds %zu bytes\n", whole_bytes(net));
    ls_free_array(box);
    ls_free_array(s.owner);
    ls_surface_free(s.whole);
    return failed;
}

/* Gathers every rank's ids and records on rank 0 and checks them there. */
static int gather_and_check(ls_net* whole_net, int rank, int size, int mine, int* ids, double* records) {
    int* counts = rank == 0 ? malloc(size * sizeof *counts) : NULL;
    MPI_Gather(&mine, 1, MPI_INT, counts, 1, MPI_INT, 0, MPI_COMM_WORLD);
    int total = 0, *displs = NULL, *rcounts = NULL, *rdispls = NULL, *all_ids = NULL;
    double* all = NULL;
    if (rank == 0) {
        displs = malloc(size * sizeof *displs);
        rcounts = malloc(size * sizeof *rcounts);
        rdispls = malloc(size * sizeof *rdispls);
        for (int r = 0; r < size; r++) {
            displs[r] = total;
            rcounts[r] = counts[r] * WIDTH;
            rdispls[r] = total * WIDTH;
            total += counts[r];
        }
        all_ids = malloc(total * sizeof *all_ids);
        all = malloc((size_t)total * WIDTH * sizeof *all);
    }
    MPI_Gatherv(ids, mine, MPI_INT, all_ids, counts, displs, MPI_INT, 0, MPI_COMM_WORLD);
    MPI_Gatherv(records, mine * WIDTH, MPI_DOUBLE, all, rcounts, rdispls, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    int failed = rank == 0 ? check_on_rank_0(whole_net, size, total, all_ids, all) : 0;
    free(all);
    free(all_ids);
    free(displs);
    free(rcounts);
    free(rdispls);
    free(counts);
    return failed;
}

int main(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    int rank, size;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (argc < 3 || (strcmp(argv[2], "scatter") != 0 && strcmp(argv[2], "read") != 0)) fail("usage: MESH scatter|read", rank);
    ls_net* whole_net = NULL;
    ls_part* part = NULL;
    double* bounds = NULL;
    if (strcmp(argv[2], "read") == 0) { /* every rank reads, builds its own part */
        whole_net = load(argv[1], rank);
        part = part_of(whole_net, size, rank, rank);
        bounds = part_bounds(whole_net, size, rank, 0);
        if (rank != 0) ls_net_free(whole_net);
    } else if (rank == 0) { /* rank 0 reads and sends each rank its part */
        whole_net = load(argv[1], 0);
        scatter_parts(whole_net, size);
        part = part_of(whole_net, size, 0, 0);
        bounds = part_bounds(whole_net, size, 0, 1);
    } else {
        part = receive_part(rank);
        bounds = part_bounds(NULL, size, rank, 1);
    }
    ls_part_surface* ps = NULL;
    if (ls_part_surface_build(part, rank, (size_t)size, bounds, &ps) != LS_OK) fail("the part's surface", rank);
    int failed = 0, *ids = NULL;
    double* records = NULL;
    int mine = evaluate_own(part, ps, rank, &ids, &records, &failed);
    failed |= gather_and_check(rank == 0 ? whole_net : NULL, rank, size, mine, ids, records);
    ls_part_surface_free(ps);
    ls_part_free(part);
    if (rank == 0) ls_net_free(whole_net);
    free(bounds); /* malloc'd here or by loopsurf */
    free(ids);
    free(records);
    int any = 0;
    MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
    MPI_Finalize();
    return any ? 1 : 0;
}
