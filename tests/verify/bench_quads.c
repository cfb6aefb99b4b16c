/* bench_quads: time vb_certify_quads on the direction cover's quadruples.
 *
 *   bench_quads [--old] [-o FILE] [--quads FILE] INPUT [THREADS...]
 *
 * Runs the cover (host) once, then for each thread count (default: 1)
 * certifies its quadruples and prints microseconds per quadruple (wall and
 * process CPU), the filter's success rates and the GMP fallbacks. --old
 * also certifies the way the prototype did (vb_certify_list on one double
 * candidate per root of each quadruple) and checks that both give the same
 * vertices. -o writes the (first) certified list as TSV; --quads reads the
 * quadruples from a file ("a b c d" per line, sorted) instead of running the
 * cover (for profiling the certifier alone). A benchmark, not a
 * test: it fails only when two runs give different lists. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "vb_cover.h"
#include "vb_geom_shared.h"
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

static double pct(uint64_t a, uint64_t b)
{
    return b ? 100.0 * (double)a / (double)b : 0.0;
}

/* The prototype's candidates: every double root of each quadruple (or the
 * base centre when there is none). */
static int old_candidates(const vb_sphere_set *set, const vb_quad_list *q, vb_vertex_list *cand)
{
    for (size_t k = 0; k < q->n; k++) {
        double s[4][4], out[2][4];
        for (int a = 0; a < 4; a++) {
            uint32_t id = q->q[k][a];
            s[a][0] = set->x[id];
            s[a][1] = set->y[id];
            s[a][2] = set->z[id];
            s[a][3] = set->r[id];
        }
        int nr = vbs_tangent_roots(s, out), rc = VB_OK;
        if (nr == 0)
            rc = vb_vertex_list_push(cand, q->q[k], 4, s[0][0], s[0][1], s[0][2], 0.0, 0.0,
                                     VB_VERTEX_CANDIDATE);
        for (int r = 0; r < nr && rc == VB_OK; r++)
            rc = vb_vertex_list_push(cand, q->q[k], 4, out[r][0], out[r][1], out[r][2],
                                     out[r][3], 0.0, VB_VERTEX_CANDIDATE);
        if (rc != VB_OK)
            return rc;
    }
    return VB_OK;
}

