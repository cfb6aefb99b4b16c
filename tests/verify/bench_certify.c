/* bench_certify: time vb_certify_list on the candidates of a real input.
 *
 *   bench_certify INPUT VERTICES [THREADS...]
 *
 * Candidates are the entries of a vertex file (e.g. the output of `vorball
 * vertices`: every certified vertex with all its ids and its point). For
 * each thread count (default: 1) it prints microseconds per candidate (wall
 * and process CPU), the exact counters and a checksum of the certified list.
 * A benchmark, not a test: it fails only when two thread counts give
 * different certified lists. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vb_vertex_io.h"
#include "vb_verify.h"
#include "vt_bench.h"
#include "vt_lists.h"

static double now(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* FNV-1a over the bytes of the certified list: equal output, equal sum. */
static uint64_t checksum(const vb_vertex_list *v)
{
    uint64_t h = 1469598103934665603ull;
    const void *part[7] = {v->start, v->ids, v->x, v->y, v->z, v->t, v->dist};
    size_t len[7] = {(v->n + 1) * sizeof *v->start, v->nids * sizeof *v->ids,
                     v->n * sizeof(double), v->n * sizeof(double), v->n * sizeof(double),
                     v->n * sizeof(double), v->n * sizeof(double)};
    for (int i = 0; i < 7; i++)
        for (size_t b = 0; b < len[i]; b++) {
            h ^= ((const unsigned char *)part[i])[b];
            h *= 1099511628211ull;
        }
    return h;
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: bench_certify INPUT VERTICES [THREADS...]\n");
        return 2;
    }
    vb_ctx *ctx;
    vb_sphere_set *set;
    if (vt_bench_open("bench_certify", argv[1], &ctx, &set))
        return 1;
    vb_vertex_list cand;
    vb_vertex_list_init(&cand);
    if (vb_vertex_read_file(ctx, argv[2], &cand, NULL, NULL) != VB_OK) {
        fprintf(stderr, "bench_certify: %s\n", vb_errmsg(ctx));
        return 1;
    }
    vb_certifier *c;
    if (vb_certifier_open(ctx, set, &c) != VB_OK)
        return 1;
    vb_vertex_list first;
    vb_vertex_list_init(&first);
    int nt = argc > 3 ? argc - 3 : 1, bad = 0, rc = VB_OK;
    for (int i = 0; i < nt; i++) {
        unsigned threads = argc > 3 ? (unsigned)atoi(argv[3 + i]) : 1;
        vb_certifier_set_threads(c, threads);
        vb_vertex_list out, rej;
        vb_vertex_list_init(&out);
        vb_vertex_list_init(&rej);
        vb_stats before = *vb_ctx_stats(ctx);
        uint64_t slow0 = vb_certifier_slow_rounds(c);
        double t0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
        rc = vb_certify_list(ctx, c, &cand, 0.0, &out, &rej);
        double t1 = now(CLOCK_MONOTONIC), c1 = now(CLOCK_PROCESS_CPUTIME_ID);
        vb_stats *st = vb_ctx_stats(ctx);
        printf("%s threads=%u candidates=%zu certified=%zu rejected=%zu  wall %.3f ms  "
               "%.2f us/cand  cpu %.2f us/cand  exact_evals=%llu filter_failures=%llu "
               "mpfr_rounds=%llu sum=%016llx\n",
               argv[1], threads, cand.n, out.n, rej.n, 1e3 * (t1 - t0),
               1e6 * (t1 - t0) / (double)(cand.n ? cand.n : 1),
               1e6 * (c1 - c0) / (double)(cand.n ? cand.n : 1),
               (unsigned long long)(st->exact_evals - before.exact_evals),
               (unsigned long long)(st->filter_failures - before.filter_failures),
               (unsigned long long)(vb_certifier_slow_rounds(c) - slow0),
               (unsigned long long)checksum(&out));
        if (rc != VB_OK) {
            fprintf(stderr, "bench_certify: %s\n", vb_errmsg(ctx));
            return 1;
        }
        if (i == 0) {
            first = out;
        } else {
            if (!vt_same_list(&first, &out, 1)) {
                fprintf(stderr, "bench_certify: %u threads differ from the first run\n",
                        threads);
                bad = 1;
            }
            vb_vertex_list_free(&out);
        }
        vb_vertex_list_free(&rej);
    }
    /* Candidates whose coordinates needed MPFR at least once. */
    size_t slow_cand = 0;
    for (size_t k = 0; rc == VB_OK && k < cand.n; k++) {
        uint64_t before = vb_certifier_slow_rounds(c);
        double p[3] = {cand.x[k], cand.y[k], cand.z[k]};
        vb_cert_result res;
        rc = vb_certify_candidate(ctx, c, cand.ids + cand.start[k],
                                  cand.start[k + 1] - cand.start[k], p, 0.0, &res);
        slow_cand += vb_certifier_slow_rounds(c) > before;
    }
    printf("%s candidates needing MPFR: %zu of %zu\n", argv[1], slow_cand, cand.n);
    vb_vertex_list_free(&first);
    vb_vertex_list_free(&cand);
    vb_certifier_close(c);
    vb_spheres_free(set);
    vb_close(ctx);
    return bad;
}
