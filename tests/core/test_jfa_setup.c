/* The ranges of a `vorball jfa` setup (vbj_setup_check) at their edges:
 * each field accepted at its bounds, refused one past them, with the
 * message the command prints. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "vb.h"
#include "vb_test.h"
#include "vbj_jfa.h"

static vbj_setup defaults(void)
{
    vbj_setup s = {.dim = 2, .n = 512, .k = 100, .margin = 2.0, .repeat = 1};
    return s;
}

/* Field at `off` set to v: VB_OK, or VB_EMISUSE with message `msg`. */
static void one(vb_ctx *ctx, size_t off, uint64_t v, const char *msg)
{
    vbj_setup s = defaults();
    memcpy((char *)&s + off, &v, sizeof v);
    CHECK_INT(vbj_setup_check(ctx, &s), msg ? VB_EMISUSE : VB_OK);
    if (msg)
        CHECK(strcmp(vb_errmsg(ctx), msg) == 0);
}

int main(void)
{
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK)
        return 1;
    vbj_setup s = defaults();
    CHECK_INT(vbj_setup_check(ctx, &s), VB_OK);
    size_t dim = offsetof(vbj_setup, dim), n = offsetof(vbj_setup, n);
    size_t k = offsetof(vbj_setup, k), m = offsetof(vbj_setup, m);
    size_t fuse = offsetof(vbj_setup, fuse_cells), rep = offsetof(vbj_setup, repeat);
    one(ctx, dim, 2, NULL);
    one(ctx, dim, 3, NULL);
    one(ctx, dim, 1, "--dim must be 2 or 3");
    one(ctx, dim, 4, "--dim must be 2 or 3");
    one(ctx, n, VBJ_MAX_N, NULL);
    one(ctx, n, VBJ_MAX_N + 1ull, "bad --size");
    one(ctx, n, UINT64_MAX, "bad --size");
    one(ctx, k, 1, NULL);
    one(ctx, k, UINT64_MAX, NULL);
    one(ctx, k, 0, "bad --seeds");
    one(ctx, m, 0, NULL);
    one(ctx, m, 1, NULL);
    one(ctx, m, VBJ_MAX_N, NULL);
    one(ctx, m, VBJ_MAX_N + 1ull, "bad -m");
    one(ctx, fuse, 0, NULL);
    one(ctx, fuse, UINT32_MAX, NULL);
    one(ctx, fuse, UINT32_MAX + 1ull, "bad --fuse-cells");
    one(ctx, rep, 1, NULL);
    one(ctx, rep, 100000, NULL);
    one(ctx, rep, 0, "bad --repeat");
    one(ctx, rep, 100001, "bad --repeat");
    s.margin = 0.0;
    CHECK_INT(vbj_setup_check(ctx, &s), VB_OK);
    s.margin = -0x1p-1074;
    CHECK_INT(vbj_setup_check(ctx, &s), VB_EMISUSE);
    CHECK(strcmp(vb_errmsg(ctx), "bad --margin") == 0);
    s.margin = NAN;
    CHECK_INT(vbj_setup_check(ctx, &s), VB_EMISUSE);
    vb_close(ctx);
    VB_TEST_END();
}
