/* Two pieces of arc closure's plumbing (verify/arcs/vbx_closure.h,
 * vbx_region.h), checked against plain references:
 *  - the map of triples (vbx_tmap_update): on synthetic lists whose first
 *    spheres have buckets of every size the sort treats apart (insertion,
 *    merges, qsort: up to 11,300 entries), in a shuffled vertex order, the
 *    map is every (triple, vertex) of the list exactly once, in strictly
 *    increasing (t0, t1, t2, k) order, and the same array on 1, 2 and 5
 *    threads;
 *  - the gather (vbx_gather) leaves out exactly the frame's own three
 *    spheres: on each triple of crambin_fragment's vertices, the tail to
 *    infinity from G = 0 has the capped gather's candidates (which keep
 *    them) less those three (as sets), and the worker's skip list is
 *    cleared after. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vb_vertex_io.h"
#include "vt_case.h"
#include "vb_verify.h"
#include "vbx_closure.h"
#include "vbx_region.h"

static uint64_t rng = 88172645463325252ull;

static uint32_t next_u32(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (uint32_t)(rng >> 11);
}

static int tent_ref_cmp(const void *pa, const void *pb)
{
    const vbx_tent *a = pa, *b = pb;
    for (int i = 0; i < 3; i++)
        if (a->t[i] != b->t[i])
            return a->t[i] < b->t[i] ? -1 : 1;
    return (a->k > b->k) - (a->k < b->k);
}

/* A list of nv vertices of 4 to 6 members each; member 0 is sphere
 * hub % nhub for a share of them, so the buckets of the hubs grow large. */
static void make_list(vb_vertex_list *v, size_t nv, uint32_t nspheres, uint32_t nhub, int share)
{
    vb_vertex_list_init(v);
    for (size_t k = 0; k < nv; k++) {
        uint32_t m[6];
        size_t nm = 4 + next_u32() % 3, n = 0;
        if ((int)(next_u32() % 100) < share)
            m[n++] = next_u32() % nhub;
        while (n < nm) {
            uint32_t x = next_u32() % nspheres, dup = 0;
            for (size_t i = 0; i < n; i++)
                dup |= m[i] == x;
            if (!dup)
                m[n++] = x;
        }
        for (size_t i = 1; i < nm; i++)
            for (size_t j = i; j > 0 && m[j - 1] > m[j]; j--) {
                uint32_t t = m[j];
                m[j] = m[j - 1];
                m[j - 1] = t;
            }
        vb_vertex_list_push(v, m, nm, (double)k, 0.0, 0.0, 1.0, 0, VB_VERTEX_CERTIFIED);
    }
}

static void map_case(size_t nv, uint32_t nspheres, uint32_t nhub, int share)
{
    vb_vertex_list v;
    make_list(&v, nv, nspheres, nhub, share);
    size_t n = 0;
    for (size_t k = 0; k < v.n; k++) {
        size_t nm = v.start[k + 1] - v.start[k];
        n += nm * (nm - 1) * (nm - 2) / 6;
    }
    vbx_tent *ref = malloc(n * sizeof *ref);
    size_t r = 0;
    for (size_t k = 0; k < v.n; k++) {
        const uint32_t *m = v.ids + v.start[k];
        size_t nm = v.start[k + 1] - v.start[k];
        for (size_t a = 0; a < nm; a++)
            for (size_t b = a + 1; b < nm; b++)
                for (size_t c = b + 1; c < nm; c++)
                    ref[r++] = (vbx_tent){{m[a], m[b], m[c]}, (uint32_t)k};
    }
    qsort(ref, n, sizeof *ref, tent_ref_cmp);
    size_t biggest = 0;
    const unsigned threads[3] = {1, 2, 5};
    for (int ti = 0; ti < 3; ti++) {
        vbx_tmap m;
        memset(&m, 0, sizeof m);
        CHECK_INT(vbx_tmap_update(&m, &v, threads[ti]), VB_OK);
        CHECK_INT((long long)m.n, (long long)n);
        int sorted = 1, same = m.n == n;
        for (size_t i = 1; i < m.n; i++)
            sorted &= tent_ref_cmp(&m.e[i - 1], &m.e[i]) < 0;
        for (size_t i = 0; same && i < n; i++)
            same = tent_ref_cmp(&m.e[i], &ref[i]) == 0;
        CHECK(sorted);
        CHECK(same);
        for (size_t i = 0; i < m.noff; i++)
            if (m.off[i + 1] - m.off[i] > biggest)
                biggest = m.off[i + 1] - m.off[i];
        free(m.e);
        free(m.off);
    }
    fprintf(stderr, "map: %zu vertices, %zu entries, biggest bucket %zu\n", v.n, n, biggest);
    free(ref);
    vb_vertex_list_free(&v);
}

