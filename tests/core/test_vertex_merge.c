/* Vertex lists across processes (MPI ranks): pack and unpack keep every
 * bit, unpack refuses what is not a packed list, and the canonical merge of
 * parts equals the whole list, a vertex of degree > 4 certified by two
 * parts kept once and two roots of one quadruple kept both. */
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vb_test.h"
#include "vb_vertex.h"
#include "vb_vertex_io.h"

/* The whole list, canonical: a degree-5 vertex, two roots of one
 * quadruple (same ids, different points), a plain vertex, a negative t. */
static void whole(vb_vertex_list *v)
{
    uint32_t d5[] = {0, 1, 2, 3, 4}, q[] = {1, 2, 5, 7}, p[] = {2, 3, 6, 8}, n[] = {4, 6, 7, 9};
    vb_vertex_list_init(v);
    vb_vertex_list_push(v, d5, 5, 0.5, -0.25, 1e-300, 2.0, 1e-15, VB_VERTEX_CERTIFIED);
    vb_vertex_list_push(v, q, 4, 1.0 / 3.0, 2.0, 3.0, 0.75, 0.0, VB_VERTEX_CERTIFIED);
    vb_vertex_list_push(v, q, 4, 1.0 / 3.0, 2.0, 3.5, 0.75, 0.0, VB_VERTEX_CERTIFIED);
    vb_vertex_list_push(v, p, 4, -7.0, 8.0, 9.0, 1.5, 0.0, VB_VERTEX_CERTIFIED);
    vb_vertex_list_push(v, n, 4, 4.0, 5.0, 6.0, -0.125, 0.0, VB_VERTEX_CERTIFIED);
}

/* The list as `vorball vertices` writes it. */
static char *text(const vb_vertex_list *v)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    vb_vertex_write(NULL, f, v, VB_VFMT_TSV, "c");
    fclose(f);
    return buf;
}

static void copy(vb_vertex_list *dst, const vb_vertex_list *src, size_t k)
{
    vb_vertex_list_push(dst, src->ids + src->start[k], src->start[k + 1] - src->start[k],
                        src->x[k], src->y[k], src->z[k], src->t[k], src->dist[k], src->status[k]);
}

static void test_pack_roundtrip(void)
{
    vb_vertex_list v, back, empty;
    whole(&v);
    vb_vertex_list_init(&back);
    vb_vertex_list_init(&empty);
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    unsigned char *buf;
    size_t len;
    CHECK_INT(vb_vertex_list_pack(&v, &buf, &len), VB_OK);
    CHECK_INT(vb_vertex_list_unpack(ctx, buf, len, &back), VB_OK);
    char *a = text(&v), *b = text(&back);
    CHECK_STR(b, a);
    CHECK_INT(back.n, 5);
    CHECK(back.x[0] == 0.5 && back.z[0] == 1e-300 && back.dist[0] == 1e-15);
    /* Not a packed list: short, wrong size, offsets out of order. */
    vb_vertex_list junk;
    vb_vertex_list_init(&junk);
    CHECK_INT(vb_vertex_list_unpack(ctx, buf, len - 1, &junk), VB_EINTERNAL);
    CHECK_INT(vb_vertex_list_unpack(ctx, buf, 7, &junk), VB_EINTERNAL);
    unsigned char *bad = malloc(len);
    memcpy(bad, buf, len);
    uint64_t big = 3;
    memcpy(bad + 8 + 16 + 8, &big, 8); /* start[1] = 3: a vertex of 3 ids */
    CHECK_INT(vb_vertex_list_unpack(ctx, bad, len, &junk), VB_EINTERNAL);
    bad[0] = 'X';
    memcpy(bad + 8 + 16 + 8, buf + 8 + 16 + 8, 8);
    CHECK_INT(vb_vertex_list_unpack(ctx, bad, len, &junk), VB_EINTERNAL);
    CHECK_INT(junk.n, 0);
    free(bad);
    free(buf);
    /* An empty part (a rank with nothing certified) packs and adds nothing. */
    CHECK_INT(vb_vertex_list_pack(&empty, &buf, &len), VB_OK);
    CHECK_INT(vb_vertex_list_unpack(ctx, buf, len, &back), VB_OK);
    CHECK_INT(back.n, 5);
    free(buf);
    free(a);
    free(b);
    vb_vertex_list_free(&v);
    vb_vertex_list_free(&back);
    vb_close(ctx);
}

