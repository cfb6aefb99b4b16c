/* The world of ranks on Open MPI (vb_world.h); built with VORBALL_WITH_MPI.
 * Every MPI call of the project is in this file.
 *
 * MPI's own errors: MPI_COMM_WORLD returns them (MPI_ERRORS_RETURN) so
 * that the rank can say which call failed (E150, naming the rank) before
 * it aborts the job; a collective that failed leaves no state the ranks
 * could agree on, so nothing else is attempted.
 *
 * Test knob: VORBALL_TEST_FAIL_RANK=R makes rank R fail (E6, "failure
 * injected") at its first vb_world_agree, as a rank whose device or memory
 * failed would. */
#define _GNU_SOURCE /* sched_getaffinity, CPU_COUNT */
#include "vb_world.h"

#include <mpi.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli_common.h"
#include "vb_diag.h"

/* Bytes per point-to-point message: MPI counts are ints. */
#define CHUNK (1u << 30)

static struct {
    int up;             /* MPI_Init_thread succeeded and MPI_Finalize is due */
    int rank, size;
    int stopped;        /* an agree failed because of another rank */
    int injected;       /* VORBALL_TEST_FAIL_RANK already fired */
    FILE *diag;         /* ranks > 0: the context's diagnostic records, kept */
    char *diag_buf;
    size_t diag_len;
} W = {0, 0, 1, 0, 0, NULL, NULL, 0};

/* The exit status of catalogue entry E<number>. */
static int exit_of(int number)
{
#define EXIT_OF(kind, num, name, exit, meaning)                                                   \
    if (#kind[0] == 'E' && num == number)                                                       \
        return exit;
    VB_DIAG_LIST(EXIT_OF)
#undef EXIT_OF
    return VB_EXIT_INTERNAL;
}

/* An MPI call failed: nothing can be agreed any more. */
static void mpi_die(const char *what, int err)
{
    char s[MPI_MAX_ERROR_STRING] = "";
    int n = 0;
    MPI_Error_string(err, s, &n);
    fprintf(stderr, "vorball: E%d: rank %d of %d: %s: %s\n", VB_E_MPI_FAILED, W.rank, W.size, what,
            s);
    fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, exit_of(VB_E_MPI_FAILED));
    exit(exit_of(VB_E_MPI_FAILED));
}

#define MPI_CHECK(call)                                                                            \
    do {                                                                                           \
        int e_ = (call);                                                                           \
        if (e_ != MPI_SUCCESS)                                                                     \
            mpi_die(#call, e_);                                                                    \
    } while (0)

/* Out of memory in the middle of a collective: the other ranks wait on
 * this one, so the job stops here. */
static void oom_die(const char *what)
{
    fprintf(stderr, "vorball: E%d: rank %d of %d: out of memory (%s)\n", vb_diag_number(VB_ENOMEM),
            W.rank, W.size, what);
    fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, exit_of(vb_diag_number(VB_ENOMEM)));
    exit(exit_of(vb_diag_number(VB_ENOMEM)));
}

/* CPUs this process may run on: the online CPUs, or fewer when mpirun
 * bound it to some. */
static long usable_cpus(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
#ifdef CPU_COUNT
    cpu_set_t set;
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0 &&
        (n < 1 || CPU_COUNT(&set) < n))
        n = CPU_COUNT(&set);
#endif
    return n < 1 ? 1 : n;
}

static void set_default(const char *name, long value)
{
    const char *v = getenv(name);
    if (v && *v)
        return;
    char buf[32];
    snprintf(buf, sizeof buf, "%ld", value);
    setenv(name, buf, 1);
}

