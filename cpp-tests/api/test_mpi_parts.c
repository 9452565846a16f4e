/* The partitioned MPI pattern: rank 0 reads the mesh, partitions it and
 * sends each rank only its part's stream (in pieces of at most INT_MAX
 * bytes, as a part of 2 GiB and more needs); each rank builds the surface
 * of its part alone and evaluates its owned triangles; the gathered
 * results equal rank 0's serial evaluation of the whole surface bit for
 * bit, and every triangle is evaluated by exactly one rank.
 * Usage: test_mpi_parts MESH */
#include <loopsurf.h>
#include <mpi.h>

#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Where each owned triangle is evaluated: corners, an edge, inside. */
static const double PARAMS[][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0.5}, {0.2, 0.3}, {0.125, 0.625}};
#define NP (int)(sizeof PARAMS / sizeof PARAMS[0])

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

/* Rank 0: the whole net's parts, one stream to each rank; returns rank
 * 0's own stream and its length. */
static uint8_t* scatter_parts(ls_net* net, int size, size_t* own_len) {
    uint8_t* own = NULL;
    for (int r = 0; r < size; r++) {
        ls_part_options o;
        ls_part_options_default(&o);
        o.parts = size;
        o.part = r;
        ls_part* part = NULL;
        uint8_t* bytes = NULL;
        size_t len = 0;
        if (ls_net_part(net, &o, &part) != LS_OK || ls_part_save(part, &bytes, &len) != LS_OK) fail("partition", 0);
        ls_part_free(part);
        if (r == 0) {
            own = bytes;
            *own_len = len;
            continue;
        }
        unsigned long long n = len;
        MPI_Send(&n, 1, MPI_UNSIGNED_LONG_LONG, r, 0, MPI_COMM_WORLD);
        transfer(bytes, n, r, 1);
        ls_free_bytes(bytes, len);
    }
    return own;
}

/* This rank's part alone: its surface evaluates its owned triangles at
 * PARAMS; writes their global ids and records, returns how many. */
static int evaluate_own(const uint8_t* stream, size_t len, int rank, int** ids, double** records, int* failed) {
    ls_part* part = NULL;
    ls_net* net = NULL;
    ls_surface* surface = NULL;
    if (ls_part_load(stream, len, &part) != LS_OK || ls_part_net(part, &net) != LS_OK ||
        ls_surface_build(net, &surface) != LS_OK)
        fail("building the part", rank);
    size_t ntris = 0, owned_count = 0, halo = 0, nverts = 0;
    int32_t *global = NULL, *owned = NULL;
    if (ls_part_triangles(part, &ntris, &global, &owned) != LS_OK ||
        ls_part_counts(part, &owned_count, &halo, &nverts) != LS_OK)
        fail("reading the part", rank);
    printf("rank %d: part of %zu owned and %zu halo triangles, stream of %zu bytes\n", rank, owned_count, halo, len);
    int mine = 0;
    *ids = malloc((owned_count ? owned_count : 1) * sizeof **ids);
    *records = malloc((owned_count ? owned_count : 1) * NP * 18 * sizeof **records);
    for (size_t t = 0; t < ntris; t++) {
        if (!owned[t]) continue;
        for (int k = 0; k < NP; k++)
            *failed |= ls_evaluate(surface, (int)t, PARAMS[k][0], PARAMS[k][1], *records + (size_t)(mine * NP + k) * 18) != LS_OK;
        (*ids)[mine++] = global[t];
    }
    *failed |= (size_t)mine != owned_count;
    ls_free_array(global);
    ls_free_array(owned);
    ls_surface_free(surface);
    ls_net_free(net);
    ls_part_free(part);
    return mine;
}

/* Rank 0: every triangle gathered once, each record the whole surface's. */
static int check_gathered(ls_net* whole_net, int total, const int* ids, const double* all) {
    int failed = 0;
    ls_surface* whole = NULL;
    size_t n = 0;
    if (ls_surface_build(whole_net, &whole) != LS_OK || ls_surface_num_triangles(whole, &n) != LS_OK) fail("whole", 0);
    failed |= (size_t)total != n;
    char* seen = calloc(n, 1);
    double serial[18];
    for (int i = 0; i < total; i++) {
        int g = ids[i];
        if (g < 0 || (size_t)g >= n || seen[g]) {
            failed = 1;
            continue;
        }
        seen[g] = 1;
        for (int k = 0; k < NP; k++) {
            failed |= ls_evaluate(whole, g, PARAMS[k][0], PARAMS[k][1], serial) != LS_OK;
            failed |= memcmp(serial, all + (size_t)(i * NP + k) * 18, sizeof serial) != 0;
        }
    }
    printf("MPI parts: %d triangles, %d evaluations %s\n", total, total * NP,
           failed ? "DIFFER" : "bit-identical to the whole surface");
    free(seen);
    ls_surface_free(whole);
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
            rcounts[r] = counts[r] * NP * 18;
            rdispls[r] = total * NP * 18;
            total += counts[r];
        }
        all_ids = malloc(total * sizeof *all_ids);
        all = malloc((size_t)total * NP * 18 * sizeof *all);
    }
    MPI_Gatherv(ids, mine, MPI_INT, all_ids, counts, displs, MPI_INT, 0, MPI_COMM_WORLD);
    MPI_Gatherv(records, mine * NP * 18, MPI_DOUBLE, all, rcounts, rdispls, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    int failed = rank == 0 ? check_gathered(whole_net, total, all_ids, all) : 0;
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
    ls_net* whole_net = NULL;
    uint8_t* stream = NULL;
    size_t len = 0;
    if (rank == 0) {
        if (argc < 2 || ls_net_load(argv[1], &whole_net) != LS_OK || ls_net_tag_by_angle(whole_net, 30, NULL) != LS_OK)
            fail("loading", 0);
        stream = scatter_parts(whole_net, size, &len);
    } else {
        unsigned long long n = 0;
        MPI_Recv(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        stream = malloc(n ? n : 1);
        transfer(stream, n, 0, 0);
        len = (size_t)n;
    }
    int failed = 0, *ids = NULL;
    double* records = NULL;
    int mine = evaluate_own(stream, len, rank, &ids, &records, &failed);
    failed |= gather_and_check(whole_net, rank, size, mine, ids, records);
    if (rank == 0) {
        ls_free_bytes(stream, len);
        ls_net_free(whole_net);
    } else {
        free(stream);
    }
    free(ids);
    free(records);
    int any = 0;
    MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
    MPI_Finalize();
    return any ? 1 : 0;
}
