/* Unit test of the engine's lazy device (core/cells/vb_vertices.h,
 * vb_vertices_open): the device is opened at the first run that needs it,
 * so that `--device auto`'s host-thread crossover (vb_vertices_device)
 * applies to an engine as to vb_vertices_run. A device layer that counts
 * its openings (and has no device: each opening falls back to the twin,
 * W760) stands for a host that shows a GPU. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vb_test_spheres.h"
#include "vorball.h"

static int opens;

static int count_open(vb_ctx *ctx, vb_device_kind kind, vb_device **out)
{
    (void)kind;
    opens++;
    *out = NULL;
    return vb_error(ctx, VB_EDEVICE, NULL, 0, "no device in this test");
}

static int gpu_shown(void)
{
    return 1;
}

static vb_sphere_set *lattice(vb_ctx *ctx)
{
    vb_sphere_set *set = vb_test_corpus_load(ctx, "cubic_lattice");
    CHECK(set != NULL);
    return set;
}

/* Runs twice on an engine of cfg and checks the openings after each run
 * and the certified vertices (the 3x3x3 lattice's 8). */
static void runs(vb_ctx *ctx, const vb_vertices_backends *be, const vb_sphere_set *set,
                 const vb_vertices_config *cfg, int opens_after_first)
{
    opens = 0;
    vb_vertices_engine *e = NULL;
    CHECK_INT(vb_vertices_open(ctx, be, cfg, &e), VB_OK);
    CHECK_INT(opens, 0); /* nothing opened before the input is known */
    for (int k = 0; k < 2 && e; k++) {
        vb_vertices_result res;
        vb_vertices_result_init(&res);
        CHECK_INT(vb_vertices_run_on(ctx, e, set, cfg, &res), VB_OK);
        CHECK_INT(res.certified.n, 8);
        CHECK_STR(res.backend, "ref");
        CHECK_INT(opens, opens_after_first); /* opened once at most */
        vb_vertices_result_free(&res);
    }
    vb_vertices_close(e);
}

int main(void)
{
    vb_config vc = {0, NULL};
    vb_ctx *ctx;
    if (vb_open(&ctx, &vc) != VB_OK)
        return 1;
    vb_set_verbosity(ctx, 0); /* the fallback's W760 */
    vb_device_layer layer = *vb_default_backends()->devices;
    layer.open = count_open;
    layer.gpu_present = gpu_shown;
    vb_vertices_backends be = *vb_default_backends();
    be.devices = &layer;
    vb_sphere_set *set = lattice(ctx);
    if (set) {
        vb_vertices_config cfg = {0};
        cfg.device = VB_DEVICE_AUTO;
        cfg.propose.threads = 2;
        cfg.host_below = VB_HOST_BELOW_DEFAULT; /* not the tests' VORBALL_HOST_BELOW=1 */
        runs(ctx, &be, set, &cfg, 0); /* 27 spheres, below the crossover: host threads */
        cfg.host_below = 1;           /* always the device */
        runs(ctx, &be, set, &cfg, 1);
        cfg.device = VB_DEVICE_CPU;   /* asked for by name: opened at the first run */
        runs(ctx, &be, set, &cfg, 1);
        cfg.device = VB_DEVICE_REF;
        runs(ctx, &be, set, &cfg, 0);
    }
    vb_spheres_free(set);
    vb_close(ctx);
    VB_TEST_END();
}
