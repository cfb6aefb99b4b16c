/* The certification filter's input and its plain-C twin (vb_cert_filter.h);
 * the judge itself is vbd_cert_shared.h, shared with gpu/cert_filter.cl. */
#include "vb_cert_filter.h"

#include <limits.h>
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "vb_parallel.h"

int vb_cert_filter_mode(void)
{
    const char *e = getenv("VORBALL_DEVICE_CERT");
    return e && strcmp(e, "0") == 0 ? 0 : e && strcmp(e, "1") == 0 ? 1 : -1;
}

void vb_cert_filter_free(vb_cert_filter *f)
{
    free(f->z);
    free(f->cell_start);
    free(f->cell_ids);
    free(f->cell_z);
    free(f->cell_d);
    memset(f, 0, sizeof *f);
}

/* mant 10^p (p >= 0) when it stays below 2^61 in magnitude: 1, else 0. */
static int scaled(int64_t mant, int p, int64_t *out)
{
    int64_t v = mant;
    for (int k = 0; k < p; k++)
        if (__builtin_mul_overflow(v, (int64_t)10, &v))
            return 0;
    if (v >= ((int64_t)1 << 61) || v <= -((int64_t)1 << 61))
        return 0;
    *out = v;
    return 1;
}

/* The scaled input; 0 when it does not fit. */
static int scale_input(const vb_sphere_set *set, int64_t *z)
{
    if (!set->ex || !set->ey || !set->ez || !set->er)
        return 0;
    const vb_decimal *col[4] = {set->ex, set->ey, set->ez, set->er};
    int32_t e = 0;
    for (size_t i = 0; i < set->n; i++)
        for (int k = 0; k < 4; k++)
            if (-col[k][i].exp10 > e)
                e = -col[k][i].exp10;
    if (e > 40)
        return 0;
    for (size_t i = 0; i < set->n; i++)
        for (int k = 0; k < 4; k++) {
            int64_t p = (int64_t)col[k][i].exp10 + e;
            if (p > 40 || !scaled(col[k][i].mant, (int)p, &z[4 * i + k]))
                return 0;
        }
    return 1;
}

/* Cells per axis for side 1 / inv over [o, hi]. */
static uint32_t axis_cells(double o, double hi, double inv)
{
    double c = floor((hi - o) * inv) + 1.0;
    return c > 1e9 ? 1000000000u : (uint32_t)c;
}

/* The twin's copy of cell_z as doubles by column (f->cell_d), where every
 * |z| < 2^52: each value is then a double, and so is each difference
 * z_j - z_a (below 2^53), which the twin subtracts in double with the
 * result vbd_scan_fast converts. Left NULL otherwise (the shared scan
 * runs). 0, or -1 when out of memory. */
static int host_columns(vb_cert_filter *f)
{
    size_t n = f->n;
    const int64_t lim = (int64_t)1 << 52;
    for (size_t i = 0; i < 4 * n; i++)
        if (f->z[i] >= lim || f->z[i] <= -lim)
            return 0;
    f->cell_d = calloc(4 * n + 4, sizeof *f->cell_d); /* 4 more: cert_scan.c's lanes */
    if (!f->cell_d)
        return -1;
    for (size_t t = 0; t < n; t++)
        for (int k = 0; k < 4; k++)
            f->cell_d[k * n + t] = (double)f->cell_z[4 * t + k];
    return 0;
}

/* The grid: side about twice the mean radius, widened until there are at
 * most 32 cells a sphere (and fewer than 2^31: 32-bit keys). Keys by
 * vbd_cell, the kernel's own function. */
