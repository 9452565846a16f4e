/* loopsurf-mpi: `loopsurf mesh` on the ranks of an MPI job. Every rank
 * runs it with the same arguments; each reads the control net, the ranks
 * share out the remeshing in parts (ls_remesh_job: each stage, every rank
 * meshes its share of the parts and MPI_Allgatherv hands what the next
 * stage needs to all: the first pass's pieces near the interfaces, whose
 * interiors stay with the rank that made them, then the remeshed pieces
 * of that band), and each writes its piece of the mesh with the global node ids
 * (ls_trimesh_write): for -o OUT.pvtu, rank q writes OUT_q.vtu and rank 0
 * the .pvtu that names them; for -o OUT.msh, rank q writes OUT_q.msh
 * (gmsh 4.1), its nodes tagged global id + 1 and its elements tagged from
 * an offset of its own, so that gmsh merging the files shares the border
 * nodes and keeps every element. The pieces merged on their global ids
 * are the mesh `loopsurf mesh --parts K` makes, bit for bit, on any
 * number of ranks.
 *
 * Usage (`loopsurf-mpi --help` prints it): mpirun -np N loopsurf-mpi MESH
 *          [--hard-angle DEG] [--repair] [--size H] [--tolerance EPS]
 *          [--adapt curvature] [--gradation G] [--max-triangles N]
 *          [--parts K] [--threads T] [--binary] [--verbose]
 *          -o OUT.pvtu|OUT.msh
 * The options mean what they mean to `loopsurf mesh`; K defaults to the
 * number of ranks (at least 2), T to the library's default. --binary
 * writes binary .msh, or .vtu pieces with base64 arrays. --verbose
 * prints, per stage, the slowest rank's time in its tasks, in the
 * exchange and in advancing (every rank advances alike: joins and cuts
 * are not shared out), and each rank's peak resident
 * memory so far (getrusage), so a run that is to grow can be sized. Bad
 * arguments or input: one line on rank 0's stderr, exit status 2. */
#include <loopsurf.h>
#include <mpi.h>

#include <errno.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

typedef struct {
    const char* input;
    const char* output;
    double hard_angle;
    int has_hard_angle, repair, adapt, verbose, binary, msh;
    ls_remesh_options remesh;
    int has_size, has_tolerance;
} args;

static int rank_, ranks_;

static const char USAGE[] =
    "usage: mpirun -np N loopsurf-mpi MESH [options] -o OUT.pvtu|OUT.msh\n"
    "\n"
    "Remeshes MESH's limit surface in parts shared out among the ranks, as\n"
    "`loopsurf mesh --parts K` does on threads (the merged pieces are its mesh,\n"
    "bit for bit), and writes each rank's piece with global node ids.\n"
    "\n"
    "  -o, --output OUT      OUT.pvtu: rank q writes OUT_q.vtu, rank 0 the .pvtu;\n"
    "                        OUT.msh: rank q writes OUT_q.msh (gmsh 4.1)\n"
    "  --hard-angle DEG      tag every edge whose dihedral angle exceeds DEG as hard\n"
    "  --repair              triangulate, orient, split non-manifold vertices, keep\n"
    "                        degenerate triangles while reading\n"
    "  --size H              target edge length (model units)\n"
    "  --tolerance EPS       chord tolerance, times the bounding-box diagonal\n"
    "  --adapt curvature     sizes by curvature under the tolerance (the default\n"
    "                        without --size or --tolerance)\n"
    "  --gradation G         largest ratio of neighbouring sizes per edge\n"
    "  --max-triangles N     the triangle budget\n"
    "  --parts K             parts of the control net (default: the rank count, at\n"
    "                        least 2)\n"
    "  --threads T           threads per rank\n"
    "  --binary              binary .msh, or .vtu pieces with base64 arrays\n"
    "  --verbose             per stage: the slowest rank's time in tasks, exchange\n"
    "                        and advance; every rank's peak resident memory\n"
    "  -h, --help            this text\n"
    "\n"
    "Bad arguments or input: one line on stderr, exit status 2.\n";

/* One line on rank 0, then every rank leaves with status 2. */
static void refuse(const char* fmt, const char* a, const char* b) {
    if (rank_ == 0) {
        fprintf(stderr, "loopsurf-mpi: error: ");
        fprintf(stderr, fmt, a, b);
        fprintf(stderr, "\n");
    }
    MPI_Finalize();
    exit(2);
}

/* After set-up, where every rank should fail alike: the lowest rank
 * that failed says why in one line, and every rank leaves with status 2
 * (a rank that failed alone would leave the others waiting). */
static void agree(const char* error) {
    int mine = error ? rank_ : ranks_, first = ranks_;
    MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (first == ranks_) return;
    if (rank_ == first) fprintf(stderr, "loopsurf-mpi: error: %s\n", error);
    MPI_Finalize();
    exit(2);
}

