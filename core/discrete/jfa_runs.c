/* A `vorball jfa` run, whole (vbj_runs.h): the seeds from their source,
 * the timed variants with their warnings and checks, the figures' two
 * printed forms and the picture. */
#include <stdlib.h>
#include <string.h>

#include "vb_diag.h"
#include "vb_json.h"
#include "vb_parallel.h"
#include "vbj_runs.h"

/* Seeds at the atom centres, fitted into an [n]^3 grid. */
static int protein_seeds(vb_ctx *ctx, const vbj_seed_source *src, uint32_t n, double margin,
                         vbj_seeds *s)
{
    const vb_sphere_set *set = src->spheres;
    vbj_grid_fit fit;
    int rc = vbj_fit_grid(ctx, set->x, set->y, set->z, set->n, n, margin, &fit);
    if (!rc)
        rc = vbj_seeds_from_world(ctx, &fit, set->x, set->y, set->z, set->n, s);
    if (!rc)
        vb_info(ctx, "protein %s: %zu atoms, pitch %.4f A, origin (%.3f, %.3f, %.3f)",
                src->spheres_name ? src->spheres_name : "", set->n, fit.pitch, fit.origin[0],
                fit.origin[1], fit.origin[2]);
    return rc;
}

static int points_seeds(vb_ctx *ctx, const vbj_seed_source *src, int dim, uint32_t n,
                        vbj_seeds *s)
{
    int rc = vbj_seeds_alloc(ctx, dim, n, src->npoints, s);
    for (size_t i = 0; rc == VB_OK && i < src->npoints; i++) {
        const double *p = src->points + (size_t)dim * i;
        rc = vbj_seed_set(ctx, s, i, p[0], p[1], dim == 3 ? p[2] : 0.0);
    }
    if (rc != VB_OK)
        vbj_seeds_free(s);
    return rc;
}

int vbj_seeds_make(vb_ctx *ctx, const vbj_setup *setup, const vbj_seed_source *src,
                   vbj_seeds *out, char *source, size_t len)
{
    memset(out, 0, sizeof *out);
    uint32_t n = (uint32_t)setup->n;
    int dim = (int)setup->dim;
    if (src->spheres && dim != 3)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "seeds at atom centres need dim 3");
    if (src->spheres) {
        snprintf(source, len, "protein %s", src->spheres_name ? src->spheres_name : "");
        return protein_seeds(ctx, src, n, setup->margin, out);
    }
    if (src->points) {
        snprintf(source, len, "points");
        return points_seeds(ctx, src, dim, n, out);
    }
    if (src->path) {
        snprintf(source, len, "file %s", src->path);
        return vbj_seeds_read(ctx, src->path, dim, n, out);
    }
    snprintf(source, len, "%s, rng %llu", vbj_distribution_name(src->dist),
             (unsigned long long)setup->rng);
    return vbj_seeds_generate(ctx, dim, n, (size_t)setup->k, src->dist, setup->rng, out);
}

int vbj_variants_parse(vb_ctx *ctx, const char *s, vbj_variant *v, int *nv)
{
    *nv = 0;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", s);
    char *save = NULL;
    for (char *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        int all = strcmp(tok, "all") == 0;
        int need = all ? VBJ_FACET + 2 : 1;
        if (*nv + need > VBJ_MAX_VARIANTS)
            return vb_error(ctx, VB_EMISUSE, NULL, 0, "too many variants");
        if (all) {
            for (int i = 0; i <= VBJ_FACET; i++)
                v[(*nv)++] = (vbj_variant)i;
            v[(*nv)++] = VBJ_EXACT;
            continue;
        }
        int rc = vbj_variant_parse(ctx, tok, &v[*nv]);
        if (rc)
            return rc;
        (*nv)++;
    }
    return *nv ? VB_OK : vb_error(ctx, VB_EMISUSE, NULL, 0, "no variant given");
}

/* One variant: an untimed run first when repeated (it allocates the device
 * buffers), then `repeat` timed runs; the last one's result is kept. */
static int run_one(vb_ctx *ctx, vbj_backend *e, const vbj_seeds *s, const vbj_options *o,
                   int repeat, vbj_figures *x)
{
    double sum = 0, mn = 0, gpu = 0;
    int rc = VB_OK;
    if (repeat > 1 && !(rc = vbj_run(ctx, e, s, o, &x->r)))
        vbj_result_free(&x->r);
    for (int t = 0; !rc && t < repeat; t++) {
        vbj_result_free(&x->r);
        rc = vbj_run(ctx, e, s, o, &x->r);
        sum += x->r.ms_kernel;
        gpu += x->r.ms_gpu;
        mn = t == 0 || x->r.ms_kernel < mn ? x->r.ms_kernel : mn;
    }
    x->mean_ms = sum / repeat;
    x->mean_gpu_ms = gpu / repeat;
    x->min_ms = mn;
    return rc;
}

