/* cover -> vb_certify_quads on every corpus input (the pipeline the lead
 * will wire): the goldens of corpus/golden reproduced byte for byte, on one
 * and on two threads. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_cover.h"
#include "vb_test.h"
#include "vb_verify.h"
#include "vb_vertex_io.h"
#include "vt_corpus.h"

/* The vertex lines of a TSV text (the header's '#' lines dropped). */
static char *body(const char *text)
{
    size_t n = strlen(text);
    char *out = malloc(n + 1), *o = out;
    for (const char *p = text; *p;) {
        const char *e = strchr(p, '\n');
        size_t len = e ? (size_t)(e - p) + 1 : strlen(p);
        if (*p != '#') {
            memcpy(o, p, len);
            o += len;
        }
        p += len;
    }
    *o = '\0';
    return out;
}

/* cover -> vb_certify_quads on one corpus input, against its golden. */
static void one_case(const char *name, const char *in, const char *gold)
{
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    vb_sphere_set *s = NULL;
    vb_quad_list q = {0};
    int rc = vb_spheres_read_file(ctx, in, &ro, &s);
    if (rc == VB_OK)
        rc = vb_spheres_validate(ctx, s, 4);
    if (rc == VB_OK)
        rc = vb_cover_run(ctx, s, NULL, NULL, &q, NULL);
    CHECK_INT(rc, VB_OK);
    for (unsigned threads = 1; rc == VB_OK && threads <= 2; threads++) {
        vb_certifier *c;
        vb_vertex_list out;
        vb_vertex_list_init(&out);
        rc = vb_certifier_open(ctx, s, &c);
        if (rc == VB_OK) {
            vb_certifier_set_threads(c, threads);
            rc = vb_certify_quads(ctx, c, (const uint32_t(*)[4])q.q, q.n, &out, NULL);
            vb_certifier_close(c);
        }
        CHECK_INT(rc, VB_OK);
        char *text = NULL;
        size_t tlen = 0;
        FILE *m = open_memstream(&text, &tlen);
        vb_vertex_write(ctx, m, &out, VB_VFMT_TSV, NULL);
        fclose(m);
        char *want = vb_test_slurp(gold);
        CHECK(want != NULL);
        if (want) {
            char *a = body(text), *b = body(want);
            int same = strcmp(a, b) == 0;
            if (!same)
                fprintf(stderr, "%s: differs from its golden (%u threads)\n", name,
                        threads);
            CHECK(same);
            free(a);
            free(b);
        }
        free(want);
        free(text);
        vb_vertex_list_free(&out);
    }
    vb_quad_list_free(&q);
    vb_spheres_free(s);
    vb_close(ctx);
}

int main(void)
{
    CHECK(vt_each_golden(one_case) >= 15);
    VB_TEST_END();
}
