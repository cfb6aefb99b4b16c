/* The selected frames one by one (vb_frames_each.h). */
#include "vb_frames_each.h"

int vb_frames_each(vb_ctx *ctx, const char *path, const char *traj_path,
                   const vb_read_options *ro, const vb_frame_range *range, vb_frame_each_fn fn,
                   void *arg, long *selected)
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
            rc = fn(arg, index, model, s);
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
