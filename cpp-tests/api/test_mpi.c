/* The MPI pattern: rank 0 loads and builds the surface and broadcasts its
 * stream; every rank loads it and evaluates its share; the gathered results
 * equal rank 0's serial evaluation bit for bit. Usage: test_mpi MESH */
#include <loopsurf.h>
#include <mpi.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define N 20000

int main(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    int rank, size;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    int failed = 0;

    ls_surface* original = NULL;
    uint8_t* bytes = NULL;
    unsigned long long n = 0;
    if (rank == 0) {
        ls_net* net = NULL;
        size_t len = 0;
        if (argc < 2 || ls_net_load(argv[1], &net) != LS_OK || ls_net_tag_by_angle(net, 30, NULL) != LS_OK ||
            ls_surface_build(net, &original) != LS_OK || ls_surface_save(original, &bytes, &len) != LS_OK) {
            fprintf(stderr, "rank 0 setup failed: %s\n", ls_last_error());
            MPI_Abort(MPI_COMM_WORLD, 1);
        }
        ls_net_free(net);
        n = len;
    }
    MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    uint8_t* buffer = rank == 0 ? bytes : malloc(n);
    MPI_Bcast(buffer, (int)n, MPI_BYTE, 0, MPI_COMM_WORLD);
    ls_surface* surface = NULL;
    if (ls_surface_load(buffer, (size_t)n, &surface) != LS_OK) {
        fprintf(stderr, "rank %d: load failed: %s\n", rank, ls_last_error());
        MPI_Abort(MPI_COMM_WORLD, 1);
    }

    /* The same deterministic queries everywhere; rank r takes a share. */
    size_t ntris = 0;
    ls_surface_num_triangles(surface, &ntris);
    int32_t* tri = malloc(N * sizeof *tri);
    double* vw = malloc(2 * N * sizeof *vw);
    uint64_t state = 12345;
    for (int i = 0; i < N; i++) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        tri[i] = (int32_t)((state >> 20) % ntris);
        double v = (double)((state >> 11) & 0xfffff) / 0x100000, w = (double)((state >> 33) & 0xfffff) / 0x100000;
        if (v + w > 1) v = 1 - v, w = 1 - w;
        vw[2 * i] = v, vw[2 * i + 1] = w;
    }
    int* counts = malloc(size * sizeof *counts);
    int* displs = malloc(size * sizeof *displs);
    for (int r = 0; r < size; r++) {
        int begin = (int)((long long)N * r / size), end = (int)((long long)N * (r + 1) / size);
        counts[r] = 18 * (end - begin);
        displs[r] = 18 * begin;
    }
    int begin = displs[rank] / 18, mine = counts[rank] / 18;
    double* local = malloc((size_t)(18 * (mine > 0 ? mine : 1)) * sizeof *local);
    failed |= ls_evaluate_many(surface, (size_t)mine, tri + begin, vw + 2 * begin, local) != LS_OK;
    double* gathered = rank == 0 ? malloc(18 * N * sizeof *gathered) : NULL;
    MPI_Gatherv(local, counts[rank], MPI_DOUBLE, gathered, counts, displs, MPI_DOUBLE, 0, MPI_COMM_WORLD);

    if (rank == 0) {
        double* serial = malloc(18 * N * sizeof *serial);
        for (int i = 0; i < N; i++) failed |= ls_evaluate(original, tri[i], vw[2 * i], vw[2 * i + 1], serial + 18 * i) != LS_OK;
        failed |= memcmp(serial, gathered, 18 * N * sizeof *serial) != 0;
        printf("MPI: %d ranks, stream of %llu bytes, %d evaluations %s\n", size, n, N,
               failed ? "DIFFER" : "bit-identical to the serial run");
        free(serial);
        free(gathered);
        ls_free_bytes(bytes, (size_t)n);
        ls_surface_free(original);
    } else {
        free(buffer);
    }
    int any = 0;
    MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
    ls_surface_free(surface);
    free(tri), free(vw), free(counts), free(displs), free(local);
    MPI_Finalize();
    return any ? 1 : 0;
}
