/* Seeds of the discrete Voronoi diagram: allocation, fixed-point conversion,
 * generators (uniform, clustered, shell), a text reader and the grid fit for
 * atom centres. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vbj_jfa.h"

static int is_pow2(uint32_t n) { return n >= 2 && (n & (n - 1)) == 0; }

void vbj_setup_defaults(vbj_setup *s)
{
    memset(s, 0, sizeof *s);
    s->dim = 2;
    s->n = 512;
    s->k = 100;
    s->margin = 2.0;
    s->repeat = 1;
    s->rng = 1;
}

/* Nonzero when a slice is refused: too many, or one not below n. */
static int bad_slices(const vbj_setup *s)
{
    if (s->nslices > VBJ_MAX_SLICES)
        return 1;
    for (uint32_t i = 0; i < s->nslices; i++)
        if (s->slice[i] >= s->n)
            return 1;
    return 0;
}

int vbj_setup_check(vb_ctx *ctx, const vbj_setup *s)
{
    const char *bad = s->dim != 2 && s->dim != 3    ? "--dim must be 2 or 3"
                      : s->n > VBJ_MAX_N            ? "bad --size"
                      : s->k == 0                   ? "bad --seeds"
                      : !(s->margin >= 0.0)         ? "bad --margin"
                      : s->m > VBJ_MAX_N            ? "bad -m"
                      : s->fuse_cells > UINT32_MAX  ? "bad --fuse-cells"
                      : s->repeat == 0 || s->repeat > 100000 ? "bad --repeat"
                      : bad_slices(s)               ? "bad --slice"
                                                    : NULL;
    return bad ? vb_error(ctx, VB_EMISUSE, NULL, 0, "%s", bad) : VB_OK;
}

int vbj_seeds_alloc(vb_ctx *ctx, int dim, uint32_t n, size_t k, vbj_seeds *out)
{
    memset(out, 0, sizeof *out);
    if (dim != 2 && dim != 3)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "grid dimension must be 2 or 3, not %d", dim);
    if (!is_pow2(n) || n > VBJ_MAX_N)
        return vb_error(ctx, VB_EMISUSE, NULL, 0,
                        "grid size must be a power of two in 2..%u, not %u", VBJ_MAX_N, n);
    /* Labels and offsets are 32-bit on the device. */
    if ((double)n * n * (dim == 3 ? n : 1) > 2147483648.0)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "grid of %u^%d pixels is too large", n, dim);
    if (k == 0)
        return vb_error(ctx, VB_EINPUT_EMPTY, NULL, 0, "no seeds");
    if (k > VBJ_MAX_SEEDS)
        return vb_error(ctx, VB_EINPUT_TOOLARGE, NULL, 0, "%zu seeds: at most %u", k,
                        VBJ_MAX_SEEDS);
    out->x = calloc(k, sizeof *out->x);
    out->y = calloc(k, sizeof *out->y);
    out->z = calloc(k, sizeof *out->z);
    if (!out->x || !out->y || !out->z) {
        vbj_seeds_free(out);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "seeds: out of memory");
    }
    out->dim = dim;
    out->n = n;
    out->k = k;
    return VB_OK;
}

void vbj_seeds_free(vbj_seeds *s)
{
    if (!s)
        return;
    free(s->x);
    free(s->y);
    free(s->z);
    memset(s, 0, sizeof *s);
}

static int to_fixed(vb_ctx *ctx, uint32_t n, double g, int32_t *out)
{
    if (!isfinite(g) || g < -0.5 || g >= (double)n - 0.5)
        return vb_error(ctx, VB_EINPUT, NULL, 0,
                        "seed coordinate %.9g outside the grid [-0.5, %u.5)", g, n - 1);
    double f = nearbyint(g * VBJ_FIX_ONE);
    /* Rounding may reach the open upper end. */
    double hi = (double)n * VBJ_FIX_ONE - VBJ_FIX_HALF - 1;
    *out = (int32_t)(f > hi ? hi : f);
    return VB_OK;
}

int vbj_seed_set(vb_ctx *ctx, vbj_seeds *s, size_t i, double gx, double gy, double gz)
{
    int rc;
    if ((rc = to_fixed(ctx, s->n, gx, &s->x[i])) || (rc = to_fixed(ctx, s->n, gy, &s->y[i])))
        return rc;
    if (s->dim == 3)
        return to_fixed(ctx, s->n, gz, &s->z[i]);
    s->z[i] = 0;
    return VB_OK;
}

