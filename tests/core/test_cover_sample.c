/* The sample a device sizes its arenas from (vb_cover_sample_over,
 * core/cells/cover_sample.c) on corpus inputs (two crystals, a protein
 * fragment): the counts are the host cover's own (the same cells, spread
 * over the tree's order, covered one after the other in the sample's
 * arenas) on 1 and 3 threads, fall as the arenas grow, and are those
 * measured at stop 51 (the inputs' cells run out of 16 records, none of
 * 65,536; the fragment's of 64 and 256 records, as few as the jittered
 * crystal's of 64). The counts on the device's inputs:
 * tests/verify/bench_cover_cells. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_cover.h"
#include "vb_spheres.h"
#include "vb_test.h"

typedef struct loaded {
    vb_sphere_set *set;
    vb_cover_tree *tree;
    vbq_env env;
} loaded;

static int load(vb_ctx *ctx, const char *name, loaded *l)
{
    char path[4096];
    const char *src = getenv("VORBALL_SOURCE_DIR");
    snprintf(path, sizeof path, "%s/corpus/inputs/%s", src ? src : ".", name);
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    memset(l, 0, sizeof *l);
    int rc = vb_spheres_read_file(ctx, path, &ro, &l->set);
    if (rc == VB_OK)
        rc = vb_spheres_validate(ctx, l->set, 4);
    if (rc == VB_OK)
        rc = vb_cover_prepare(ctx, l->set, NULL, &l->tree, &l->env);
    return rc;
}

static void unload(loaded *l)
{
    vb_cover_tree_free(l->tree);
    vb_spheres_free(l->set);
}

/* The cells of `want` sampled that ran out of nb records (4 nb labels),
 * checked the same on 1 and 3 threads; *covered: the cells counted. */
static size_t sample(const vbq_env *e, size_t want, uint32_t nb, size_t *covered)
{
    size_t c1 = 0, o1 = 0, c3 = 0, o3 = 0;
    CHECK_INT(vb_cover_sample_over(e, want, nb, 4 * nb, 1, &c1, &o1), VB_OK);
    CHECK_INT(vb_cover_sample_over(e, want, nb, 4 * nb, 3, &c3, &o3), VB_OK);
    CHECK(c1 == c3 && o1 == o3);
    *covered = c1;
    return o1;
}

/* The sample's counts by hand: the same cells covered one after the other. */
static size_t by_hand(const vbq_env *e, size_t want, uint32_t nb, size_t *covered)
{
    vbq_arena ar;
    memset(&ar, 0, sizeof ar);
    size_t over = 0, count = want < e->m ? want : e->m;
    *covered = 0;
    CHECK_INT(vbq_arena_make(&ar, nb, 4 * nb, 512u, 512u), VB_OK);
    for (size_t k = 0; k < count; k++) {
        vbq_cell_out o;
        vb_cover_cell_host(e, &ar, e->ids[(size_t)((double)k * e->m / (double)count)],
                           VBQ_ALL_ROOTS, &o);
        if (o.status == VBQ_OK || o.status == VBQ_OVER_NB || o.status == VBQ_OVER_LAB) {
            ++*covered;
            over += o.status != VBQ_OK;
        }
    }
    vbq_arena_free(&ar);
    return over;
}

static void input(vb_ctx *ctx, const char *name, size_t want, const size_t expect[4])
{
    loaded l;
    CHECK_INT(load(ctx, name, &l), VB_OK);
    uint32_t nbs[4] = {16u, 64u, 256u, 65536u};
    size_t last = SIZE_MAX;
    for (int k = 0; k < 4 && l.env.m; k++) {
        size_t covered, hc, over = sample(&l.env, want, nbs[k], &covered);
        size_t hover = by_hand(&l.env, want, nbs[k], &hc);
        printf("%s: %zu of %zu cells sampled ran out of %u records (m %u)\n", name, over,
               covered, nbs[k], l.env.m);
        CHECK(over == hover && covered == hc);
        CHECK(covered == (want < l.env.m ? want : l.env.m));
        CHECK(over <= last);
        CHECK(over == expect[k]);
        last = over;
    }
    unload(&l);
}

int main(void)
{
    vb_ctx *ctx;
    CHECK_INT(vb_open(&ctx, NULL), VB_OK);
    size_t fcc[4] = {32, 10, 0, 0}, crn[4] = {32, 11, 3, 0}, ties[4] = {32, 0, 0, 0};
    input(ctx, "jittered_fcc.xyzr", 32, fcc);
    input(ctx, "fcc_hull_ties.xyzr", 32, ties);
    input(ctx, "crambin_fragment.xyzr", 32, crn);
    /* nothing to sample */
    size_t c = 1, o = 1;
    vbq_env none;
    memset(&none, 0, sizeof none);
    CHECK_INT(vb_cover_sample_over(&none, 32, 64, 256, 2, &c, &o), VB_OK);
    CHECK(c == 0 && o == 0);
    vb_close(ctx);
    VB_TEST_END();
}
