/* A channels program outside the tree, compiled against the installed
 * headers and libvorball (tests/pipeline/install.sh), through the public
 * handle of vb_channels.h alone:
 *   install_channels one INPUT          the first frame by vb_channels_run,
 *                                       its table by vb_channels_write_frame_csv
 *   install_channels frames INPUT TRAJ  every frame of the trajectory by
 *                                       vb_channels_run_frames
 * with --grid 64 --device ref set by name, the CSV table on stdout (the
 * same bytes as `vorball channels` with those options) and, on stderr,
 * "rows N" (one) or "frames N" (frames). Exit 0, or 1 with a message. */
#include <stdio.h>
#include <string.h>

#include "vorball.h"

static int setup(vb_ctx *ctx, vb_channels **ch, const char *traj)
{
    char err[512];
    int rc = vb_channels_new(ctx, ch);
    if (rc == VB_OK && (vb_channels_set(*ch, "--grid", "64", err, sizeof err) != 0 ||
                        vb_channels_set(*ch, "device", "ref", err, sizeof err) != 0 ||
                        (traj && vb_channels_set(*ch, "--traj", traj, err, sizeof err) != 0) ||
                        vb_channels_check(*ch, err, sizeof err) != 0))
        rc = vb_error(ctx, VB_EMISUSE, NULL, 0, "%s", err);
    return rc == VB_OK ? vb_channels_open(ctx, *ch) : rc;
}

int main(int argc, char **argv)
{
    int frames = argc == 4 && strcmp(argv[1], "frames") == 0;
    if (!frames && !(argc == 3 && strcmp(argv[1], "one") == 0)) {
        fprintf(stderr, "usage: install_channels one INPUT | frames INPUT TRAJ\n");
        return 1;
    }
    vb_config cfg = {0, NULL}; /* quiet */
    vb_ctx *ctx;
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 1;
    vb_channels *ch = NULL;
    vb_frame_source *F = NULL;
    vb_sphere_set *s = NULL;
    vb_read_options ro = {0};
    int model = 0, rc = setup(ctx, &ch, frames ? argv[3] : NULL);
    if (rc == VB_OK)
        rc = vb_frame_source_open(ctx, argv[2], frames ? argv[3] : NULL, &ro, &F);
    if (rc == VB_OK && frames) {
        vb_channels_io io = {0};
        long selected = 0;
        io.input = argv[2];
        io.sink[VB_CHANNELS_SINK_TABLE] = stdout;
        vb_channels_write_head(ch, &io, NULL);
        rc = vb_channels_run_frames(ctx, ch, F, &io, &selected);
        if (rc == VB_OK)
            rc = vb_channels_finish(ctx, ch, &io, 1, selected);
        if (rc == VB_OK)
            fprintf(stderr, "frames %ld\n", selected);
    } else if (rc == VB_OK) {
        rc = vb_frame_source_next(ctx, F, &s, &model);
        if (rc == VB_OK && !s)
            rc = vb_error(ctx, VB_EINPUT_MODEL, argv[2], 0, "no frame");
        if (rc == VB_OK)
            rc = vb_channels_run(ctx, ch, s, 0, model, 1, 0);
        if (rc == VB_OK) {
            vb_channels_write_frame_csv(ch, stdout);
            fprintf(stderr, "rows %zu\n", vb_channels_result_rows(vb_channels_last(ch)));
        }
    }
    if (rc != VB_OK)
        fprintf(stderr, "install_channels: E%d: %s\n", vb_diag_number(rc), vb_errmsg(ctx));
    vb_channels_free(ch);
    vb_spheres_free(s);
    vb_frame_source_close(F);
    vb_close(ctx);
    return rc == VB_OK && fflush(stdout) == 0 ? 0 : 1;
}