/* One device and a share of the CPUs for each rank on a host. */
static void share_host(void)
{
    MPI_Comm local;
    MPI_CHECK(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &local));
    int lrank = 0, lsize = 1;
    MPI_CHECK(MPI_Comm_rank(local, &lrank));
    MPI_CHECK(MPI_Comm_size(local, &lsize));
    MPI_CHECK(MPI_Comm_free(&local));
    if (lsize < 2)
        return;
    set_default("VORBALL_DEVICE_INDEX", lrank);
    /* Bound to a few cores, a rank keeps them; unbound, it takes its share. */
    long online = sysconf(_SC_NPROCESSORS_ONLN), usable = usable_cpus();
    long share = (online > 0 ? online : 1) / lsize;
    long threads = share < usable ? share : usable;
    if (threads < 1)
        threads = 1;
    set_default("VORBALL_THREADS", threads);
    set_default("POCL_MAX_PTHREAD_COUNT", threads);  /* PoCL 3 */
    set_default("POCL_CPU_MAX_CU_COUNT", threads);   /* PoCL 4 and later */
}

int vb_world_init(int *argc, char ***argv)
{
    int provided = 0;
    if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
        fprintf(stderr, "vorball: E%d: MPI_Init_thread failed\n", VB_E_MPI_FAILED);
        return exit_of(VB_E_MPI_FAILED);
    }
    W.up = 1;
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    MPI_CHECK(MPI_Comm_rank(MPI_COMM_WORLD, &W.rank));
    MPI_CHECK(MPI_Comm_size(MPI_COMM_WORLD, &W.size));
    share_host();
    /* Only rank 0 writes: help texts and stdout outputs of the others go
     * nowhere. */
    if (W.rank > 0 && !freopen("/dev/null", "w", stdout))
        fclose(stdout);
    return 0;
}

int vb_world_finish(int exit_code)
{
    if (W.diag)
        fclose(W.diag);
    free(W.diag_buf);
    W.diag = NULL;
    W.diag_buf = NULL;
    if (W.up)
        MPI_Finalize();
    W.up = 0;
    return exit_code;
}

int vb_world_rank(void)
{
    return W.rank;
}

int vb_world_size(void)
{
    return W.size;
}

int vb_world_check_command(const char *cmd)
{
    if (W.size < 2 || strcmp(cmd, "vertices") == 0 || strcmp(cmd, "bench") == 0 ||
        strcmp(cmd, "channels") == 0)
        return 0;
    if (W.rank == 0)
        fprintf(stderr,
                "vorball: E%d: '%s' runs on one process only, not on %d MPI ranks (vertices, "
                "bench and channels split their work; run '%s' without mpirun or with -np 1)\n",
                VB_E_MPI_COMMAND, cmd, W.size, cmd);
    return exit_of(VB_E_MPI_COMMAND);
}

int vb_world_check_input(const char *cmd, const char *path)
{
    if (W.size < 2 || !path || strcmp(path, "-") != 0)
        return 0;
    if (W.rank == 0)
        fprintf(stderr,
                "vorball: E%d: %s: every one of the %d MPI ranks reads the input, and only rank 0 "
                "has stdin: give a file, not '-'\n",
                VB_E_MPI_STDIN, cmd, W.size);
    return exit_of(VB_E_MPI_STDIN);
}

/* A rank's kept diagnostic record (the context's log callback), as five
 * NUL-terminated fields: kind, number, line, file ("" for none), message.
 * Rank 0 prints it, tagged with the ranks that gave it: no text is parsed. */
static void keep_record(void *arg, const vb_diag_record *r)
{
    (void)arg;
    fprintf(W.diag, "%c%c%d%c%ld%c%s%c%s%c", r->kind, 0, r->number, 0, r->line, 0,
            r->file ? r->file : "", 0, r->message, 0);
}

int vb_world_open_ctx(vb_ctx **ctx)
{
    if (W.rank == 0 || W.size < 2)
        return vb_open(ctx, NULL);
    if (!W.diag && !(W.diag = open_memstream(&W.diag_buf, &W.diag_len)))
        return VB_ENOMEM;
    int rc = vb_open(ctx, NULL);
    if (rc == VB_OK)
        vb_set_log(*ctx, keep_record, NULL);
    return rc;
}

int vb_world_quiet(vb_ctx *ctx)
{
    return W.rank > 0 ? vb_set_verbosity(ctx, 0) : -1;
}

void vb_world_loud(vb_ctx *ctx, int saved)
{
    if (saved >= 0)
        vb_set_verbosity(ctx, saved);
}

