/* Vertex files: tsv / json / voronota round trips are bit-exact, detection by
 * content, the voronota quadruple fan of a degenerate vertex, and malformed
 * input refused with the right code and line. */
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vb_test.h"
#include "vb_vertex_io.h"

/* Doubles whose %.17g text is the hardest to round-trip. */
static const double awkward[] = {0.1, -1.0 / 3.0, 1e-300, 5e-324, 123456789.12345678,
                                 -0.0, 2.2250738585072014e-308, 1.7976931348623157e308};

static void make_list(vb_vertex_list *v)
{
    vb_vertex_list_init(v);
    uint32_t a[] = {7, 3, 1, 2};
    uint32_t b[] = {0, 1, 2, 3, 4, 5, 6, 7};
    vb_vertex_list_push(v, a, 4, awkward[0], awkward[1], awkward[2], awkward[3], 0,
                        VB_VERTEX_CERTIFIED);
    vb_vertex_list_push(v, b, 8, awkward[4], awkward[5], awkward[6], awkward[7], 0,
                        VB_VERTEX_REJECTED);
    vb_vertex_list_push(v, a, 4, -2.5, 4294967296.0, 1e22, -7.25, 0, VB_VERTEX_CANDIDATE);
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* Writes v in fmt to memory and reads it back. */
static int round_trip(vb_ctx *ctx, const vb_vertex_list *v, vb_vertex_format fmt,
                      vb_vertex_list *back, vb_vertex_format *det, long **lines, char **text)
{
    size_t len = 0;
    FILE *f = open_memstream(text, &len);
    int rc = vb_vertex_write(ctx, f, v, fmt, "test\nsecond line");
    fclose(f);
    if (rc)
        return rc;
    vb_vertex_list_init(back);
    return vb_vertex_read_buffer(ctx, "mem", *text, len, back, det, lines);
}

static void test_round_trip(vb_ctx *ctx, vb_vertex_format fmt)
{
    vb_vertex_list v, back;
    make_list(&v);
    vb_vertex_format det = (vb_vertex_format)-1;
    long *lines = NULL;
    char *text = NULL;
    CHECK_INT(round_trip(ctx, &v, fmt, &back, &det, &lines, &text), VB_OK);
    CHECK_INT(det, fmt);
    CHECK_INT(back.n, v.n);
    CHECK_INT(back.nids, v.nids);
    for (size_t k = 0; k < v.n && k < back.n; k++) {
        CHECK(same_bits(back.x[k], v.x[k]) && same_bits(back.y[k], v.y[k]) &&
              same_bits(back.z[k], v.z[k]) && same_bits(back.t[k], v.t[k]));
        CHECK_INT(back.status[k], v.status[k]);
        CHECK_INT(back.start[k + 1], v.start[k + 1]);
    }
    CHECK(memcmp(back.ids, v.ids, v.nids * sizeof *v.ids) == 0);
    /* header lines: the tsv has 4 comment lines (title, 2 comment, columns) */
    if (fmt == VB_VFMT_TSV) {
        CHECK_INT(lines[0], 5);
        CHECK_INT(lines[2], 7);
        CHECK(strncmp(text, "# vorball vertices\n# test\n# second line\n# ids\tx", 44) == 0);
        CHECK(strstr(text, "\n1,2,3,7\t0.10000000000000001\t") != NULL);
    }
    if (fmt == VB_VFMT_JSON) {
        CHECK_INT(lines[0], 2);
        CHECK_INT(lines[1], 3);
    }
    free(lines);
    free(text);
    vb_vertex_list_free(&v);
    vb_vertex_list_free(&back);
}

static void test_voronota(vb_ctx *ctx)
{
    vb_vertex_list v, back;
    make_list(&v);
    vb_vertex_format det;
    long *lines = NULL;
    char *text = NULL;
    CHECK_INT(round_trip(ctx, &v, VB_VFMT_VORONOTA, &back, &det, &lines, &text), VB_OK);
    CHECK_INT(det, VB_VFMT_VORONOTA);
    /* 1 + (8 - 3) + 1 quadruple lines, each with 4 ids */
    CHECK_INT(back.n, 7);
    CHECK_INT(back.nids, 28);
    uint32_t fan[5][4] = {{0, 1, 2, 3}, {0, 1, 2, 4}, {0, 1, 2, 5}, {0, 1, 2, 6}, {0, 1, 2, 7}};
    for (int i = 0; i < 5 && back.n == 7; i++) {
        CHECK(memcmp(back.ids + back.start[1 + i], fan[i], sizeof fan[i]) == 0);
        CHECK(same_bits(back.x[1 + i], awkward[4]) && same_bits(back.t[1 + i], awkward[7]));
        CHECK_INT(lines[1 + i], 2 + i);
        CHECK_INT(back.status[1 + i], VB_VERTEX_CANDIDATE);
    }
    CHECK(strncmp(text, "1 2 3 7 0.10000000000000001 ", 28) == 0);
    free(lines);
    free(text);
    vb_vertex_list_free(&back);
    /* a vertex of three ids cannot be written as a quadruple */
    uint32_t three[] = {0, 1, 2};
    vb_vertex_list_push(&v, three, 3, 0, 0, 0, 0, 0, VB_VERTEX_CANDIDATE);
    FILE *f = fopen("/dev/null", "w");
    CHECK_INT(vb_vertex_write(ctx, f, &v, VB_VFMT_VORONOTA, NULL), VB_EMISUSE);
    fclose(f);
    vb_vertex_list_free(&v);
}

/* Reads `text`; returns the status and leaves the line of the error in *line. */
static int read_text(vb_ctx *ctx, const char *text, vb_vertex_list *out, vb_vertex_format *det)
{
    vb_clear_error(ctx);
    return vb_vertex_read_buffer(ctx, "bad.txt", text, strlen(text), out, det, NULL);
}

static void test_errors(vb_ctx *ctx)
{
    vb_vertex_list v;
    vb_vertex_list_init(&v);
    vb_vertex_format det;
    CHECK_INT(read_text(ctx, "", &v, &det), VB_OK);
    CHECK_INT(det, VB_VFMT_TSV);
    CHECK_INT(v.n, 0);
    CHECK_INT(read_text(ctx, "# only\n\n", &v, &det), VB_OK);
    CHECK_INT(read_text(ctx, "0,1,2,3\t1\t2\t3\t4\tcertified\n0,1,x,3\t1\t2\t3\t4\n", &v, &det),
              VB_EINPUT_MALFORMED);
    CHECK(strstr(vb_errmsg(ctx), "bad.txt:2:") != NULL);
    CHECK_INT(v.n, 0); /* the good first line was dropped again */
    CHECK_INT(read_text(ctx, "0,1,2,3\t1\t2\tnan\t4\n", &v, &det), VB_EINPUT_NONFINITE);
    CHECK_INT(read_text(ctx, "0,1,2,3\t1\t2\t3\t4\tgood\n", &v, &det), VB_EINPUT_MALFORMED);
    CHECK_INT(read_text(ctx, "0,1,2,4294967296\t1\t2\t3\t4\n", &v, &det), VB_EINPUT_MALFORMED);
    CHECK_INT(read_text(ctx, "0,1,2,3\t1\t2\t3\n", &v, &det), VB_EINPUT_MALFORMED);
    CHECK_INT(read_text(ctx, "0 1 2 3 1 2 3 4\n0 1 2 3 1 2 3\n", &v, &det), VB_EINPUT_MALFORMED);
    CHECK(strstr(vb_errmsg(ctx), "bad.txt:2:") != NULL);
    CHECK_INT(read_text(ctx, "0 1 2 3 1 2 3 inf\n", &v, &det), VB_EINPUT_NONFINITE);
    CHECK_INT(read_text(ctx, "{\"vertices\":[\n{\"ids\":[0,1,2,3],\"x\":1,\"y\":2,\"z\":null,\"t\":0}]}",
                        &v, &det),
              VB_EINPUT_NONFINITE);
    CHECK(strstr(vb_errmsg(ctx), "bad.txt:2:") != NULL);
    CHECK_INT(read_text(ctx, "{\"vertices\":[{\"ids\":[0,1,2,3],\"x\":1,\"y\":2,\"t\":0}]}", &v,
                        &det),
              VB_EINPUT_MALFORMED);
    CHECK_INT(read_text(ctx, "{\"vertices\":[{\"ids\":[0,1,2,3],\"x\":1,\"y\":2,\"z\":3,\"t\":0}]",
                        &v, &det),
              VB_EINPUT_MALFORMED);
    CHECK_INT(read_text(ctx, "{\"other\":1}", &v, &det), VB_EINPUT_MALFORMED);
    CHECK_INT(read_text(ctx, "{\"vertices\":[{\"ids\":[],\"x\":1,\"y\":2,\"z\":3,\"t\":0}]}", &v,
                        &det),
              VB_EINPUT_MALFORMED);
    /* unknown keys, nested values and escapes are skipped */
    CHECK_INT(read_text(ctx,
                        "{\"meta\":{\"a\":[1,{\"b\":\"q\\\"x\"}],\"c\":true},\"vertices\":[{\"ids\":"
                        "[4,0,2,1],\"extra\":[null,false],\"x\":1.5,\"y\":-2,\"z\":3e2,\"t\":0}]}",
                        &v, &det),
              VB_OK);
    CHECK_INT(det, VB_VFMT_JSON);
    CHECK_INT(v.n, 1);
    CHECK_INT(v.ids[3], 4);
    CHECK_NEAR(v.z[0], 300.0, 0);
    /* deep nesting is refused, not recursed into without bound */
    char deep[400] = "{\"x\":";
    for (int i = 0; i < 100; i++)
        strcat(deep, "[");
    CHECK_INT(read_text(ctx, deep, &v, &det), VB_EINPUT_MALFORMED);
    CHECK_INT(v.n, 1);
    vb_vertex_list_free(&v);
    CHECK_INT(vb_vertex_read_file(ctx, "/nonexistent/vertices.tsv", &v, &det, NULL), VB_EIO);
}

static void test_format_names(vb_ctx *ctx)
{
    vb_vertex_format f;
    CHECK_INT(vb_vertex_format_parse(ctx, "json", &f), VB_OK);
    CHECK_INT(f, VB_VFMT_JSON);
    CHECK_INT(vb_vertex_format_parse(ctx, "voronota", &f), VB_OK);
    CHECK_INT(f, VB_VFMT_VORONOTA);
    CHECK_INT(vb_vertex_format_parse(ctx, "csv", &f), VB_EMISUSE);
    CHECK_STR(vb_vertex_status_name(VB_VERTEX_REJECTED), "rejected");
}

/* The provenance (issue 35): tsv '#' lines after the title, json keys
 * before the comment; both read back to the same vertices (the reader skips
 * '#' lines and unknown keys, a number among them). */
static void test_provenance(vb_ctx *ctx)
{
    vb_vertex_list v;
    make_list(&v);
    vb_provenance prov = {"in \"x\".pdb", 327, "vertices --arcs in.pdb"};
    char want[512];
    snprintf(want, sizeof want,
             "# vorball vertices\n# tool: vorball %s (commit %s)\n# input: in \"x\".pdb, 327 "
             "spheres\n# options: vertices --arcs in.pdb\n# cert\n# ids\t",
             vb_build_version(), vb_build_commit());
    CHECK_INT(vb_provenance_text(&prov, NULL, 0),
              strlen(want) - strlen("# vorball vertices\n# cert\n# ids\t") - 3 * 2);
    for (int fmt = VB_VFMT_TSV; fmt <= VB_VFMT_JSON; fmt++) {
        char *text = NULL;
        size_t len = 0;
        FILE *f = open_memstream(&text, &len);
        CHECK_INT(vb_vertex_write_prov(ctx, f, &v, (vb_vertex_format)fmt, &prov, "cert"), VB_OK);
        fclose(f);
        if (fmt == VB_VFMT_TSV) {
            CHECK(strncmp(text, want, strlen(want)) == 0);
        } else {
            char head[512];
            snprintf(head, sizeof head,
                     "{\"tool\":\"vorball %s (commit %s)\",\"input\":\"in \\\"x\\\".pdb\","
                     "\"spheres\":327,\"options\":\"vertices --arcs in.pdb\",\"comment\":\"cert\","
                     "\"vertices\":[",
                     vb_build_version(), vb_build_commit());
            CHECK(strncmp(text, head, strlen(head)) == 0);
        }
        vb_vertex_list back;
        vb_vertex_list_init(&back);
        vb_vertex_format det;
        CHECK_INT(vb_vertex_read_buffer(ctx, "mem", text, len, &back, &det, NULL), VB_OK);
        CHECK_INT(det, fmt);
        CHECK_INT(back.n, v.n);
        CHECK(back.n == v.n && same_bits(back.t[1], v.t[1]));
        vb_vertex_list_free(&back);
        free(text);
    }
    vb_vertex_list_free(&v);
}

int main(void)
{
    vb_ctx *ctx;
    vb_config cfg = {0};
    if (vb_open(&ctx, &cfg))
        return 1;
    test_round_trip(ctx, VB_VFMT_TSV);
    test_round_trip(ctx, VB_VFMT_JSON);
    test_voronota(ctx);
    test_provenance(ctx);
    test_errors(ctx);
    test_format_names(ctx);
    vb_close(ctx);
    VB_TEST_END();
}
