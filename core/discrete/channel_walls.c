/* The pore verdict's rasters (vbc_walls.h): the filter's input from a
 * frame's cell list and a pore, its proven bound, and the plain-C twin of
 * gpu/channel_walls.cl. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "channel_walls_math.h"
#include "vb_parallel.h"
#include "vbc_walls.h"

/* The kernel reads the cell list's start as 64-bit words. */
_Static_assert(sizeof(size_t) == sizeof(uint64_t), "size_t start read as uint64_t");

int vbc_plane_raster_half(double r)
{
    double rr = r > 0.0 ? r : 0.0;
    double reach = fmin(2.0 * rr + VBC_WALL_REACH, VBC_WALL_MAX_REACH);
    return (int)ceil(reach / VBC_WALL_PIXEL);
}

int vbc_walls_window(double r)
{
    double rr = r > 0.0 ? r : 0.0;
    int m = (int)ceil((rr + VBC_WALLS_WINDOW) / VBC_WALL_PIXEL), n = vbc_plane_raster_half(r);
    return m < n ? m : n;
}

/* The error of the filter's t = |q - c|^2 - R2 (channel_walls_math.h) for
 * an atom it tests (|q - c|^2 at most far2 = F^2 in float), against the
 * exact value for the host's double pixel q_h = p + x a + y b. u = 2^-24;
 * L bounds every coordinate relative to the corner (atoms and centres), X
 * the pixel offsets |x|, |y|, H the absolute coordinates (the host's own
 * rounding, 2^-53 a step, is covered by 1e-14 H).
 *   x a_f + y b_f: a_f, b_f err by u, each product rounds (u), the sum
 *     rounds: within 7 u X of x a + y b;
 *   q = P_f + that: P_f errs by u L, the sum rounds by u (L + 2 X);
 *   c_f errs by u L; dx = q - c_f rounds by u F: per component
 *     e1 = 3 u L + 9 u X + u F + 1e-14 H (generously);
 *   |sum dx_f^2 - sum dx^2| <= sum e1 (2 |dx_f| + e1) <= 2 sqrt(3) F e1
 *     + 3 e1^2, the three products and two sums round by 3 u far2;
 *   R2_f (rounded from double) errs by u far2, t rounds by u far2.
 * The bound is twice their sum plus 1e-9 A^2: a t beyond it holds the
 * host's double test |q_h - c| - r <= probe to the same answer, its own
 * error (1e-14 H) being far below 1e-9 / (2 F). */
static double filter_bound(double L, double X, double H, double F)
{
    const double u = 0x1p-24;
    double e1 = 3.0 * u * L + 9.0 * u * X + u * F + 1e-14 * H;
    double err = 5.0 * u * F * F + 2.0 * sqrt(3.0) * F * e1 + 3.0 * e1 * e1;
    return 2.0 * err + 1e-9;
}

/* A float at least d. */
static float float_up(double d)
{
    float f = (float)d;
    return (double)f >= d ? f : nextafterf(f, INFINITY);
}

void vbc_walls_input_free(vbc_walls_input *in)
{
    free(in->atoms);
    free(in->planes);
    free(in->half);
    free(in->word0);
    memset(in, 0, sizeof *in);
}