/* Every rank's own status, on every rank; the lowest failing rank or -1. */
static int statuses(int own, int *codes)
{
    MPI_CHECK(MPI_Allgather(&own, 1, MPI_INT, codes, 1, MPI_INT, MPI_COMM_WORLD));
    for (int r = 0; r < W.size; r++)
        if (codes[r] != VB_OK)
            return r;
    return -1;
}

int vb_world_agree(vb_ctx *ctx, int rc)
{
    if (W.size < 2)
        return rc;
    const char *knob = getenv("VORBALL_TEST_FAIL_RANK");
    if (rc == VB_OK && knob && !W.injected && atoi(knob) == W.rank) {
        W.injected = 1;
        rc = vb_error(ctx, VB_EINTERNAL, NULL, 0, "failure injected (VORBALL_TEST_FAIL_RANK=%s)",
                      knob);
    }
    int *codes = malloc((size_t)W.size * sizeof *codes);
    if (!codes)
        oom_die("status of the ranks");
    int low = statuses(rc, codes);
    int job = low < 0 ? VB_OK : codes[low];
    free(codes);
    if (low < 0 || rc != VB_OK)
        return rc;
    W.stopped = 1;
    return vb_error(ctx, job, NULL, 0, "stopped: rank %d of %d failed", low, W.size);
}

/* p2p transfer of any size: the length, then chunks. */
static void send_bytes(const void *buf, size_t len, int to)
{
    uint64_t n = len;
    MPI_CHECK(MPI_Send(&n, 1, MPI_UINT64_T, to, 1, MPI_COMM_WORLD));
    for (size_t off = 0; off < len; off += CHUNK) {
        size_t k = len - off < CHUNK ? len - off : CHUNK;
        MPI_CHECK(MPI_Send((const char *)buf + off, (int)k, MPI_BYTE, to, 2, MPI_COMM_WORLD));
    }
}

static unsigned char *recv_bytes(int from, size_t *len)
{
    uint64_t n = 0;
    MPI_CHECK(MPI_Recv(&n, 1, MPI_UINT64_T, from, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE));
    unsigned char *b = malloc(n ? (size_t)n : 1);
    if (!b || n > SIZE_MAX)
        oom_die("message from another rank");
    for (size_t off = 0; off < n; off += CHUNK) {
        size_t k = n - off < CHUNK ? n - off : CHUNK;
        MPI_CHECK(MPI_Recv(b + off, (int)k, MPI_BYTE, from, 2, MPI_COMM_WORLD, MPI_STATUS_IGNORE));
    }
    *len = (size_t)n;
    return b;
}

int vb_world_gather(vb_ctx *ctx, const void *buf, size_t len, unsigned char ***parts,
                    size_t **lens)
{
    (void)ctx;
    *parts = NULL;
    *lens = NULL;
    if (W.rank > 0) {
        send_bytes(buf, len, 0);
        return VB_OK;
    }
    unsigned char **p = calloc((size_t)W.size, sizeof *p);
    size_t *l = calloc((size_t)W.size, sizeof *l);
    if (!p || !l || !(p[0] = malloc(len ? len : 1)))
        oom_die("messages of the ranks");
    if (len)
        memcpy(p[0], buf, len);
    l[0] = len;
    for (int r = 1; r < W.size; r++)
        p[r] = recv_bytes(r, &l[r]);
    *parts = p;
    *lens = l;
    return VB_OK;
}

int vb_world_sum_u64(vb_ctx *ctx, uint64_t *v, int n)
{
    (void)ctx;
    if (W.size > 1)
        MPI_CHECK(MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD));
    return VB_OK;
}

int vb_world_sum_double(vb_ctx *ctx, double *v, int n)
{
    (void)ctx;
    if (W.size > 1)
        MPI_CHECK(MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD));
    return VB_OK;
}

int vb_world_max_double(vb_ctx *ctx, double *v, int n)
{
    (void)ctx;
    if (W.size > 1)
        MPI_CHECK(MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD));
    return VB_OK;
}