/* A library call that failed on some rank: its message, then status 2
 * on every rank (MPI_Abort, since the others may wait in a collective). */
static void check(int status, const char* what) {
    if (status != LS_OK) {
        fprintf(stderr, "loopsurf-mpi: error: rank %d: %s: %s\n", rank_, what, ls_last_error());
        MPI_Abort(MPI_COMM_WORLD, 2);
    }
}

static double number(const char* flag, const char* text) {
    char* end = NULL;
    errno = 0;
    double x = strtod(text, &end);
    if (errno != 0 || end == text || *end != '\0') refuse("%s %s: not a number", flag, text);
    return x;
}

static size_t count(const char* flag, const char* text) {
    char* end = NULL;
    errno = 0;
    unsigned long long n = strtoull(text, &end, 10);
    if (errno != 0 || end == text || *end != '\0' || text[0] == '-')
        refuse("%s %s: not a count", flag, text);
    return (size_t)n;
}

static args parse(int argc, char** argv) {
    args a;
    memset(&a, 0, sizeof a);
    check(ls_remesh_options_default(&a.remesh), "defaults");
    a.remesh.parts = 0;
    for (int i = 1; i < argc; i++) {
        const char* f = argv[i];
        const char* v = i + 1 < argc ? argv[i + 1] : NULL;
        int takes = strcmp(f, "--hard-angle") == 0 || strcmp(f, "--size") == 0 ||
                    strcmp(f, "--tolerance") == 0 || strcmp(f, "--adapt") == 0 ||
                    strcmp(f, "--gradation") == 0 || strcmp(f, "--max-triangles") == 0 ||
                    strcmp(f, "--parts") == 0 || strcmp(f, "--threads") == 0 ||
                    strcmp(f, "-o") == 0 || strcmp(f, "--output") == 0;
        if (takes && v == NULL) refuse("%s needs a value%s", f, "");
        if (strcmp(f, "-h") == 0 || strcmp(f, "--help") == 0) {
            if (rank_ == 0) fputs(USAGE, stdout);
            MPI_Finalize();
            exit(0);
        } else if (strcmp(f, "--hard-angle") == 0) {
            a.hard_angle = number(f, v);
            a.has_hard_angle = 1;
        } else if (strcmp(f, "--verbose") == 0) {
            a.verbose = 1;
            continue;
        } else if (strcmp(f, "--repair") == 0) {
            a.repair = 1;
            continue;
        } else if (strcmp(f, "--binary") == 0) {
            a.binary = 1;
            continue;
        } else if (strcmp(f, "--size") == 0) {
            a.remesh.size = number(f, v);
            a.has_size = 1;
        } else if (strcmp(f, "--tolerance") == 0) {
            a.remesh.tolerance = number(f, v);
            a.has_tolerance = 1;
        } else if (strcmp(f, "--adapt") == 0) {
            if (strcmp(v, "curvature") != 0) refuse("--adapt %s: only curvature%s", v, "");
            a.adapt = 1;
        } else if (strcmp(f, "--gradation") == 0) {
            a.remesh.gradation = number(f, v);
        } else if (strcmp(f, "--max-triangles") == 0) {
            a.remesh.max_triangles = count(f, v);
        } else if (strcmp(f, "--parts") == 0) {
            a.remesh.parts = count(f, v);
            if (a.remesh.parts == 0) refuse("--parts %s: must be at least 1%s", v, "");
        } else if (strcmp(f, "--threads") == 0) {
            a.remesh.threads = count(f, v);
        } else if (strcmp(f, "-o") == 0 || strcmp(f, "--output") == 0) {
            a.output = v;
        } else if (f[0] == '-') {
            refuse("unknown option %s (see --help)%s", f, "");
        } else if (a.input == NULL) {
            a.input = f;
            continue;
        } else {
            refuse("a second input %s (the first is %s)", f, a.input);
        }
        i++;
    }
    if (a.input == NULL) refuse("no input mesh given (see --help)%s%s", "", "");
    if (a.output == NULL) refuse("no output given (-o OUT.pvtu or OUT.msh)%s%s", "", "");
    size_t n = strlen(a.output);
    a.msh = n >= 4 && strcmp(a.output + n - 4, ".msh") == 0;
    if (!a.msh && (n < 5 || strcmp(a.output + n - 5, ".pvtu") != 0))
        refuse("-o %s: the output is a .pvtu (one .vtu piece per rank beside it) or a .msh (one "
               "OUT_rank.msh per rank)%s",
               a.output, "");
    /* As `loopsurf mesh`: with neither a size nor a tolerance, the
     * curvature-adaptive mesh at the default tolerance. */
    int adapt = a.adapt || (!a.has_size && !a.has_tolerance);
    a.remesh.adapt_curvature = adapt;
    if (!a.has_size) a.remesh.size = 0;
    if (!a.has_tolerance) a.remesh.tolerance = 0;
    if (a.remesh.parts == 0) a.remesh.parts = ranks_ < 2 ? 2 : (size_t)ranks_;
    return a;
}

