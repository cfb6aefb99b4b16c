/* bench_judge: time the certification filter's host twin
 * (vb_cert_filter_judge) on the direction cover's quadruples.
 *
 *   bench_judge [--quads FILE] [--dump FILE] [--verdicts FILE] [--repeat R]
 *               [--shared] INPUT [THREADS...]
 *
 * Runs the cover (host) once, or reads its quadruples from FILE ("a b c d"
 * per line, sorted; --dump writes them so), builds the filter, then for each
 * thread count (default: 1) judges every quadruple R times (default 1) and
 * prints the process CPU and wall nanoseconds per quadruple, the counts of
 * root verdicts and an FNV-1a hash of the verdict bytes (the twin before and
 * after a change must print the same hash); --verdicts writes the bytes of
 * the first run. --shared judges with vbd_judge itself on this thread (the
 * kernel's code as the twin ran it before stop 52), whatever THREADS say:
 * the old twin beside the new in one binary. A benchmark, not a test: it fails only when two thread
 * counts give different verdicts. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vb_cert_filter.h"
#include "vb_cover.h"
#include "vt_bench.h"

static double now(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static uint64_t fnv1a(const uint8_t *b, size_t n)
{
    uint64_t h = 0xcbf29ce484222325u;
    for (size_t k = 0; k < n; k++)
        h = (h ^ b[k]) * 0x100000001b3u;
    return h;
}

int main(int argc, char **argv)
{
    const char *quadpath = NULL, *dumppath = NULL, *vpath = NULL;
    int a = 1, repeat = 1, shared = 0;
    for (; a + 1 < argc && argv[a][0] == '-'; a += 2) {
        if (strcmp(argv[a], "--shared") == 0) {
            shared = 1;
            a--;
        } else if (strcmp(argv[a], "--quads") == 0)
            quadpath = argv[a + 1];
        else if (strcmp(argv[a], "--dump") == 0)
            dumppath = argv[a + 1];
        else if (strcmp(argv[a], "--verdicts") == 0)
            vpath = argv[a + 1];
        else if (strcmp(argv[a], "--repeat") == 0)
            repeat = atoi(argv[a + 1]);
        else
            break;
    }
    if (a >= argc || repeat < 1) {
        fprintf(stderr, "usage: bench_judge [--quads FILE] [--dump FILE] [--verdicts FILE] "
                        "[--repeat R] [--shared] INPUT [THREADS...]\n");
        return 2;
    }
    const char *input = argv[a++];
    vb_ctx *ctx;
    vb_sphere_set *set;
    if (vt_bench_open("bench_judge", input, &ctx, &set))
        return 1;
    vb_quad_list q = {0};
    int rc = VB_OK;
    if (quadpath && vt_read_quads(quadpath, &q) != 0)
        rc = vb_error(ctx, VB_EIO, quadpath, 0, "cannot read");
    else if (!quadpath)
        rc = vb_cover_run(ctx, set, NULL, NULL, &q, NULL);
    vb_cert_filter f;
    memset(&f, 0, sizeof f);
    if (rc == VB_OK)
        rc = vb_cert_filter_build(ctx, set, &f);
    if (rc != VB_OK) {
        fprintf(stderr, "bench_judge: %s\n", vb_errmsg(ctx));
        return 1;
    }
    if (dumppath) {
        FILE *d = fopen(dumppath, "w");
        for (size_t k = 0; d && k < q.n; k++)
            fprintf(d, "%u %u %u %u\n", q.q[k][0], q.q[k][1], q.q[k][2], q.q[k][3]);
        if (!d || fclose(d) != 0) {
            fprintf(stderr, "bench_judge: cannot write %s\n", dumppath);
            return 1;
        }
    }
    printf("%s: %zu spheres, %zu quadruples, filter ok %d, grid %u x %u x %u\n", input, set->n,
           q.n, f.ok, f.g.nx, f.g.ny, f.g.nz);
    uint8_t *first = malloc(q.n + 1), *v = malloc(q.n + 1);
    int nt = a < argc ? argc - a : 1, bad = 0;
    for (int i = 0; i < nt; i++) {
        unsigned threads = a < argc ? (unsigned)atoi(argv[a + i]) : 1;
        uint8_t *out = i ? v : first;
        double w0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
        for (int r = 0; r < repeat; r++) {
            if (!shared || !f.ok) {
                vb_cert_filter_judge(&f, (const uint32_t(*)[4])q.q, q.n, out, threads);
                continue;
            }
            for (size_t k = 0; k < q.n; k++)
                out[k] = (uint8_t)vbd_judge(f.z, f.cell_start, f.cell_ids, f.cell_z, &f.g,
                                            q.q[k][0], q.q[k][1], q.q[k][2], q.q[k][3]);
        }
        double w1 = now(CLOCK_MONOTONIC), c1 = now(CLOCK_PROCESS_CPUTIME_ID);
        double nq = (double)(q.n ? q.n : 1) * repeat;
        size_t cnt[3] = {0, 0, 0};
        for (size_t k = 0; k < q.n; k++)
            for (int r = 0; r < 2; r++)
                cnt[VBD_ROOT(out[k], r) < 3 ? VBD_ROOT(out[k], r) : 0]++;
        printf("%sthreads=%u repeat=%d: cpu %.1f ns/quad, wall %.1f ns/quad; roots vertex %zu "
               "not %zu open %zu; verdict hash %016llx\n",
               shared ? "shared " : "", threads, repeat, 1e9 * (c1 - c0) / nq, 1e9 * (w1 - w0) / nq, cnt[VBD_VERTEX],
               cnt[VBD_NOT], cnt[VBD_OPEN], (unsigned long long)fnv1a(out, q.n));
        if (i && memcmp(first, v, q.n) != 0) {
            fprintf(stderr, "bench_judge: %u threads differ from the first run\n", threads);
            bad = 1;
        }
    }
    if (vpath) {
        FILE *d = fopen(vpath, "wb");
        if (!d || fwrite(first, 1, q.n, d) != q.n || fclose(d) != 0) {
            fprintf(stderr, "bench_judge: cannot write %s\n", vpath);
            return 1;
        }
    }
    free(first);
    free(v);
    vb_cert_filter_free(&f);
    vb_quad_list_free(&q);
    vb_spheres_free(set);
    vb_close(ctx);
    return bad;
}