int vbj_runs_run(vb_ctx *ctx, vbj_backend *e, const vbj_seeds *s, const vbj_setup *setup,
                 const vbj_variant *v, int nv, int check, vbj_runs *out)
{
    memset(out, 0, sizeof *out);
    out->repeat = (int)setup->repeat;
    out->exact_ms = -1;
    if (nv < 1 || nv > VBJ_MAX_VARIANTS)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "1 to %d variants, not %d", VBJ_MAX_VARIANTS,
                        nv);
    uint32_t *exact = NULL;
    int rc = VB_OK;
    if (check) {
        exact = malloc((size_t)s->n * s->n * (s->dim == 3 ? s->n : 1) * sizeof *exact);
        if (!exact)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "exact labels: out of memory");
        else {
            double t0 = vb_now();
            rc = vbj_exact(ctx, e, s, exact);
            out->exact_ms = (vb_now() - t0) * 1e3;
        }
    }
    int warned_collision = 0, warned_m = 0;
    for (int i = 0; !rc && i < nv; i++) {
        vbj_figures *x = &out->run[i];
        x->v = v[i];
        out->n = i + 1;
        vbj_options o = {x->v, (uint32_t)setup->m, VBJ_WANT_LABELS,
                         (uint32_t)setup->fuse_cells};
        if ((rc = run_one(ctx, e, s, &o, out->repeat, x)) != VB_OK)
            break;
        if (x->r.counts.collisions && !warned_collision) {
            vb_warn(ctx, VB_W_JFA_SEEDS_LOST, NULL, 0,
                    "%u seed(s) share their start pixel with a nearer seed and cannot own "
                    "any pixel",
                    x->r.counts.collisions);
            warned_collision = 1;
        }
        if ((x->v == VBJ_FACET || x->v == VBJ_FACET_FULL) && x->r.counts.m == s->n &&
            s->n > 1 && !warned_m) {
            vb_warn(ctx, VB_W_FACET_START_FINE, NULL, 0,
                    "Facet-JFA starts at m = n = %u (seeds too close): it does the work of "
                    "JFA and more",
                    s->n);
            warned_m = 1;
        }
        if (exact) {
            rc = vbj_compare(ctx, s, x->r.labels, exact, &x->m);
            x->checked = 1;
        }
    }
    snprintf(out->device, sizeof out->device, "%s", e->device);
    free(exact);
    return rc;
}

void vbj_runs_free(vbj_runs *r)
{
    for (int i = 0; i < VBJ_MAX_VARIANTS; i++)
        vbj_result_free(&r->run[i].r);
}

static void write_json(FILE *f, const vbj_runs *R, const vbj_seeds *s, const char *source)
{
    fprintf(f, "{\"device\": ");
    vb_json_write_string(f, R->device);
    fprintf(f, ", \"dim\": %d, \"n\": %u, \"seeds\": %zu, \"source\": ", s->dim, s->n, s->k);
    vb_json_write_string(f, source);
    fprintf(f, ", \"repeat\": %d", R->repeat);
    if (R->exact_ms >= 0)
        fprintf(f, ", \"exact_ms\": %.4f", R->exact_ms);
    fprintf(f, ",\n \"runs\": [");
    for (int i = 0; i < R->n; i++) {
        const vbj_figures *x = &R->run[i];
        const vbj_counts *c = &x->r.counts;
        fprintf(f,
                "%s\n  {\"variant\": \"%s\", \"time_ms\": %.4f, \"time_ms_min\": %.4f, "
                "\"gpu_ms\": %.4f, \"fill_ms\": %.4f, \"prep_transfer_ms\": %.4f, \"prep_ms\": %.4f, "
                "\"steps\": %u, "
                "\"pixels_processed\": %llu, \"threads\": %llu, \"m\": %u, \"boundary\": %llu, "
                "\"collisions\": %u",
                i ? "," : "", vbj_variant_name(x->v), x->mean_ms, x->min_ms, x->mean_gpu_ms,
                x->r.ms_fill, x->r.ms_transfer, x->r.ms_prep, c->steps,
                (unsigned long long)c->step_pixels, (unsigned long long)c->threads, c->m,
                (unsigned long long)c->boundary, c->collisions);
        if (VBJ_IS_EXACT(x->v))
            fprintf(f,
                    ", \"tiles\": %llu, \"tiles_uniform\": %llu, \"candidates\": %llu, "
                    "\"survivors\": %llu, \"evals\": %llu, \"exact_voxels\": %llu, "
                    "\"tiles_chunked\": %llu, \"visited\": %llu",
                    (unsigned long long)c->tiles, (unsigned long long)c->tiles_uniform,
                    (unsigned long long)c->candidates, (unsigned long long)c->survivors,
                    (unsigned long long)c->evals, (unsigned long long)c->exact_voxels,
                    (unsigned long long)c->tiles_chunked, (unsigned long long)c->visited);
        if (x->checked)
            fprintf(f,
                    ", \"wrong\": %zu, \"differ\": %zu, \"wrong_rate\": %.8g, \"max_err\": %.6g, "
                    "\"mean_err\": %.6g, \"boundary_exact\": %zu, \"boundary_found\": %zu, "
                    "\"boundary_missed\": %zu, \"boundary_extra\": %zu",
                    x->m.wrong, x->m.differ, x->m.wrong_rate, x->m.max_err, x->m.mean_err,
                    x->m.boundary_exact, x->m.boundary_found, x->m.boundary_missed,
                    x->m.boundary_extra);
        fprintf(f, "}");
    }
    fprintf(f, "\n]}\n");
}

