/* vb_certify_list on several threads writes exactly what one thread writes:
 * the same certified and rejected lists, byte for byte, and the same stats.
 * Candidates come from the golden answers of every corpus input (the
 * crambin fragment is a protein): each vertex from several quadruples of its
 * members (duplicates to merge), and quadruples with one member swapped out
 * (mostly refused). The certified list must be the golden list itself. */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vb_verify.h"
#include "vb_vertex_io.h"
#include "vt_lists.h"

/* Candidates from the golden vertices g of a set of n spheres. */
static int make_candidates(const vb_vertex_list *g, size_t n, vb_vertex_list *cand)
{
    int rc = VB_OK;
    for (size_t k = 0; k < g->n && rc == VB_OK; k++) {
        const uint32_t *m = g->ids + g->start[k];
        size_t nm = g->start[k + 1] - g->start[k];
        double x = g->x[k], y = g->y[k], z = g->z[k], t = g->t[k];
        rc = vb_vertex_list_push(cand, m, 4, x, y, z, t, 0.0, VB_VERTEX_CANDIDATE);
        if (rc == VB_OK && nm > 4)
            rc = vb_vertex_list_push(cand, m + nm - 4, 4, x, y, z, t, 0.0, VB_VERTEX_CANDIDATE);
        if (rc == VB_OK && nm > 4)
            rc = vb_vertex_list_push(cand, m, nm, x, y, z, t, 0.0, VB_VERTEX_CANDIDATE);
        /* Swap the last of four for a sphere that is no member. */
        uint32_t q[4] = {m[0], m[1], m[2], (uint32_t)((m[3] + 1 + k) % n)};
        int member = 0;
        for (size_t i = 0; i < nm; i++)
            member |= m[i] == q[3];
        if (rc == VB_OK && !member)
            rc = vb_vertex_list_push(cand, q, 4, x + 0.25, y, z, t, 0.0, VB_VERTEX_CANDIDATE);
    }
    return rc;
}

typedef struct run {
    vb_vertex_list out, rej;
    vb_stats st;
    int rc;
} run;

/* A fresh context and certifier, so the stats are this run's alone. */
static void certify(const vb_sphere_set *set, const vb_vertex_list *cand, unsigned threads,
                    run *r)
{
    vb_ctx *ctx;
    vb_certifier *c = NULL;
    vb_vertex_list_init(&r->out);
    vb_vertex_list_init(&r->rej);
    r->rc = vb_open(&ctx, NULL);
    if (r->rc != VB_OK)
        return;
    r->rc = vb_certifier_open(ctx, set, &c);
    if (r->rc == VB_OK) {
        vb_certifier_set_threads(c, threads);
        r->rc = vb_certify_list(ctx, c, cand, 0.0, &r->out, &r->rej);
        /* A second list on the same certifier: keys persist across calls. */
        if (r->rc == VB_OK) {
            vb_vertex_list again;
            vb_vertex_list_init(&again);
            r->rc = vb_certify_list(ctx, c, cand, 0.0, &again, NULL);
            if (r->rc == VB_OK && !vt_same_list(&again, &r->out, 1))
                r->rc = -1;
            vb_vertex_list_free(&again);
        }
    }
    r->st = *vb_ctx_stats(ctx);
    vb_certifier_close(c);
    vb_close(ctx);
}

static void free_run(run *r)
{
    vb_vertex_list_free(&r->out);
    vb_vertex_list_free(&r->rej);
}

static size_t check_case(const char *src, const char *name)
{
    char in[1024], gold[1024];
    size_t len = strlen(name) - 4; /* without ".tsv" */
    snprintf(in, sizeof in, "%s/corpus/inputs/%.*s.xyzr", src, (int)len, name);
    snprintf(gold, sizeof gold, "%s/corpus/golden/%s", src, name);
    vb_ctx *ctx;
    CHECK_INT(vb_open(&ctx, NULL), VB_OK);
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    vb_sphere_set *set = NULL;
    vb_vertex_list g, cand;
    vb_vertex_list_init(&g);
    vb_vertex_list_init(&cand);
    int rc = vb_spheres_read_file(ctx, in, &ro, &set);
    if (rc == VB_OK)
        rc = vb_spheres_validate(ctx, set, 4);
    if (rc == VB_OK)
        rc = vb_vertex_read_file(ctx, gold, &g, NULL, NULL);
    if (rc == VB_OK)
        rc = make_candidates(&g, set->n, &cand);
    if (rc != VB_OK)
        fprintf(stderr, "%s: %s\n", name, vb_errmsg(ctx));
    CHECK_INT(rc, VB_OK);
    size_t ncand = cand.n;
    if (rc == VB_OK) {
        static const unsigned threads[] = {1, 2, 3, 8};
        run one;
        certify(set, &cand, 1, &one);
        CHECK_INT(one.rc, VB_OK);
        /* Every golden vertex has a candidate at its exact rounded point. */
        if (!vt_same_list(&one.out, &g, 0))
            fprintf(stderr, "%s: certified list differs from the golden answer\n", name);
        CHECK(vt_same_list(&one.out, &g, 0));
        /* Two lists: candidates counted twice, each vertex once per list. */
        CHECK_INT(one.st.candidates, 2 * ncand);
        CHECK_INT(one.st.certified, 2 * g.n);
        CHECK_INT(one.st.rejected, 2 * one.rej.n);
        for (size_t i = 1; i < sizeof threads / sizeof *threads; i++) {
            run r;
            certify(set, &cand, threads[i], &r);
            CHECK_INT(r.rc, VB_OK);
            CHECK(vt_same_list(&r.out, &one.out, 1));
            CHECK(vt_same_list(&r.rej, &one.rej, 1));
            CHECK(memcmp(&r.st, &one.st, sizeof r.st) == 0);
            free_run(&r);
        }
        free_run(&one);
    }
    vb_vertex_list_free(&g);
    vb_vertex_list_free(&cand);
    vb_spheres_free(set);
    vb_close(ctx);
    return ncand;
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

int main(void)
{
    const char *src = getenv("VORBALL_SOURCE_DIR");
    if (!src)
        src = ".";
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/corpus/golden", src);
    DIR *d = opendir(dir);
    CHECK(d != NULL);
    char *names[256];
    size_t n = 0;
    for (struct dirent *e; d && (e = readdir(d)) && n < 256;) {
        size_t len = strlen(e->d_name);
        if (len > 4 && strcmp(e->d_name + len - 4, ".tsv") == 0)
            names[n++] = strdup(e->d_name);
    }
    if (d)
        closedir(d);
    qsort(names, n, sizeof *names, cmp_str);
    size_t total = 0;
    int protein = 0;
    for (size_t i = 0; i < n; i++) {
        total += check_case(src, names[i]);
        protein |= strcmp(names[i], "crambin_fragment.tsv") == 0;
        free(names[i]);
    }
    CHECK(n >= 10);
    CHECK(protein);
    /* Enough candidates that 8 threads really run in parallel on some case. */
    CHECK(total > 1000);
    VB_TEST_END();
}