static const char *dist_names[] = {"uniform", "clustered", "shell"};

int vbj_distribution_parse(vb_ctx *ctx, const char *s, vbj_distribution *out)
{
    for (int i = 0; i < 3; i++)
        if (strcmp(s, dist_names[i]) == 0) {
            *out = (vbj_distribution)i;
            return VB_OK;
        }
    return vb_error(ctx, VB_EMISUSE, NULL, 0,
                    "unknown seed distribution '%s' (uniform|clustered|shell)", s);
}

const char *vbj_distribution_name(vbj_distribution d)
{
    return (unsigned)d < 3 ? dist_names[d] : "?";
}

/* splitmix64: small, seedable, identical on every platform. */
static uint64_t next_u64(uint64_t *st)
{
    uint64_t z = (*st += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1). */
static double next_unit(uint64_t *st) { return (double)(next_u64(st) >> 11) * 0x1p-53; }

static double next_gauss(uint64_t *st)
{
    double u = next_unit(st), v = next_unit(st);
    return sqrt(-2.0 * log(1.0 - u)) * cos(6.283185307179586 * v);
}

/* Keeps a coordinate inside the open grid box. */
static double clampg(double g, uint32_t n)
{
    double lo = -0.5, hi = (double)n - 0.5 - 1.0 / VBJ_FIX_ONE;
    return g < lo ? lo : g > hi ? hi : g;
}

int vbj_seeds_generate(vb_ctx *ctx, int dim, uint32_t n, size_t k, vbj_distribution dist,
                       uint64_t seed, vbj_seeds *out)
{
    int rc = vbj_seeds_alloc(ctx, dim, n, k, out);
    if (rc)
        return rc;
    uint64_t st = seed;
    double span = (double)n; /* coordinates in [-0.5, n - 0.5) */
    size_t nclusters = (size_t)ceil(sqrt((double)k));
    double centres[3] = {0, 0, 0};
    for (size_t i = 0; i < k; i++) {
        double g[3] = {0, 0, 0};
        switch (dist) {
        case VBJ_DIST_UNIFORM:
            for (int a = 0; a < dim; a++)
                g[a] = next_unit(&st) * span - 0.5;
            break;
        case VBJ_DIST_CLUSTERED:
            /* Cluster j's centre comes from its own stream so clusters do not
             * depend on k's order of draws. */
            {
                uint64_t cs = seed ^ (0xa5a5a5a5ull + (i % nclusters) * 0x9e3779b97f4a7c15ull);
                for (int a = 0; a < dim; a++)
                    centres[a] = (0.1 + 0.8 * next_unit(&cs)) * span - 0.5;
                double sigma = 0.03 * span;
                for (int a = 0; a < dim; a++)
                    g[a] = clampg(centres[a] + sigma * next_gauss(&st), n);
            }
            break;
        case VBJ_DIST_SHELL: {
            double v[3], len;
            do {
                for (int a = 0; a < 3; a++)
                    v[a] = a < dim ? next_gauss(&st) : 0.0;
                len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            } while (len < 1e-9);
            for (int a = 0; a < dim; a++)
                g[a] = clampg(0.5 * (span - 1.0) + 0.4 * span * v[a] / len, n);
            break;
        }
        default:
            vbj_seeds_free(out);
            return vb_error(ctx, VB_EMISUSE, NULL, 0, "unknown seed distribution %d", (int)dist);
        }
        if ((rc = vbj_seed_set(ctx, out, i, g[0], g[1], g[2]))) {
            vbj_seeds_free(out);
            return rc;
        }
    }
    return VB_OK;
}

int vbj_seeds_read(vb_ctx *ctx, const char *path, int dim, uint32_t n, vbj_seeds *out)
{
    memset(out, 0, sizeof *out);
    FILE *f = strcmp(path, "-") == 0 ? stdin : fopen(path, "r");
    if (!f)
        return vb_error(ctx, VB_EIO, path, 0, "cannot open: %s", strerror(errno));
    size_t cap = 0, k = 0;
    double *pts = NULL;
    char *line = NULL;
    size_t lcap = 0;
    long lineno = 0;
    int rc = VB_OK;
    while (getline(&line, &lcap, f) >= 0) {
        lineno++;
        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        char *p = line, *end;
        double v[3] = {0, 0, 0};
        int got = 0;
        for (;;) {
            while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n')
                p++;
            if (!*p)
                break;
            if (got == dim) {
                rc = vb_error(ctx, VB_EINPUT_MALFORMED, path, lineno,
                              "expected %d coordinates per seed", dim);
                goto done;
            }
            v[got] = strtod(p, &end);
            if (end == p) {
                rc = vb_error(ctx, VB_EINPUT_MALFORMED, path, lineno, "not a number: '%.20s'", p);
                goto done;
            }
            if (!isfinite(v[got])) {
                rc = vb_error(ctx, VB_EINPUT_NONFINITE, path, lineno, "coordinate is not finite");
                goto done;
            }
            got++;
            p = end;
        }
        if (got == 0)
            continue;
        if (got != dim) {
            rc = vb_error(ctx, VB_EINPUT_MALFORMED, path, lineno,
                          "expected %d coordinates per seed, found %d", dim, got);
            goto done;
        }
        pts = vb_array_grow(pts, &cap, k + 1, 3 * sizeof *pts, 256);
        if (cap < k + 1) {
            rc = vb_error(ctx, VB_ENOMEM, path, lineno, "out of memory");
            goto done;
        }
        memcpy(pts + 3 * k, v, sizeof v);
        k++;
    }
    if (ferror(f)) {
        rc = vb_error(ctx, VB_EIO, path, 0, "read error");
        goto done;
    }
    if (k == 0) {
        rc = vb_error(ctx, VB_EINPUT_EMPTY, path, 0, "no seeds");
        goto done;
    }
    if ((rc = vbj_seeds_alloc(ctx, dim, n, k, out)))
        goto done;
    for (size_t i = 0; i < k && !rc; i++)
        if ((rc = vbj_seed_set(ctx, out, i, pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]))) {
            char msg[256];
            snprintf(msg, sizeof msg, "%s", vb_errmsg(ctx));
            vb_error(ctx, rc, path, 0, "seed %zu: %s", i + 1, msg);
        }
    if (rc)
        vbj_seeds_free(out);
done:
    free(line);
    free(pts);
    if (f != stdin)
        fclose(f);
    return rc;
}