/* Every rank's bytes to every rank, in rank order (MPI_Allgatherv counts
 * are ints: a stage's bytes past 2 GiB are refused). */
static uint8_t* gather(const uint8_t* mine, size_t n, size_t* counts) {
    unsigned long long own = n, all[1024];
    unsigned long long* each = ranks_ <= 1024 ? all : malloc(sizeof *each * (size_t)ranks_);
    MPI_Allgather(&own, 1, MPI_UNSIGNED_LONG_LONG, each, 1, MPI_UNSIGNED_LONG_LONG, MPI_COMM_WORLD);
    int* c = malloc(sizeof *c * (size_t)ranks_);
    int* at = malloc(sizeof *at * (size_t)ranks_);
    unsigned long long total = 0;
    for (int q = 0; q < ranks_; q++) {
        counts[q] = (size_t)each[q];
        if (total + each[q] > INT_MAX) {
            fprintf(stderr, "loopsurf-mpi: error: a stage's outcomes pass 2 GiB (MPI_Allgatherv counts are ints)\n");
            MPI_Abort(MPI_COMM_WORLD, 2);
        }
        c[q] = (int)each[q];
        at[q] = (int)total;
        total += each[q];
    }
    uint8_t* bytes = malloc(total ? total : 1);
    MPI_Allgatherv(mine, (int)n, MPI_BYTE, bytes, c, at, MPI_BYTE, MPI_COMM_WORLD);
    if (each != all) free(each);
    free(c);
    free(at);
    return bytes;
}

/* Every rank's peak resident memory so far, in MB, printed by rank 0 as
 * one line "  peak RSS after WHEN: R0, R1, ... MB" (on Linux ru_maxrss is
 * in kB). */
static void print_peak_rss(const char* when) {
    struct rusage usage;
    long mine = getrusage(RUSAGE_SELF, &usage) == 0 ? usage.ru_maxrss / 1024 : -1;
    long* all = rank_ == 0 ? malloc(sizeof *all * (size_t)ranks_) : NULL;
    MPI_Gather(&mine, 1, MPI_LONG, all, 1, MPI_LONG, 0, MPI_COMM_WORLD);
    if (rank_ == 0 && all != NULL) {
        printf("  peak RSS after %s:", when);
        for (int q = 0; q < ranks_; q++) printf("%s %ld", q ? "," : "", all[q]);
        printf(" MB\n");
    }
    free(all);
}

/* Rank q's piece: OUT_q.vtu for OUT.pvtu, OUT_q.msh for OUT.msh, and
 * its name beside OUT. */
static void piece_name(const char* out, int q, char* path, size_t size, const char** base) {
    int msh = strcmp(out + strlen(out) - 4, ".msh") == 0;
    size_t n = strlen(out) - (msh ? 4 : 5);
    snprintf(path, size, "%.*s_%d.%s", (int)n, out, q, msh ? "msh" : "vtu");
    const char* slash = strrchr(path, '/');
    *base = slash ? slash + 1 : path;
}

/* This rank's piece, nodes by their global ids; in a .msh its elements
 * are tagged from past every lower rank's (a piece has at most
 * nnodes + 4 * nelements elements: corners, lines and triangles). */