static int build_grid(vb_cert_filter *f)
{
    size_t n = f->n;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    double rsum = 0.0;
    int64_t rmax = INT64_MIN;
    for (size_t i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++) {
            double x = (double)f->z[4 * i + k];
            lo[k] = x < lo[k] ? x : lo[k];
            hi[k] = x > hi[k] ? x : hi[k];
        }
        rsum += (double)f->z[4 * i + 3];
        if (f->z[4 * i + 3] > rmax)
            rmax = f->z[4 * i + 3];
    }
    double ext = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
    double h = fmax(2.0 * rsum / (double)n, fmax(ext * 0x1p-20, 1.0));
    uint32_t nc[3];
    for (;;) {
        double inv = 1.0 / h;
        uint64_t cells = 1;
        for (int k = 0; k < 3; k++) {
            nc[k] = axis_cells(lo[k], hi[k], inv);
            cells *= nc[k];
        }
        if (cells <= 32 * (uint64_t)n + 64 && cells < ((uint64_t)1 << 31)) {
            f->ncells = (size_t)cells;
            f->g.inv = inv;
            break;
        }
        h *= 1.5;
    }
    f->g.ox = lo[0];
    f->g.oy = lo[1];
    f->g.oz = lo[2];
    f->g.nx = nc[0];
    f->g.ny = nc[1];
    f->g.nz = nc[2];
    f->g.rmax = rmax;
    f->cell_start = calloc(f->ncells + 1, sizeof *f->cell_start);
    f->cell_ids = calloc(n + 4, sizeof *f->cell_ids); /* 4 more: cert_scan.c's lanes */
    f->cell_z = malloc(4 * n * sizeof *f->cell_z);
    uint32_t *key = malloc(n * sizeof *key);
    if (!f->cell_start || !f->cell_ids || !f->cell_z || !key) {
        free(key);
        return -1;
    }
    for (size_t i = 0; i < n; i++) {
        const int64_t *zi = &f->z[4 * i];
        uint32_t cx = vbd_cell((double)zi[0], f->g.ox, f->g.inv, f->g.nx);
        uint32_t cy = vbd_cell((double)zi[1], f->g.oy, f->g.inv, f->g.ny);
        uint32_t cz = vbd_cell((double)zi[2], f->g.oz, f->g.inv, f->g.nz);
        key[i] = (uint32_t)(((uint64_t)cz * f->g.ny + cy) * f->g.nx + cx);
        f->cell_start[key[i] + 1]++;
    }
    for (size_t c = 0; c < f->ncells; c++)
        f->cell_start[c + 1] += f->cell_start[c];
    uint32_t *pos = malloc(f->ncells * sizeof *pos);
    if (!pos) {
        free(key);
        return -1;
    }
    memcpy(pos, f->cell_start, f->ncells * sizeof *pos);
    for (size_t i = 0; i < n; i++) {
        uint32_t t = pos[key[i]]++;
        f->cell_ids[t] = (uint32_t)i;
        memcpy(&f->cell_z[4 * (size_t)t], &f->z[4 * i], 4 * sizeof *f->z);
    }
    free(pos);
    free(key);
    return host_columns(f);
}

int vb_cert_filter_build(vb_ctx *ctx, const vb_sphere_set *set, vb_cert_filter *f)
{
    static atomic_uint_fast64_t serials;
    memset(f, 0, sizeof *f);
    f->serial = atomic_fetch_add(&serials, 1) + 1;
    f->n = set->n;
    if (set->n == 0 || set->n > (size_t)UINT32_MAX - 1)
        return VB_OK;
    f->z = malloc(4 * set->n * sizeof *f->z);
    if (!f->z) {
        vb_cert_filter_free(f);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (certification filter)");
    }
    if (!scale_input(set, f->z)) {
        free(f->z);
        f->z = NULL;
        return VB_OK;
    }
    if (build_grid(f) != 0) {
        vb_cert_filter_free(f);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (certification filter)");
    }
    f->ok = 1;
    return VB_OK;
}

#define JUDGE_CHUNK 512

typedef struct judge_job {
    const vb_cert_filter *f;
    const uint32_t (*q)[4];
    size_t n;
    uint8_t *verdict;
} judge_job;

static void judge_chunk(void *arg, size_t c, int tid)
{
    (void)tid;
    const judge_job *j = arg;
    const vb_cert_filter *f = j->f;
    size_t k0 = c * JUDGE_CHUNK, k1 = (c + 1) * JUDGE_CHUNK < j->n ? (c + 1) * JUDGE_CHUNK : j->n;
    vb_cert_judge_run_pick()(f, j->q + k0, k1 - k0, j->verdict + k0);
}

void vb_cert_filter_judge(const vb_cert_filter *f, const uint32_t (*q)[4], size_t n,
                          uint8_t *verdict, unsigned threads)
{
    if (!f->ok) {
        memset(verdict, VBD_OPEN, n);
        return;
    }
    judge_job j = {f, q, n, verdict};
    size_t chunks = (n + JUDGE_CHUNK - 1) / JUDGE_CHUNK;
    int nt = vb_threads(threads);
    if ((size_t)nt > chunks)
        nt = chunks ? (int)chunks : 1;
    vb_parallel_for(judge_chunk, &j, chunks, nt);
}
