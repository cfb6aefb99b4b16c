/* The jfa handle's run and results (lib/vb_jfa.h): the seeds made from
 * their source, the engine opened on the default device layer, the timed
 * variants checked, the figures read and written, the picture. */
#include <stdlib.h>
#include <string.h>

#include "jfa_handle.h"
#include "vb_default.h"

/* The run's seeds, engine and figures released (the options stay). */
static void run_free(vb_jfa *j)
{
    vbj_runs_free(&j->runs);
    memset(&j->runs, 0, sizeof j->runs);
    vbj_seeds_free(&j->s);
    j->ran = 0;
}

void vb_jfa_free(vb_jfa *j)
{
    if (!j)
        return;
    run_free(j);
    vbj_backend_close(j->e);
    if (j->dev)
        vb_default_devices()->close(j->dev);
    free(j->points);
    free(j);
}

int vb_jfa_source_file(vb_jfa *j, const char *path)
{
    j->path = path;
    return VB_OK;
}

int vb_jfa_source_points(vb_jfa *j, const double *points, size_t npoints)
{
    size_t dim = j->set.dim == 3 ? 3 : 2, bytes = npoints * dim * sizeof *points;
    double *p = malloc(bytes ? bytes : 1);
    if (!p)
        return vb_error(j->ctx, VB_ENOMEM, NULL, 0, "jfa points: out of memory");
    memcpy(p, points, bytes);
    free(j->points);
    j->points = p;
    j->npoints = npoints;
    return VB_OK;
}

int vb_jfa_source_spheres(vb_jfa *j, const vb_sphere_set *s, const char *name)
{
    j->spheres = s;
    j->spheres_name = name;
    return VB_OK;
}

int vb_jfa_run(vb_ctx *ctx, vb_jfa *j)
{
    run_free(j);
    vbj_seed_source src = {j->spheres, j->spheres_name, j->points, j->npoints, j->path, j->dist};
    int rc = vbj_seeds_make(ctx, &j->set, &src, &j->s, j->source, sizeof j->source);
    j->spheres = NULL; /* kept by pointer until here */
    if (!rc && !j->e)
        rc = vbj_backend_open(ctx, vb_default_devices(), j->kind, &j->dev, &j->e);
    if (!rc)
        rc = vbj_runs_run(ctx, j->e, &j->s, &j->set, j->v, j->nv, j->check, &j->runs);
    if (rc)
        run_free(j);
    else
        j->ran = 1;
    return rc;
}

int vb_jfa_info_get(const vb_jfa *j, vb_jfa_info *i)
{
    if (!j->ran)
        return -1;
    *i = (vb_jfa_info){j->runs.device, j->source, j->s.dim, j->s.n, j->s.k,
                       j->runs.repeat, j->runs.exact_ms, j->runs.n};
    return 0;
}

int vb_jfa_figures_get(const vb_jfa *j, int k, vb_jfa_figures *f)
{
    if (!j->ran || k < 0 || k >= j->runs.n)
        return -1;
    const vbj_figures *x = &j->runs.run[k];
    const vbj_counts *c = &x->r.counts;
    const vbj_metrics *m = &x->m;
    *f = (vb_jfa_figures){
        .variant = vbj_variant_name(x->v), .time_ms = x->mean_ms, .time_ms_min = x->min_ms,
        .gpu_ms = x->mean_gpu_ms, .fill_ms = x->r.ms_fill, .prep_transfer_ms = x->r.ms_transfer,
        .prep_ms = x->r.ms_prep, .steps = c->steps, .m = c->m, .collisions = c->collisions,
        .pixels_processed = c->step_pixels, .threads = c->threads, .boundary = c->boundary,
        .tiles = c->tiles, .tiles_uniform = c->tiles_uniform, .candidates = c->candidates,
        .survivors = c->survivors, .evals = c->evals, .exact_voxels = c->exact_voxels,
        .tiles_chunked = c->tiles_chunked, .visited = c->visited, .checked = x->checked,
        .wrong = m->wrong, .differ = m->differ, .boundary_exact = m->boundary_exact,
        .boundary_found = m->boundary_found, .boundary_missed = m->boundary_missed,
        .boundary_extra = m->boundary_extra, .wrong_rate = m->wrong_rate,
        .max_err = m->max_err, .mean_err = m->mean_err, .labels = x->r.labels,
        .pixels = x->r.pixels};
    return 0;
}

void vb_jfa_write(const vb_jfa *j, FILE *f, int json)
{
    if (j->ran)
        vbj_runs_write(f, &j->runs, &j->s, j->source, json);
}

int vb_jfa_picture(vb_ctx *ctx, const vb_jfa *j, const uint32_t *labels, uint8_t **rgb,
                   uint32_t *w)
{
    if (!labels && j->ran)
        labels = j->runs.run[j->runs.n - 1].r.labels;
    if (!labels)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "jfa picture: no labels");
    vbj_seeds grid = {.dim = (int)j->set.dim, .n = (uint32_t)j->set.n};
    return vbj_picture(ctx, &grid, labels, &j->set, rgb, w);
}