static int has(const uint32_t *c, size_t n, uint32_t j)
{
    for (size_t i = 0; i < n; i++)
        if (c[i] == j)
            return 1;
    return 0;
}

static void gather_case(void)
{
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    vb_sphere_set *s;
    vb_vertex_list g;
    CHECK_INT(vt_read_named(ctx, "crambin_fragment", &s, &g), VB_OK);
    vb_certifier *c = NULL;
    CHECK_INT(vb_certifier_open(ctx, s, &c), VB_OK);
    vbx_arcw w;
    CHECK_INT(vbx_arcw_init(&w, ctx, c), VB_OK);
    vbx_tframe f;
    vbx_tframe_init(&f);
    uint32_t *capped = malloc((s->n + 1) * sizeof *capped);
    size_t tails = 0, own_seen = 0, others = 0, bad = 0;
    for (size_t k = 0; k < g.n && k < 120; k++) {
        const uint32_t *m = g.ids + g.start[k];
        size_t nm = g.start[k + 1] - g.start[k];
        for (size_t a = 0; a + 2 < nm; a++) {
            uint32_t t[3] = {m[a], m[a + 1], m[a + 2]};
            vbx_tframe_reset(&f);
            CHECK_INT(vbx_tframe_setup(&w, &f, t), VB_OK);
            if (f.kind != VBX_TRI_OPEN || !f.ok)
                continue;
            vbx_region rg;
            vbx_tail_from(&f, 0.0, 1.0, &rg);
            if (vbx_gather_capped(&w, &f, &rg, SIZE_MAX) != 1)
                continue;
            size_t nc = w.ncand;
            memcpy(capped, w.cand, nc * sizeof *capped);
            vbx_tail_from(&f, 0.0, 1.0, &rg);
            CHECK_INT(vbx_gather(&w, &f, &rg), VB_OK);
            CHECK(w.own == NULL);
            if (rg.brute)
                continue;
            tails++;
            /* gather = capped less t[0..2], as sets (the capped gather
             * walks a strip's half-space before its box) */
            size_t o = 0;
            for (size_t i = 0; i < nc; i++) {
                if (capped[i] == t[0] || capped[i] == t[1] || capped[i] == t[2]) {
                    own_seen++;
                    bad += has(w.cand, w.ncand, capped[i]);
                    continue;
                }
                others++;
                bad += !has(w.cand, w.ncand, capped[i]);
                o++;
            }
            bad += o != w.ncand;
            vbx_clear_cands(&w);
        }
    }
    fprintf(stderr, "gather: %zu tails, %zu own spheres left out, %zu others kept\n", tails,
            own_seen, others);
    CHECK(tails > 50);
    CHECK(own_seen >= 3 * tails);
    CHECK(others > 0);
    CHECK_INT((long long)bad, 0);
    free(capped);
    vbx_tframe_clear(&f);
    vbx_arcw_free(&w);
    vb_certifier_close(c);
    vb_vertex_list_free(&g);
    vb_spheres_free(s);
    vb_close(ctx);
}

int main(void)
{
    map_case(300, 4000, 1, 0);   /* buckets of a few: insertion sort */
    map_case(300, 40, 1, 0);     /* buckets of tens to 276: merges */
    map_case(2000, 3000, 1, 90); /* one hub of 11,300: qsort */
    gather_case();
    VB_TEST_END();
}