/* Parts as ranks hand them in: each sorted, the degree-5 vertex in two of
 * them, in an order that is not the canonical one. */
static void test_merge_parts(void)
{
    vb_vertex_list v, part[3], all;
    whole(&v);
    for (int r = 0; r < 3; r++)
        vb_vertex_list_init(&part[r]);
    vb_vertex_list_init(&all);
    copy(&part[0], &v, 3);
    copy(&part[0], &v, 0);
    copy(&part[1], &v, 4);
    copy(&part[1], &v, 1);
    copy(&part[2], &v, 2);
    copy(&part[2], &v, 0);
    part[2].dist[1] = 0.0; /* the same vertex, judged from another candidate */
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    for (int r = 0; r < 3; r++) {
        unsigned char *buf;
        size_t len;
        CHECK_INT(vb_vertex_list_pack(&part[r], &buf, &len), VB_OK);
        CHECK_INT(vb_vertex_list_unpack(ctx, buf, len, &all), VB_OK);
        free(buf);
    }
    CHECK_INT(all.n, 6);
    size_t dropped = 99;
    CHECK_INT(vb_vertex_list_canonical(&all, &dropped), VB_OK);
    CHECK_INT(dropped, 1);
    CHECK_INT(all.n, 5);
    char *a = text(&v), *b = text(&all);
    CHECK_STR(b, a);
    /* Canonical twice is canonical. */
    CHECK_INT(vb_vertex_list_canonical(&all, &dropped), VB_OK);
    CHECK_INT(dropped, 0);
    free(a);
    free(b);
    for (int r = 0; r < 3; r++)
        vb_vertex_list_free(&part[r]);
    vb_vertex_list_free(&all);
    vb_vertex_list_free(&v);
    vb_close(ctx);
}

/* The pipeline's merge of parts certified apart: each part sorted, the
 * two roots of one quadruple in different parts, an empty part, a vertex
 * of degree 5 certified in two parts. */
static void test_merge_sorted(void)
{
    vb_vertex_list v, part[4], out;
    whole(&v);
    for (int r = 0; r < 4; r++)
        vb_vertex_list_init(&part[r]);
    vb_vertex_list_init(&out);
    copy(&part[0], &v, 2);
    copy(&part[0], &v, 4);
    copy(&part[2], &v, 0);
    copy(&part[2], &v, 1);
    copy(&part[3], &v, 0); /* the degree-5 vertex from a second part */
    copy(&part[3], &v, 3);
    size_t dropped = 0;
    CHECK_INT(vb_vertex_list_merge(&out, part, 4, &dropped), VB_OK);
    CHECK_INT(dropped, 1);
    CHECK_INT(out.n, 5);
    char *a = text(&v), *b = text(&out);
    CHECK_STR(b, a);
    free(a);
    free(b);
    CHECK_INT(vb_vertex_list_merge(&out, part, 65, NULL), VB_EMISUSE);
    CHECK_INT(out.n, 5);
    for (int r = 0; r < 4; r++)
        vb_vertex_list_free(&part[r]);
    vb_vertex_list_free(&out);
    vb_vertex_list_free(&v);
}

/* Append keeps order and contents; it is how the pipeline's repair merges. */
static void test_append(void)
{
    vb_vertex_list v, w;
    whole(&v);
    vb_vertex_list_init(&w);
    CHECK_INT(vb_vertex_list_append(&w, &v), VB_OK);
    CHECK_INT(vb_vertex_list_append(&w, &v), VB_OK);
    CHECK_INT(w.n, 10);
    CHECK_INT(w.nids, 2 * v.nids);
    CHECK(w.y[6] == v.y[1] && w.ids[w.start[5]] == 0);
    size_t dropped;
    CHECK_INT(vb_vertex_list_canonical(&w, &dropped), VB_OK);
    CHECK_INT(dropped, 5);
    CHECK_INT(w.n, 5);
    vb_vertex_list_free(&v);
    vb_vertex_list_free(&w);
}

int main(void)
{
    test_pack_roundtrip();
    test_merge_parts();
    test_merge_sorted();
    test_append();
    VB_TEST_END();
}