int vbj_fit_grid(vb_ctx *ctx, const double *x, const double *y, const double *z, size_t k,
                 uint32_t n, double margin, vbj_grid_fit *out)
{
    if (k == 0)
        return vb_error(ctx, VB_EINPUT_EMPTY, NULL, 0, "no points to fit a grid to");
    if (!is_pow2(n) || n > VBJ_MAX_N || !(margin >= 0))
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "grid fit: bad size %u or margin", n);
    const double *c[3] = {x, y, z};
    double lo[3], hi[3], ext = 0;
    for (int a = 0; a < 3; a++) {
        lo[a] = hi[a] = c[a][0];
        for (size_t i = 1; i < k; i++) {
            lo[a] = c[a][i] < lo[a] ? c[a][i] : lo[a];
            hi[a] = c[a][i] > hi[a] ? c[a][i] : hi[a];
        }
        if (!isfinite(lo[a]) || !isfinite(hi[a]))
            return vb_error(ctx, VB_EINPUT_NONFINITE, NULL, 0, "point coordinate not finite");
        double e = hi[a] - lo[a] + 2 * margin;
        ext = e > ext ? e : ext;
    }
    if (!(ext > 0))
        ext = 1.0;
    out->n = n;
    /* n - 1 pixel steps span the pixel centres; a little slack keeps points
     * rounded to 1/65536 px inside. */
    out->pitch = ext / ((double)n - 1.0) * (1.0 + 1e-9);
    for (int a = 0; a < 3; a++)
        out->origin[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * ((double)n - 1.0) * out->pitch;
    return VB_OK;
}

int vbj_seeds_from_world(vb_ctx *ctx, const vbj_grid_fit *fit, const double *x, const double *y,
                         const double *z, size_t k, vbj_seeds *out)
{
    int rc = vbj_seeds_alloc(ctx, 3, fit->n, k, out);
    if (rc)
        return rc;
    for (size_t i = 0; i < k; i++) {
        rc = vbj_seed_set(ctx, out, i, (x[i] - fit->origin[0]) / fit->pitch,
                          (y[i] - fit->origin[1]) / fit->pitch, (z[i] - fit->origin[2]) / fit->pitch);
        if (rc) {
            char msg[256];
            snprintf(msg, sizeof msg, "%s", vb_errmsg(ctx));
            vbj_seeds_free(out);
            return vb_error(ctx, rc, NULL, 0, "point %zu: %s", i, msg);
        }
    }
    return VB_OK;
}