void vb_world_barrier(void)
{
    if (W.size > 1)
        MPI_CHECK(MPI_Barrier(MPI_COMM_WORLD));
}

/* ---- the end of a command: what rank 0 prints ---------------------------- */

/* "1", "0-2", "1, 3": the ranks whose flag is set, as ranges. */
static void rank_list(const unsigned char *on, char *out, size_t size)
{
    size_t n = 0;
    out[0] = '\0';
    for (int r = 0; r < W.size && n < size; r++) {
        if (!on[r] || (r > 0 && on[r - 1]))
            continue;
        int e = r;
        while (e + 1 < W.size && on[e + 1])
            e++;
        n += (size_t)snprintf(out + n, size - n, n ? ", %d" : "%d", r);
        if (e > r && n < size)
            n += (size_t)snprintf(out + n, size - n, e > r + 1 ? "-%d" : ", %d", e);
    }
}

/* One rank's report for rank 0: its own status, its error message, and
 * the records it kept (keep_record), as "code message\0 records". */
typedef struct report {
    int code;
    const char *msg, *rec, *end;  /* records: [rec, end) */
} report;

/* The length of the record at p (five NUL-terminated fields) before end,
 * or 0 when it is cut short. */
static size_t record_len(const char *p, const char *end)
{
    const char *q = p;
    for (int k = 0; k < 5; k++) {
        const char *z = memchr(q, '\0', (size_t)(end - q));
        if (!z)
            return 0;
        q = z + 1;
    }
    return (size_t)(q - p);
}

static int parse_report(const unsigned char *b, size_t len, report *r)
{
    if (len < sizeof(int) + 1 || b[len - 1] != '\0')
        return -1;
    memcpy(&r->code, b, sizeof(int));
    r->msg = (const char *)b + sizeof(int);
    r->rec = r->msg + strlen(r->msg) + 1;
    r->end = (const char *)b + len;
    for (const char *p = r->rec; p < r->end;) {
        size_t l = record_len(p, r->end);
        if (!l)
            return -1;
        p += l;
    }
    return 0;
}

/* A record as rank 0 prints it: "vorball: W760: ranks 1-2 of 3: file:line:
 * message", as vb_warn would with the ranks after the number. */
static void print_tagged(const char *rec, const char *ranks, int plural)
{
    const char *kind = rec, *number = kind + strlen(kind) + 1;
    const char *line = number + strlen(number) + 1, *file = line + strlen(line) + 1;
    const char *msg = file + strlen(file) + 1;
    fputs("vorball: ", stderr);
    if (kind[0] == 'W')
        fprintf(stderr, "W%s: ", number);
    fprintf(stderr, "%s %s of %d: ", plural ? "ranks" : "rank", ranks, W.size);
    if (*file && strcmp(line, "0") != 0)
        fprintf(stderr, "%s:%s: ", file, line);
    else if (*file)
        fprintf(stderr, "%s: ", file);
    fprintf(stderr, "%s\n", msg);
}

/* Whether rank q kept the record [p, p + len). */
static int kept_by(const report *q, const char *p, size_t len)
{
    for (const char *m = q->rec; m < q->end;) {
        size_t ml = record_len(m, q->end);
        if (ml == len && memcmp(m, p, len) == 0)
            return 1;
        m += ml;
    }
    return 0;
}

/* The records of ranks 1.., each distinct one once, in the order first
 * given, with the ranks that gave it. */
static void print_kept(const report *rep)
{
    unsigned char *on = calloc((size_t)W.size, 1);
    char *ranks = malloc(16 * (size_t)W.size + 16);
    if (!on || !ranks)
        oom_die("warnings of the ranks");
    for (int r = 1; r < W.size; r++) {
        for (const char *l = rep[r].rec; l < rep[r].end;) {
            size_t len = record_len(l, rep[r].end);
            int seen = 0;
            /* Given by an earlier rank: printed with it already. */
            for (int q = 1; q < r && !seen; q++)
                seen = kept_by(&rep[q], l, len);
            if (!seen) {
                memset(on, 0, (size_t)W.size);
                int count = 0;
                for (int q = r; q < W.size; q++)
                    if (kept_by(&rep[q], l, len)) {
                        count++;
                        on[q] = 1;
                    }
                rank_list(on, ranks, 16 * (size_t)W.size + 16);
                print_tagged(l, ranks, count > 1);
            }
            l += len;
        }
    }
    free(on);
    free(ranks);
}

