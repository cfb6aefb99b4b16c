/* The certification stream (core/cells/vbv_certify.h) that overlaps the
 * cover: the cover's quadruples cut into many random parts (a quadruple to
 * any part: stronger than the cover's cells, which keep a cell's together),
 * each part shuffled (a streamed device batch comes unsorted) and the parts
 * handed over in a random order, certified on 1, 2 and 3 threads, give the
 * vertices of one vb_certify_quads over the whole sorted list, entry for
 * entry; more than 64 parts (merged as they come) too, and the certified
 * counter counts each vertex once (a degree-8 vertex of the cubic lattice
 * is certified in several parts). A stream that gets no part gives
 * nothing. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_cover.h"
#include "vb_test.h"
#include "vb_verify.h"
#include "vb_vertices.h"
#include "vbv_certify.h"
#include "vt_lists.h"

static uint64_t rnd_state = 88172645463325252ull;
static size_t rnd(size_t n)
{
    vb_test_xorshift(&rnd_state);
    return (size_t)(rnd_state % n);
}

/* The whole sorted list through vb_certify_quads: the reference. */
static int whole(const vb_sphere_set *s, const vb_quad_list *q, vb_vertex_list *out,
                 uint64_t *certified)
{
    vb_ctx *ctx;
    vb_certifier *c = NULL;
    int rc = vb_open(&ctx, NULL);
    if (rc != VB_OK)
        return rc;
    rc = vb_certifier_open(ctx, s, &c);
    if (rc == VB_OK)
        rc = vb_certify_quads(ctx, c, (const uint32_t(*)[4])q->q, q->n, out, NULL);
    *certified = vb_ctx_stats(ctx)->certified;
    vb_certifier_close(c);
    vb_close(ctx);
    return rc;
}

/* The quadruples in `parts` random parts, every part shuffled, the parts
 * streamed in a random order on `threads`. */
static int streamed(const vb_sphere_set *s, const vb_quad_list *q, size_t parts, unsigned threads,
                    vb_vertex_list *out, uint64_t *certified, size_t *nparts)
{
    vb_ctx *ctx;
    int rc = vb_open(&ctx, NULL);
    if (rc != VB_OK)
        return rc;
    size_t *order = malloc(parts * sizeof *order);
    vb_quad_list *lists = calloc(parts, sizeof *lists);
    if (!order || !lists)
        rc = VB_ENOMEM;
    for (size_t k = 0; rc == VB_OK && k < q->n; k++) {
        vb_quad_list *l = &lists[rnd(parts)];
        void *p = realloc(l->q, (l->n + 1) * sizeof *l->q);
        if (!p) {
            rc = VB_ENOMEM;
            break;
        }
        l->q = p;
        memcpy(l->q[l->n++], q->q[k], sizeof *q->q);
        l->cap = l->n;
    }
    for (size_t p = 0; rc == VB_OK && p < parts; p++) {
        order[p] = p;
        for (size_t k = lists[p].n; k > 1; k--) { /* Fisher-Yates */
            size_t j = rnd(k);
            uint32_t t[4];
            memcpy(t, lists[p].q[k - 1], sizeof t);
            memcpy(lists[p].q[k - 1], lists[p].q[j], sizeof t);
            memcpy(lists[p].q[j], t, sizeof t);
        }
    }
    for (size_t k = parts; rc == VB_OK && k > 1; k--) {
        size_t j = rnd(k), t = order[k - 1];
        order[k - 1] = order[j];
        order[j] = t;
    }
    vbv_cert_open co;
    vbv_cert_stream cs;
    if (rc == VB_OK) {
        vbv_cert_open_start(&co, &vb_exact_certifier, s, threads, ctx);
        rc = vbv_cert_stream_init(&cs, &co, ctx);
        for (size_t p = 0; rc == VB_OK && p < parts; p++)
            if (lists[order[p]].n)
                rc = vbv_cert_stream_sink(&cs, &lists[order[p]]);
        if (rc == VB_OK)
            rc = vbv_cert_stream_finish(ctx, &cs, out);
        *nparts = cs.certified_parts;
        void *cert = vbv_cert_stream_free(&cs);
        if (cert)
            vb_exact_certifier.close(cert);
    }
    *certified = vb_ctx_stats(ctx)->certified;
    for (size_t p = 0; lists && p < parts; p++)
        vb_quad_list_free(&lists[p]);
    free(lists);
    free(order);
    vb_close(ctx);
    return rc;
}

