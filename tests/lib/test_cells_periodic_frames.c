/* Periodic cell measures frame by frame (vb_cells_run_frames_periodic,
 * issue 34) on a short synthetic trajectory: a three-model PDB whose
 * models each carry their own CRYST1 before MODEL (as MD trajectories
 * written as PDB do), two atoms moving in a cubic box of 5, 5.5 and 6 A.
 * - each frame runs in its own box: with a probe that covers the box, the
 *   frame's volumes enclose its box's volume (125, 166.375, 216);
 * - each frame's measures equal the one-set call (vb_cells_run_periodic)
 *   on that frame's atoms and box, bound for bound;
 * - one box for every frame (--box) instead: 343 each;
 * - a model without a box and no fixed box: VB_EINPUT_BOX (E120). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "vb_test.h"
#include "vorball.h"

static vb_ctx *g_ctx;

typedef struct seen {
    int frames;
    double expect[3];   /* the volume each frame's box has */
    const vb_box *fixed;
    vb_measure_options opt;
} seen;

static int on_frame(void *arg, long frame, int model, const vb_sphere_set *set,
                    const vb_cell_measures *m)
{
    seen *s = arg;
    CHECK_INT(model, (int)frame + 1);
    CHECK(frame >= 0 && frame < 3);
    if (frame < 0 || frame >= 3)
        return VB_OK;
    CHECK(m->periodic == 1 && m->n == 2);
    double lo = m->vol_lo[0] + m->vol_lo[1], hi = m->vol_hi[0] + m->vol_hi[1];
    if (!(lo <= s->expect[frame] && s->expect[frame] <= hi && hi - lo < 5e-3 * s->expect[frame]))
        fprintf(stderr, "frame %ld: volume [%.9g, %.9g], box %.9g\n", frame, lo, hi, s->expect[frame]);
    CHECK(lo <= s->expect[frame] && s->expect[frame] <= hi && hi - lo < 5e-3 * s->expect[frame]);
    /* The one-set call on the frame's atoms in the same box. */
    const vb_box *b = s->fixed ? s->fixed : set->box;
    CHECK(b != NULL);
    vb_cell_measures one;
    CHECK_INT(vb_cells_run_periodic(g_ctx, set, b, &s->opt, &one), VB_OK);
    for (size_t i = 0; i < 2 && one.n == 2; i++)
        CHECK(one.vol_lo[i] == m->vol_lo[i] && one.vol_hi[i] == m->vol_hi[i] &&
              one.sas_lo[i] == m->sas_lo[i] && one.sas_hi[i] == m->sas_hi[i]);
    vb_cell_measures_free(&one);
    s->frames++;
    return VB_OK;
}

static void write_models(const char *path, int boxes)
{
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f)
        return;
    const double edge[3] = {5.0, 5.5, 6.0};
    for (int k = 0; k < 3; k++) {
        if (boxes || k != 1)
            fprintf(f, "CRYST1%9.3f%9.3f%9.3f  90.00  90.00  90.00 P 1           1\n", edge[k],
                    edge[k], edge[k]);
        fprintf(f, "MODEL     %4d\n", k + 1);
        const double p[2][3] = {{1.0 + 0.1 * k, 1.25, 0.5}, {3.5, 2.75 - 0.2 * k, 3.0 + 0.1 * k}};
        for (int a = 0; a < 2; a++)
            fprintf(f, "ATOM  %5d  C   GLY A   1    %8.3f%8.3f%8.3f  1.00  0.00           C\n",
                    a + 1, p[a][0], p[a][1], p[a][2]);
        fputs("ENDMDL\n", f);
    }
    fclose(f);
}

int main(void)
{
    vb_config cfg0 = {0, NULL};
    if (vb_open(&g_ctx, &cfg0) != VB_OK)
        return 1;
    char path[] = "/tmp/vb_cells_frames_XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    if (fd < 0)
        return 1;
    close(fd);
    write_models(path, 1);
    vb_read_options ro = {0};
    vb_frame_range all = {0, -1, 1};
    seen s;
    memset(&s, 0, sizeof s);
    vb_measure_defaults(&s.opt);
    s.opt.probe = 4.0; /* expanded radius 5.7: the balls cover every box */
    s.opt.max_patches = 4000;
    s.opt.threads = 1;
    s.expect[0] = 125.0, s.expect[1] = 166.375, s.expect[2] = 216.0;
    long selected = 0;
    CHECK_INT(vb_cells_run_frames_periodic(g_ctx, path, NULL, &ro, &all, NULL, &s.opt, on_frame,
                                           &s, &selected),
              VB_OK);
    CHECK_INT(selected, 3);
    CHECK_INT(s.frames, 3);
    /* One box for every frame. */
    const char *seven[3] = {"7", "7", "7"};
    vb_box fixed;
    CHECK_INT(vb_box_parse_args(g_ctx, seven, 3, &fixed), VB_OK);
    s.frames = 0;
    s.fixed = &fixed;
    s.expect[0] = s.expect[1] = s.expect[2] = 343.0;
    CHECK_INT(vb_cells_run_frames_periodic(g_ctx, path, NULL, &ro, &all, &fixed, &s.opt, on_frame,
                                           &s, &selected),
              VB_OK);
    CHECK_INT(s.frames, 3);
    /* Model 2 without its CRYST1: E120 naming frame 1. */
    write_models(path, 0);
    s.frames = 0;
    s.fixed = NULL;
    s.expect[0] = 125.0;
    CHECK_INT(vb_cells_run_frames_periodic(g_ctx, path, NULL, &ro, &all, NULL, &s.opt, on_frame,
                                           &s, &selected),
              VB_EINPUT_BOX);
    CHECK_INT(s.frames, 1);
    CHECK(strstr(vb_errmsg(g_ctx), "frame 1") != NULL);
    remove(path);
    vb_close(g_ctx);
    VB_TEST_END();
}