int main(int argc, char **argv)
{
    int old = 0, a = 1;
    const char *outpath = NULL, *quadpath = NULL;
    for (; a < argc && argv[a][0] == '-'; a++) {
        if (strcmp(argv[a], "--old") == 0)
            old = 1;
        else if (strcmp(argv[a], "-o") == 0 && a + 1 < argc)
            outpath = argv[++a];
        else if (strcmp(argv[a], "--quads") == 0 && a + 1 < argc)
            quadpath = argv[++a];
        else
            break;
    }
    if (a >= argc) {
        fprintf(stderr, "usage: bench_quads [--old] [-o FILE] [--quads FILE] INPUT [THREADS...]\n");
        return 2;
    }
    const char *input = argv[a++];
    vb_ctx *ctx;
    vb_sphere_set *set;
    if (vt_bench_open("bench_quads", input, &ctx, &set))
        return 1;
    vb_quad_list q = {0};
    double t0 = now(CLOCK_MONOTONIC);
    int rc = VB_OK;
    if (quadpath && vt_read_quads(quadpath, &q) != 0)
        rc = vb_error(ctx, VB_EIO, quadpath, 0, "cannot read");
    else if (!quadpath)
        rc = vb_cover_run(ctx, set, NULL, NULL, &q, NULL);
    if (rc != VB_OK) {
        fprintf(stderr, "bench_quads: %s\n", vb_errmsg(ctx));
        return 1;
    }
    printf("%s: %zu spheres, %zu quadruples (cover %.3f s wall)\n", input, set->n, q.n,
           now(CLOCK_MONOTONIC) - t0);
    vb_certifier *c;
    t0 = now(CLOCK_MONOTONIC);
    if (vb_certifier_open(ctx, set, &c) != VB_OK) {
        fprintf(stderr, "bench_quads: %s\n", vb_errmsg(ctx));
        return 1;
    }
    printf("certifier open %.3f s\n", now(CLOCK_MONOTONIC) - t0);
    vb_vertex_list first;
    vb_vertex_list_init(&first);
    int nt = a < argc ? argc - a : 1, bad = 0;
    for (int i = 0; i < nt; i++) {
        unsigned threads = a < argc ? (unsigned)atoi(argv[a + i]) : 1;
        vb_certifier_set_threads(c, threads);
        vb_vertex_list out;
        vb_vertex_list_init(&out);
        vb_stats before = *vb_ctx_stats(ctx);
        vb_cert_quad_stats qs;
        double w0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
        rc = vb_certify_quads(ctx, c, (const uint32_t(*)[4])q.q, q.n, &out, &qs);
        double w1 = now(CLOCK_MONOTONIC), c1 = now(CLOCK_PROCESS_CPUTIME_ID);
        if (rc != VB_OK) {
            fprintf(stderr, "bench_quads: %s\n", vb_errmsg(ctx));
            return 1;
        }
        const vb_stats *st = vb_ctx_stats(ctx);
        double nq = (double)(q.n ? q.n : 1);
        uint64_t roots_filter = qs.refused_tangent + qs.refused_intruder + qs.roots_fast +
                                qs.roots_round_exact;
        printf("quads threads=%u: %zu vertices  wall %.3f ms  %.3f us/quad  cpu %.3f us/quad\n",
               threads, out.n, 1e3 * (w1 - w0), 1e6 * (w1 - w0) / nq, 1e6 * (c1 - c0) / nq);
        printf("  no root %llu (%.1f%%), quads rejected without GMP %llu (%.1f%% of quads), "
               "filter undecided quads %llu; rank < 3 %llu, delta signs in GMP %llu "
               "(one root %llu)\n",
               (unsigned long long)qs.no_root, pct(qs.no_root, qs.quads),
               (unsigned long long)qs.rejected_fast, pct(qs.rejected_fast, qs.quads),
               (unsigned long long)qs.quads_exact, (unsigned long long)qs.flat,
               (unsigned long long)qs.delta_exact, (unsigned long long)qs.one_root);
        printf("  roots decided by the filter %llu: refused (t+R<0) %llu, refused (intruder) %llu, "
               "certified %llu (rounded in double-double %llu = %.2f%%, by GMP %llu); "
               "roots left to the exact path %llu (ties proven found already %llu)\n",
               (unsigned long long)roots_filter, (unsigned long long)qs.refused_tangent,
               (unsigned long long)qs.refused_intruder,
               (unsigned long long)(qs.roots_fast + qs.roots_round_exact),
               (unsigned long long)qs.roots_fast,
               pct(qs.roots_fast, qs.roots_fast + qs.roots_round_exact),
               (unsigned long long)qs.roots_round_exact, (unsigned long long)qs.roots_exact,
               (unsigned long long)qs.roots_tied);
        printf("  GMP solves %llu (%.2f%% of quads), MPFR roundings %llu, duplicates %llu, "
               "scan signs by the power %llu (double-double %llu); "
               "ctx: filter_calls %llu filter_failures %llu exact_evals %llu\n",
               (unsigned long long)qs.exact_solves, pct(qs.exact_solves, qs.quads),
               (unsigned long long)qs.mpfr_rounds, (unsigned long long)qs.duplicates,
               (unsigned long long)qs.power_signs, (unsigned long long)qs.power_signs_dd,
               (unsigned long long)(st->filter_calls - before.filter_calls),
               (unsigned long long)(st->filter_failures - before.filter_failures),
               (unsigned long long)(st->exact_evals - before.exact_evals));
        if (i == 0) {
            first = out;
        } else {
            if (!vt_same_list(&first, &out, 1)) {
                fprintf(stderr, "bench_quads: %u threads differ from the first run\n", threads);
                bad = 1;
            }
            vb_vertex_list_free(&out);
        }
    }
    if (outpath) {
        FILE *f = fopen(outpath, "w");
        if (!f || vb_vertex_write(ctx, f, &first, VB_VFMT_TSV, NULL) != VB_OK) {
            fprintf(stderr, "bench_quads: cannot write %s\n", outpath);
            return 1;
        }
        fclose(f);
    }
    if (old) {
        vb_vertex_list cand, out;
        vb_vertex_list_init(&cand);
        vb_vertex_list_init(&out);
        if (old_candidates(set, &q, &cand) != VB_OK)
            return 1;
        unsigned threads = a < argc ? (unsigned)atoi(argv[a]) : 1;
        vb_certifier_set_threads(c, threads);
        vb_stats before = *vb_ctx_stats(ctx);
        double w0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
        rc = vb_certify_list(ctx, c, &cand, 0.0, &out, NULL);
        double w1 = now(CLOCK_MONOTONIC), c1 = now(CLOCK_PROCESS_CPUTIME_ID);
        if (rc != VB_OK) {
            fprintf(stderr, "bench_quads: %s\n", vb_errmsg(ctx));
            return 1;
        }
        const vb_stats *st = vb_ctx_stats(ctx);
        printf("old threads=%u: %zu candidates, %zu vertices  wall %.3f ms  %.3f us/quad  "
               "cpu %.3f us/quad  exact_evals %llu\n",
               threads, cand.n, out.n, 1e3 * (w1 - w0), 1e6 * (w1 - w0) / (double)q.n,
               1e6 * (c1 - c0) / (double)q.n,
               (unsigned long long)(st->exact_evals - before.exact_evals));
        int same = vt_same_list(&first, &out, 0); /* old dist: candidate distances */
        printf("old and new lists %s\n", same ? "identical" : "DIFFER");
        bad |= !same;
        vb_vertex_list_free(&cand);
        vb_vertex_list_free(&out);
    }
    vb_vertex_list_free(&first);
    vb_quad_list_free(&q);
    vb_certifier_close(c);
    vb_spheres_free(set);
    vb_close(ctx);
    return bad;
}