int vbc_walls_prep(const vbc_cells *c, const vbc_pore *p, vbc_walls_input *in)
{
    memset(in, 0, sizeof *in);
    const vb_sphere_set *s = vbc_cells_spheres(c);
    double lo[3], cell, rmax, ab[2][3];
    const size_t *start;
    const int32_t *idx;
    vbc_cells_layout(c, lo, &cell, in->dim, &rmax, &start, &idx);
    in->natoms = s->n;
    in->ncells = (size_t)in->dim[0] * (size_t)in->dim[1] * (size_t)in->dim[2];
    in->start = (const uint64_t *)start;
    in->nplanes = p->n;
    in->atoms = malloc((s->n ? s->n : 1) * 4 * sizeof *in->atoms);
    in->planes = malloc((p->n ? p->n : 1) * 4 * sizeof *in->planes);
    in->half = malloc((p->n ? p->n : 1) * sizeof *in->half);
    in->word0 = malloc((p->n + 1) * sizeof *in->word0);
    if (!in->atoms || !in->planes || !in->half || !in->word0) {
        vbc_walls_input_free(in);
        return -1;
    }
    double L = 0.0, H = 0.0;
    for (size_t k = 0; k < s->n; k++) {
        int32_t i = idx[k];
        double x[3] = {s->x[i] - lo[0], s->y[i] - lo[1], s->z[i] - lo[2]};
        double R = s->r[i] + VBC_WALL_PROBE;
        for (int d = 0; d < 3; d++) {
            in->atoms[4 * k + (size_t)d] = (float)x[d];
            L = fmax(L, fabs(x[d]));
            H = fmax(H, fabs(x[d] + lo[d]));
        }
        in->atoms[4 * k + 3] = (float)(R * R);
    }
    int most = 0;
    in->word0[0] = 0;
    for (size_t k = 0; k < p->n; k++) {
        const vbc_pore_point *q = &p->pts[k];
        double at[3] = {q->x, q->y, q->z};
        for (int d = 0; d < 3; d++) {
            in->planes[4 * k + (size_t)d] = (float)(at[d] - lo[d]);
            L = fmax(L, fabs(at[d] - lo[d]));
            H = fmax(H, fabs(at[d]));
        }
        in->planes[4 * k + 3] = 0.0f;
        int n = vbc_walls_window(q->r);
        size_t side = (size_t)(2 * n + 1);
        in->half[k] = n;
        in->word0[k + 1] = in->word0[k] + (side * side + 31) / 32;
        most = n > most ? n : most;
    }
    vbc_plane_basis(p->axis.u, ab[0], ab[1]);
    for (int d = 0; d < 3; d++) {
        in->a[d] = (float)ab[0][d];
        in->b[d] = (float)ab[1][d];
    }
    double X = most * VBC_WALL_PIXEL, F = rmax + VBC_WALL_PROBE + 0.5;
    double bound = filter_bound(L, X, H, F);
    in->pixel = (float)VBC_WALL_PIXEL;
    in->inv_cell = (float)(1.0 / cell);
    /* The cells searched reach past F by far more than the float error of
     * their bounds (e1 above, below 1e-3 A for coordinates below 1e4 A). */
    in->reach = float_up(F + 0.05);
    in->far2 = float_up(F * F);
    in->bound = float_up(bound);
    return 0;
}

/* One plane of the twin (vb_for_fn over the planes). */
typedef struct {
    const vbc_walls_input *in;
    vbc_walls_raster *out;
} twin_job;

static void twin_plane(void *ctx, size_t k, int tid)
{
    (void)tid;
    const twin_job *J = ctx;
    const vbc_walls_input *in = J->in;
    for (size_t w = in->word0[k]; w < in->word0[k + 1]; w++)
        vbc_walls_word(in->atoms, in->start, in->dim, in->inv_cell, in->reach, in->far2, in->bound,
                       &in->planes[4 * k], in->a, in->b, in->pixel, in->half[k],
                       (vb_u32)(w - in->word0[k]), &J->out->blocked[w], &J->out->unsure[w]);
}

int vbc_walls_raster_ref(const vbc_walls_input *in, vbc_walls_raster *out)
{
    twin_job J = {in, out};
    int nt = vb_threads(0);
    if (nt > 1 && in->nplanes > 1)
        vb_parallel_for(twin_plane, &J, in->nplanes, nt);
    else
        for (size_t k = 0; k < in->nplanes; k++)
            twin_plane(&J, k, 0);
    return VB_OK;
}

static int ref_raster(void *user, const vbc_walls_input *in, vbc_walls_raster *out)
{
    (void)user;
    return vbc_walls_raster_ref(in, out);
}

const vbc_walls_engine *vbc_walls_engine_ref(void)
{
    static const vbc_walls_engine ref = {NULL, ref_raster};
    return &ref;
}

int vbc_walls_mode(void)
{
    const char *e = getenv("VORBALL_DEVICE_WALLS");
    if (e && strcmp(e, "1") == 0)
        return 1;
    if (e && strcmp(e, "2") == 0)
        return 2;
    return 0;
}