/* The spheres of path (NULL, a failed check, when they cannot be read). */
static vb_sphere_set *load(vb_ctx *ctx, const char *path)
{
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    vb_sphere_set *s = NULL;
    CHECK_INT(vb_spheres_load(ctx, path, &ro, NULL, 4, &s), VB_OK);
    return s;
}

static void one(vb_ctx *ctx, const char *path)
{
    vb_sphere_set *s = load(ctx, path);
    vb_quad_list q = {0};
    int rc = s ? vb_cover_run(ctx, s, NULL, NULL, &q, NULL) : VB_EINPUT;
    CHECK_INT(rc, VB_OK);
    vb_vertex_list ref;
    vb_vertex_list_init(&ref);
    uint64_t ref_certified = 0;
    if (rc == VB_OK)
        CHECK_INT(whole(s, &q, &ref, &ref_certified), VB_OK);
    CHECK(ref.n > 0);
    CHECK_INT(ref_certified, ref.n);
    const size_t cuts[] = {1, 7, 150};
    for (size_t c = 0; rc == VB_OK && c < sizeof cuts / sizeof cuts[0]; c++)
        for (unsigned threads = 1; threads <= 3; threads++) {
            vb_vertex_list v;
            vb_vertex_list_init(&v);
            uint64_t certified = 0;
            size_t nparts = 0;
            CHECK_INT(streamed(s, &q, cuts[c], threads, &v, &certified, &nparts), VB_OK);
            CHECK(vt_same_list(&ref, &v, 0));
            CHECK_INT(certified, ref.n);
            CHECK(nparts >= 1 && nparts <= cuts[c]);
            /* 150 parts of 250 quadruples or more (each input here):
             * more than 64 certified, merged as they came (fold_recent). */
            if (cuts[c] == 150 && q.n >= 250)
                CHECK(nparts > 64);
            if (!vt_same_list(&ref, &v, 0))
                fprintf(stderr, "%s: %zu parts, %u threads: %zu vertices, whole %zu\n", path,
                        cuts[c], threads, v.n, ref.n);
            vb_vertex_list_free(&v);
        }
    vb_vertex_list_free(&ref);
    vb_quad_list_free(&q);
    vb_spheres_free(s);
}

/* A stream that gets no part: no vertex, no error, no part counted. */
static void empty(vb_ctx *ctx, const char *path)
{
    vb_sphere_set *s = load(ctx, path);
    if (s) {
        vb_quad_list q = {0};
        vb_vertex_list v;
        vb_vertex_list_init(&v);
        uint64_t certified = 1;
        size_t nparts = 1;
        CHECK_INT(streamed(s, &q, 3, 2, &v, &certified, &nparts), VB_OK);
        CHECK_INT(v.n, 0);
        CHECK_INT(certified, 0);
        CHECK_INT(nparts, 0);
        vb_vertex_list_free(&v);
    }
    vb_spheres_free(s);
}

int main(void)
{
    const char *src = getenv("VORBALL_SOURCE_DIR");
    if (!src) {
        fprintf(stderr, "VORBALL_SOURCE_DIR must be set\n");
        return 1;
    }
    const char *cases[] = {"corpus/inputs/cubic_lattice.xyzr",
                           "corpus/inputs/jittered_lattice.xyzr",
                           "corpus/inputs/crambin_fragment.xyzr"};
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK)
        return 1;
    char path[4096];
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        snprintf(path, sizeof path, "%s/%s", src, cases[k]);
        one(ctx, path);
    }
    snprintf(path, sizeof path, "%s/%s", src, cases[0]);
    empty(ctx, path);
    vb_close(ctx);
    VB_TEST_END();
}