/* The errors: each distinct (status, message) once, with its ranks. */
static void print_errors(const report *rep)
{
    unsigned char *on = calloc((size_t)W.size, 1);
    char *ranks = malloc(16 * (size_t)W.size + 16);
    if (!on || !ranks)
        oom_die("errors of the ranks");
    for (int r = 0; r < W.size; r++) {
        if (rep[r].code == VB_OK)
            continue;
        int seen = 0;
        for (int q = 0; q < r && !seen; q++)
            seen = rep[q].code == rep[r].code && strcmp(rep[q].msg, rep[r].msg) == 0;
        if (seen)
            continue;
        memset(on, 0, (size_t)W.size);
        int count = 0;
        for (int q = r; q < W.size; q++)
            if (rep[q].code == rep[r].code && strcmp(rep[q].msg, rep[r].msg) == 0)
                on[q] = 1, count++;
        rank_list(on, ranks, 16 * (size_t)W.size + 16);
        fprintf(stderr, "vorball: E%d: %s %s of %d: %s\n", vb_diag_number(rep[r].code),
                count > 1 ? "ranks" : "rank", ranks, W.size,
                rep[r].msg[0] ? rep[r].msg : vb_errstr(rep[r].code));
    }
    free(on);
    free(ranks);
}

int vb_world_end(vb_ctx *ctx, int rc)
{
    if (W.size < 2)
        return rc == VB_OK ? VB_EXIT_OK : vb_cli_fail(ctx, rc);
    /* A rank stopped by another's failure has none of its own. */
    int own = W.stopped ? VB_OK : rc;
    int *codes = malloc((size_t)W.size * sizeof *codes);
    if (!codes)
        oom_die("status of the ranks");
    int low = statuses(own, codes);
    int job = low < 0 ? VB_OK : codes[low];
    free(codes);
    /* Each rank's report to rank 0. */
    const char *msg = own != VB_OK ? vb_errmsg(ctx) : "";
    const char *rec = "";
    size_t ld = 0;
    if (W.diag) {
        fflush(W.diag);
        rec = W.diag_buf ? W.diag_buf : "";
        ld = W.diag_buf ? W.diag_len : 0;
    }
    size_t lm = strlen(msg), len = sizeof(int) + lm + 1 + ld;
    unsigned char *mine = malloc(len);
    if (!mine)
        oom_die("report to rank 0");
    memcpy(mine, &own, sizeof(int));
    memcpy(mine + sizeof(int), msg, lm + 1);
    memcpy(mine + sizeof(int) + lm + 1, rec, ld);
    unsigned char **parts = NULL;
    size_t *lens = NULL;
    vb_world_gather(ctx, mine, len, &parts, &lens);
    free(mine);
    if (W.rank == 0) {
        report *rep = calloc((size_t)W.size, sizeof *rep);
        if (!rep)
            oom_die("reports of the ranks");
        for (int r = 0; r < W.size; r++)
            if (parse_report(parts[r], lens[r], &rep[r]) != 0)
                rep[r] = (report){VB_EINTERNAL, "garbled report", "", ""};
        fflush(stderr);
        print_kept(rep);
        print_errors(rep);
        if (low >= 0 && rep[0].code == VB_OK)
            vb_warn(ctx, VB_W_MPI_STOPPED, NULL, 0,
                    "rank %d of %d failed (E%d): every rank stopped", low, W.size,
                    vb_diag_number(job));
        fflush(stderr);
        free(rep);
        for (int r = 0; r < W.size; r++)
            free(parts[r]);
        free(parts);
        free(lens);
    }
    return job == VB_OK ? VB_EXIT_OK : vb_diag_exit(job);
}
