/* Unit tests of the context: errors, extended codes, warnings, counters. */
#include <stdlib.h>

#include "vb.h"
#include "vb_diag.h"
#include "vb_test.h"
#include "vb_vertex.h"

static void test_errors(void)
{
    vb_ctx *ctx;
    CHECK_INT(vb_open(&ctx, NULL), VB_OK);
    CHECK_STR(vb_errmsg(ctx), "");
    int rc = vb_error(ctx, VB_EINPUT_RADIUS, "a.xyzr", 7, "radius %s is not positive", "-1");
    CHECK_INT(rc, VB_EINPUT_RADIUS);
    CHECK_INT(VB_CATEGORY(rc), VB_EINPUT);
    CHECK_INT(vb_diag_number(rc), 103);
    CHECK_INT(vb_diag_number(VB_EDEVICE), 5);
    CHECK_STR(vb_errmsg(ctx), "a.xyzr:7: radius -1 is not positive");
    CHECK_INT(vb_errcode(ctx), VB_EINPUT_RADIUS);
    vb_clear_error(ctx);
    CHECK_INT(vb_errcode(ctx), VB_OK);
    vb_close(ctx);
}

static void test_warnings_counted(void)
{
    FILE *sink = tmpfile();
    vb_config cfg = {.verbosity = 1, .diag = sink};
    vb_ctx *ctx;
    CHECK_INT(vb_open(&ctx, &cfg), VB_OK);
    vb_warn(ctx, VB_W_CONTAINED, "x.pdb", 3, "sphere %d is contained", 2);
    CHECK_INT(vb_ctx_stats(ctx)->warnings, 1);
    rewind(sink);
    char buf[128] = {0};
    CHECK(fgets(buf, sizeof buf, sink) != NULL);
    CHECK_STR(buf, "vorball: W701: x.pdb:3: sphere 2 is contained\n");
    fclose(sink);
    vb_close(ctx);
}

/* Quiet while reading what another process warns about already (MPI ranks
 * reading one input), loud again after; the warnings still count. */
static void test_verbosity(void)
{
    FILE *sink = tmpfile();
    vb_config cfg = {.verbosity = 1, .diag = sink};
    vb_ctx *ctx;
    CHECK_INT(vb_open(&ctx, &cfg), VB_OK);
    int old = vb_set_verbosity(ctx, 0);
    CHECK_INT(old, 1);
    vb_warn(ctx, VB_W_CONTAINED, NULL, 0, "quiet");
    CHECK_INT(vb_set_verbosity(ctx, old), 0);
    vb_warn(ctx, VB_W_CONTAINED, NULL, 0, "loud");
    CHECK_INT(vb_ctx_stats(ctx)->warnings, 2);
    rewind(sink);
    char buf[128] = {0};
    CHECK(fgets(buf, sizeof buf, sink) != NULL);
    CHECK_STR(buf, "vorball: W701: loud\n");
    CHECK(fgets(buf, sizeof buf, sink) == NULL);
    CHECK_INT(vb_set_verbosity(NULL, 1), -1);
    fclose(sink);
    vb_close(ctx);
}

/* The misuse guard: a NULL context is caught, never dereferenced. */
static void test_misuse(void)
{
    CHECK_INT(vb_ctx_check(NULL), VB_EMISUSE);
    CHECK_INT(vb_warn(NULL, VB_W_CONTAINED, "x.pdb", 3, "sphere %d", 2), VB_EMISUSE);
    CHECK_INT(vb_errcode(NULL), VB_EMISUSE);
    CHECK_INT(vb_error(NULL, VB_EINPUT, NULL, 0, "no context"), VB_EINPUT);
    CHECK(vb_ctx_stats(NULL) == NULL);
    CHECK(vb_errmsg(NULL)[0] != '\0');
    vb_clear_error(NULL);
    vb_info(NULL, "nothing");
    vb_close(NULL);
    vb_ctx *ctx;
    CHECK_INT(vb_open(&ctx, NULL), VB_OK);
    CHECK_INT(vb_ctx_check(ctx), VB_OK);
    vb_close(ctx);
}

static void test_vertex_sort(void)
{
    vb_vertex_list v;
    vb_vertex_list_init(&v);
    uint32_t a[] = {4, 1, 3, 2}, b[] = {0, 1, 2, 3, 9}, c[] = {1, 2, 3, 4};
    CHECK_INT(vb_vertex_list_push(&v, a, 4, 2.0, 0, 0, 0, 0, VB_VERTEX_CERTIFIED), VB_OK);
    CHECK_INT(vb_vertex_list_push(&v, b, 5, 0, 0, 0, 0, 0, VB_VERTEX_CERTIFIED), VB_OK);
    CHECK_INT(vb_vertex_list_push(&v, c, 4, 1.0, 0, 0, 0, 0, VB_VERTEX_CERTIFIED), VB_OK);
    CHECK_INT(vb_vertex_list_sort(&v), VB_OK);
    CHECK_INT(v.n, 3);
    CHECK_INT(v.ids[0], 0);
    CHECK_INT(v.start[1], 5);
    CHECK_INT(v.ids[5], 1);
    CHECK_INT(v.ids[8], 4);
    CHECK(v.x[1] == 1.0 && v.x[2] == 2.0);
    vb_vertex_list_free(&v);
}

int main(void)
{
    test_errors();
    test_warnings_counted();
    test_verbosity();
    test_misuse();
    test_vertex_sort();
    VB_TEST_END();
}