static void write_text(FILE *f, const vbj_runs *R, const vbj_seeds *s, const char *source)
{
    fprintf(f, "# device: %s\n# grid: %u^%d, %zu seeds (%s)\n", R->device, s->n, s->dim, s->k,
            source);
    fprintf(f, "%-14s %10s %10s %14s %6s %12s %12s %12s %10s\n", "variant", "ms", "ms_min",
            "pixels", "m", "boundary", "wrong", "wrong_rate", "max_err");
    for (int i = 0; i < R->n; i++) {
        const vbj_figures *x = &R->run[i];
        fprintf(f, "%-14s %10.3f %10.3f %14llu %6u %12llu", vbj_variant_name(x->v), x->mean_ms,
                x->min_ms, (unsigned long long)x->r.counts.step_pixels, x->r.counts.m,
                (unsigned long long)x->r.counts.boundary);
        if (x->checked)
            fprintf(f, " %12zu %12.3e %10.4f\n", x->m.wrong, x->m.wrong_rate, x->m.max_err);
        else
            fprintf(f, " %12s %12s %10s\n", "-", "-", "-");
    }
}

void vbj_runs_write(FILE *f, const vbj_runs *r, const vbj_seeds *s, const char *source,
                    int json)
{
    if (json)
        write_json(f, r, s, source);
    else
        write_text(f, r, s, source);
}

/* A bright, well-spread colour per label (integer hash). */
static void colour(uint32_t label, uint8_t out[3])
{
    uint32_t h = label * 0x9e3779b1u;
    h ^= h >> 15;
    h *= 0x85ebca77u;
    h ^= h >> 13;
    for (int c = 0; c < 3; c++)
        out[c] = (uint8_t)(64 + ((h >> (8 * c)) & 0xff) * 191 / 255);
}

/* One z-slice into rgb (n x n, y up): boundary pixels (a neighbour in the
 * slice, or across z in 3D, has another label) black. */
static void render_slice(int dim, uint32_t n, const uint32_t *labels, uint32_t z, uint8_t *rgb,
                         size_t row_stride)
{
    const uint32_t *sl = labels + (size_t)z * n * n;
    int rz = dim == 3 ? 1 : 0;
    for (uint32_t y = 0; y < n; y++)
        for (uint32_t x = 0; x < n; x++) {
            uint32_t me = sl[(size_t)y * n + x];
            int edge = 0;
            for (int dz = -rz; dz <= rz && !edge; dz++)
                for (int dy = -1; dy <= 1 && !edge; dy++)
                    for (int dx = -1; dx <= 1 && !edge; dx++) {
                        int64_t xx = (int64_t)x + dx, yy = (int64_t)y + dy, zz = (int64_t)z + dz;
                        if (xx < 0 || yy < 0 || zz < 0 || xx >= n || yy >= n ||
                            zz >= (dim == 3 ? (int64_t)n : 1))
                            continue;
                        edge = labels[((size_t)zz * n + (size_t)yy) * n + (size_t)xx] != me;
                    }
            /* Image rows run top-down; grid y runs up. */
            uint8_t *px = rgb + (size_t)(n - 1 - y) * row_stride + (size_t)x * 3;
            if (edge)
                px[0] = px[1] = px[2] = 0;
            else
                colour(me, px);
        }
}

int vbj_picture(vb_ctx *ctx, const vbj_seeds *s, const uint32_t *labels, const vbj_setup *setup,
                uint8_t **rgb, uint32_t *w)
{
    uint32_t n = s->n;
    uint32_t ns = s->dim == 3 && setup->nslices ? setup->nslices : 1;
    *w = n * ns;
    *rgb = malloc((size_t)*w * n * 3);
    if (!*rgb)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "picture: out of memory");
    for (uint32_t i = 0; i < ns; i++) {
        uint32_t z = s->dim != 3 ? 0 : setup->nslices ? (uint32_t)setup->slice[i] : n / 2;
        render_slice(s->dim, n, labels, z, *rgb + (size_t)i * n * 3, (size_t)*w * 3);
    }
    return VB_OK;
}