static void write_piece(const args* a, const char* path, const ls_surface* surface,
                        const ls_trimesh* m, const int64_t* ids) {
    size_t nodes = 0, elements = 0, per = 0;
    check(ls_trimesh_counts(m, &nodes, &elements, &per), "piece counts");
    unsigned long long most = nodes + 4 * (unsigned long long)elements, before = 0;
    MPI_Exscan(&most, &before, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
    if (rank_ == 0) before = 0; /* MPI_Exscan leaves rank 0's undefined */
    ls_trimesh_write_options o;
    check(ls_trimesh_write_options_default(&o), "write defaults");
    o.binary = a->binary;
    o.global_ids = ids;
    o.first_element_tag = (int64_t)before + 1;
    check(ls_trimesh_write(m, surface, path, &o), path);
}

static void write_master(const char* out) {
    FILE* f = fopen(out, "w");
    if (f == NULL) {
        fprintf(stderr, "loopsurf-mpi: error: %s: %s\n", out, strerror(errno));
        MPI_Abort(MPI_COMM_WORLD, 2);
    }
    fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
    fprintf(f, "<PUnstructuredGrid GhostLevel=\"0\">\n");
    /* The arrays every piece has (a piece without corners has no
     * "corner" array). */
    fprintf(f, "<PPointData GlobalIds=\"GlobalNodeId\">\n");
    fprintf(f, "<PDataArray type=\"Float64\" Name=\"loopsurf_params\" NumberOfComponents=\"3\"/>\n");
    fprintf(f, "<PDataArray type=\"Int64\" Name=\"GlobalNodeId\"/>\n</PPointData>\n");
    fprintf(f, "<PCellData>\n<PDataArray type=\"Int32\" Name=\"face\"/>\n");
    fprintf(f, "<PDataArray type=\"Int32\" Name=\"curve\"/>\n</PCellData>\n");
    fprintf(f, "<PPoints>\n<PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n</PPoints>\n");
    for (int q = 0; q < ranks_; q++) {
        char path[4096];
        const char* base = NULL;
        piece_name(out, q, path, sizeof path, &base);
        fprintf(f, "<Piece Source=\"%s\"/>\n", base);
    }
    fprintf(f, "</PUnstructuredGrid>\n</VTKFile>\n");
    fclose(f);
}

int main(int argc, char** argv) {
    MPI_Init(&argc, &argv);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
    args a = parse(argc, argv);
    double start = MPI_Wtime();

    ls_net* net = NULL;
    ls_surface* surface = NULL;
    ls_remesh_job* job = NULL;
    const unsigned repairs = LS_LOAD_TRIANGULATE | LS_LOAD_ORIENT | LS_LOAD_SPLIT_NONMANIFOLD | LS_LOAD_ALLOW_DEGENERATE;
    int st = a.repair ? ls_net_load_with(a.input, repairs, 0, &net) : ls_net_load(a.input, &net);
    if (st == LS_OK && a.has_hard_angle) st = ls_net_tag_by_angle(net, a.hard_angle, NULL);
    if (st == LS_OK) st = ls_surface_build(net, &surface);
    if (st == LS_OK) st = ls_remesh_job_new(surface, &a.remesh, rank_, ranks_, &job);
    agree(st == LS_OK ? NULL : ls_last_error());
    /* The surface holds what it needs of the net. */
    ls_net_free(net);
    net = NULL;
    if (a.verbose) print_peak_rss("reading the net and building its surface");

    size_t* counts = malloc(sizeof *counts * (size_t)ranks_);
    for (;;) {
        int done = 0;
        const char* stage = NULL;
        check(ls_remesh_job_done(job, &done, &stage), "job");
        if (done) break;
        const uint8_t* mine = NULL;
        size_t n = 0;
        double t[4], slowest[3];
        t[0] = MPI_Wtime();
        check(ls_remesh_job_run(job, &mine, &n), stage);
        t[1] = MPI_Wtime();
        uint8_t* all = gather(mine, n, counts);
        t[2] = MPI_Wtime();
        check(ls_remesh_job_advance(job, all, counts), stage);
        t[3] = MPI_Wtime();
        free(all);
        if (a.verbose) {
            double spent[3] = {t[1] - t[0], t[2] - t[1], t[3] - t[2]};
            MPI_Reduce(spent, slowest, 3, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
            if (rank_ == 0)
                printf("%s: tasks %.3f s, exchange %.3f s, advance %.3f s\n", stage, slowest[0], slowest[1],
                       slowest[2]);
            print_peak_rss(stage);
        }
    }
    free(counts);

    ls_trimesh* piece = NULL;
    int64_t* ids = NULL;
    check(ls_remesh_job_piece(job, &piece, &ids), "this rank's piece");
    char path[4096];
    const char* base = NULL;
    piece_name(a.output, rank_, path, sizeof path, &base);
    write_piece(&a, path, surface, piece, ids);
    if (rank_ == 0 && !a.msh) write_master(a.output);

    size_t nodes = 0, elements = 0, per = 0;
    check(ls_trimesh_counts(piece, &nodes, &elements, &per), "piece counts");
    unsigned long long mine[2] = {elements, nodes}, sum[2] = {0, 0};
    MPI_Reduce(mine, sum, 2, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
    double seconds = MPI_Wtime() - start;
    if (rank_ == 0) {
        char first[4096];
        const char* base = NULL;
        piece_name(a.output, 0, first, sizeof first, &base);
        printf("%llu triangles in %zu parts on %d ranks, in %.3f s; wrote %d pieces (%s, ...)%s%s\n", sum[0],
               a.remesh.parts, ranks_, seconds, ranks_, first, a.msh ? "" : " and ", a.msh ? "" : a.output);
    }
    if (a.verbose) print_peak_rss("writing");

    ls_free_array(ids);
    ls_trimesh_free(piece);
    ls_remesh_job_free(job);
    ls_surface_free(surface);
    MPI_Finalize();
    return 0;
}
