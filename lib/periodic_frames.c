/* Periodic vertices frame by frame (vb_periodic_frames.h). */
#include "vb_periodic_frames.h"

#include "vb_cells.h"
#include "vb_default.h"
#include "vb_frames_each.h"

typedef struct job {
    vb_ctx *ctx;
    const char *name;
    const vb_box *box;
    const vb_vertices_config *cfg;
    vb_periodic_frame_fn fn;
    void *arg;
} job;

static int one_frame(void *arg, long index, int model, vb_sphere_set *s)
{
    job *J = arg;
    const vb_box *b = J->box ? J->box : s->box;
    if (!b)
        return vb_error(J->ctx, VB_EINPUT_BOX, J->name, 0,
                        "--periodic: frame %ld carries no box: give --box", index);
    int rc = vb_cells_frame_decimals(J->ctx, s);
    vb_periodic_result res;
    vb_periodic_result_init(&res);
    if (rc == VB_OK)
        rc = vb_periodic_vertices_run(J->ctx, s, b, J->cfg, vb_default_backends(), &res);
    if (rc == VB_OK)
        rc = J->fn(J->arg, index, model, s, b, &res);
    vb_periodic_result_free(&res);
    return rc;
}

int vb_periodic_run_frames(vb_ctx *ctx, const char *path, const char *traj_path,
                           const vb_read_options *ro, const vb_frame_range *range,
                           const vb_box *box, const vb_vertices_config *cfg,
                           vb_periodic_frame_fn fn, void *arg, long *selected)
{
    job J = {ctx, traj_path ? traj_path : path, box, cfg, fn, arg};
    return vb_frames_each(ctx, path, traj_path, ro, range, one_frame, &J, selected);
}
