/* Periodic vertices frame by frame (vb_periodic_frames.h). */
#include "vb_periodic_frames.h"

#include "vb_cells.h"
#include "vb_default.h"

int vb_periodic_run_frames(vb_ctx *ctx, const char *path, const char *traj_path,
                           const vb_read_options *ro, const vb_frame_range *range,
                           const vb_box *box, const vb_vertices_config *cfg,
                           vb_periodic_frame_fn fn, void *arg, long *selected)
{
    vb_frame_source *F = NULL;
    long index = 0, done = 0;
    int rc = vb_frame_source_open(ctx, path, traj_path, ro, &F);
    while (rc == VB_OK && (range->end < 0 || index < range->end)) {
        vb_sphere_set *s = NULL;
        int model = 0;
        rc = vb_frame_source_next(ctx, F, &s, &model);
        if (rc != VB_OK || !s)
            break;
        if (vb_frame_range_has(range, index)) {
            const vb_box *b = box ? box : s->box;
            if (!b)
                rc = vb_error(ctx, VB_EINPUT_BOX, traj_path ? traj_path : path, 0,
                              "--periodic: frame %ld carries no box: give --box", index);
            if (rc == VB_OK)
                rc = vb_cells_frame_decimals(ctx, s);
            vb_periodic_result res;
            vb_periodic_result_init(&res);
            if (rc == VB_OK)
                rc = vb_periodic_vertices_run(ctx, s, b, cfg, vb_default_backends(), &res);
            if (rc == VB_OK)
                rc = fn(arg, index, model, s, b, &res);
            vb_periodic_result_free(&res);
            done++;
        }
        vb_spheres_free(s);
        index++;
    }
    vb_frame_source_close(F);
    if (selected)
        *selected = done;
    if (rc == VB_OK && done == 0)
        rc = vb_error(ctx, VB_EINPUT_MODEL, traj_path ? traj_path : path, 0,
                      "no frame selected (--frames / --model)");
    return rc;
}
