/* The ranges of a `vorball jfa` setup (vbj_setup_check) at their edges:
 * each field accepted at its bounds, refused one past them, with the
 * message the command prints; the defaults (vbj_setup_defaults). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "vb.h"
#include "vb_test.h"
#include "vbj_jfa.h"

static vbj_setup defaults(void)
{
    vbj_setup s;
    vbj_setup_defaults(&s);
    return s;
}

/* The 3D picture's slices: each below n, at most VBJ_MAX_SLICES. */
static void slices(vb_ctx *ctx)
{
    vbj_setup s = defaults();
    s.dim = 3;
    s.n = 32;
    s.nslices = VBJ_MAX_SLICES;
    for (uint32_t i = 0; i < VBJ_MAX_SLICES; i++)
        s.slice[i] = i == 0 ? 31 : i;
    CHECK_INT(vbj_setup_check(ctx, &s), VB_OK);
    s.slice[0] = 32;
    CHECK_INT(vbj_setup_check(ctx, &s), VB_EMISUSE);
    CHECK(strcmp(vb_errmsg(ctx), "bad --slice") == 0);
    s.slice[0] = 0;
    s.nslices = VBJ_MAX_SLICES + 1;
    CHECK_INT(vbj_setup_check(ctx, &s), VB_EMISUSE);
    CHECK(strcmp(vb_errmsg(ctx), "bad --slice") == 0);
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
    /* The command's defaults. */
    CHECK(s.dim == 2 && s.n == 512 && s.k == 100 && s.margin == 2.0 && s.repeat == 1 &&
          s.rng == 1 && s.m == 0 && s.fuse_cells == 0 && s.nslices == 0);
    slices(ctx);
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
