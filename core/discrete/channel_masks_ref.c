/* The plain-C reference of the mask stage (Algorithm 2, steps 2-7), built from
 * the same per-voxel functions as gpu/channels.cl. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "channel_math.h"
#include "vb_array.h"
#include "vbc_channel.h"

/* The y and z rays' bounds (vbc_ray_scan's first and last hit) from the
 * atomic mask and the x rays' (atomic_mask's): apart (yf, yl: nx * nz
 * each, at i + nx k; zf, zl: nx * ny each, at i + nx j) and in their
 * places in rb. One pass over the atomic mask in memory order: along y and
 * z the index grows with the pass, so a ray's first hit is the least j (k)
 * of an atomic voxel on it and its last the greatest, taken without
 * branches over each row's span of hits (its x ray's bounds: outside them
 * no voxel of the row is atomic). Only the box bx (i0, i1, j0, j1, k0, k1,
 * half open) is read: no voxel outside it is atomic. */
static void ray_bounds(const uint8_t *am, int nx, int ny, int nz, const int *bx, int *rb,
                       int16_t *restrict yf, int16_t *restrict yl, int16_t *restrict zf,
                       int16_t *restrict zl)
{
    size_t ny2 = (size_t)nx * (size_t)nz, nz2 = (size_t)nx * (size_t)ny;
    for (size_t t = 0; t < ny2; t++) {
        yf[t] = (int16_t)ny;
        yl[t] = -1;
    }
    for (size_t t = 0; t < nz2; t++) {
        zf[t] = (int16_t)nz;
        zl[t] = -1;
    }
    for (int k = bx[4]; k < bx[5]; k++) {
        int16_t *restrict yfk = yf + (size_t)nx * (size_t)k, *restrict ylk = yl + (size_t)nx * (size_t)k;
        int16_t k16 = (int16_t)k, nz16 = (int16_t)nz;
        for (int j = bx[2]; j < bx[3]; j++) {
            const uint8_t *restrict row = am + (size_t)nx * ((size_t)j + (size_t)ny * (size_t)k);
            int f = rb[2 * (j + ny * k)], l = rb[2 * (j + ny * k) + 1];
            int16_t *restrict zfj = zf + (size_t)nx * (size_t)j, *restrict zlj = zl + (size_t)nx * (size_t)j;
            int16_t j16 = (int16_t)j, ny16 = (int16_t)ny;
            /* m: all ones on an atomic voxel, else 0 (vectorised). */
            for (int i = f; i <= l; i++) {
                int16_t m = (int16_t)-(row[i] & VBC_F_ATOMIC);
                int16_t jf = (int16_t)((j16 & m) | (ny16 & ~m)), kf = (int16_t)((k16 & m) | (nz16 & ~m));
                yfk[i] = jf < yfk[i] ? jf : yfk[i];
                ylk[i] = (int16_t)((j16 & m) | (ylk[i] & ~m));
                zfj[i] = kf < zfj[i] ? kf : zfj[i];
                zlj[i] = (int16_t)((k16 & m) | (zlj[i] & ~m));
            }
        }
    }
    int *ry = rb + vbc_rb_y(nx, ny, nz), *rz = rb + vbc_rb_z(nx, ny, nz);
    for (size_t t = 0; t < ny2; t++) {
        ry[2 * t] = yf[t];
        ry[2 * t + 1] = yl[t];
    }
    for (size_t t = 0; t < nz2; t++) {
        rz[2 * t] = zf[t];
        rz[2 * t + 1] = zl[t];
    }
}

/* The voxels of row (j,k) in [i0, i1) whose centres vbc_ball_contains puts
 * in ball p: none (returns 0), or the run lo..hi (returns 1). They are one
 * run: along the row dx = (i + 0.5) - x falls and then grows in magnitude,
 * and each rounded step of the test (the difference, the squares, the
 * sums) keeps that order, so the ball's float test holds on an interval of
 * i. The estimate from the square root is only a start: every end is
 * settled by the test itself, so the run is exactly the voxels the test
 * takes. */
static int ball_row(const float *p, int i0, int i1, int j, int k, int *lo, int *hi)
{
    if (i0 >= i1)
        return 0;
    /* Exact in double (floats, and voxel centres below 2^24): the
     * distances of the float test before its roundings, which move a
     * squared distance by less than 6 units of 2^-24 relative (three
     * nonnegative terms, each rounded at most three times; R^2 once). So
     * a row whose squared distance exceeds R^2 (1 + 1e-5) + 1e-5 holds no
     * voxel of the ball, and a voxel within R^2 (1 - 1e-5) - 1e-5 is in
     * it: the test need not run there. */
    double dy = (double)j + 0.5 - p[1], dz = (double)k + 0.5 - p[2], r2 = (double)p[3] * p[3];
    double yz = dy * dy + dz * dz;
    if (yz > r2 * (1.0 + 1e-5) + 1e-5)
        return 0;
    /* The voxel nearest the centre in the range: the run holds it when the
     * row meets the ball at all. */
    int c = (int)floorf(p[0] - 0.5f);
    c = c < i0 ? i0 : c >= i1 ? i1 - 1 : c;
    double dc = (double)c + 0.5 - p[0];
    if (dc * dc + yz >= r2 * (1.0 - 1e-5) - 1e-5) {
        if (c + 1 < i1 && !vbc_ball_contains(p[0], p[1], p[2], p[3], c, j, k))
            c++;
        if (!vbc_ball_contains(p[0], p[1], p[2], p[3], c, j, k))
            return 0;
    }
    double rem = r2 - dy * dy - dz * dz;
    double w = rem > 0.0 ? sqrt(rem) : 0.0;
    int l = (int)floor(p[0] - 0.5 - w), r = (int)ceil(p[0] - 0.5 + w);
    l = l < i0 ? i0 : l > c ? c : l;
    r = r >= i1 ? i1 - 1 : r < c ? c : r;
    while (l > i0 && vbc_ball_contains(p[0], p[1], p[2], p[3], l - 1, j, k))
        l--;
    while (!vbc_ball_contains(p[0], p[1], p[2], p[3], l, j, k))
        l++;
    while (r + 1 < i1 && vbc_ball_contains(p[0], p[1], p[2], p[3], r + 1, j, k))
        r++;
    while (!vbc_ball_contains(p[0], p[1], p[2], p[3], r, j, k))
        r--;
    *lo = l;
    *hi = r;
    return 1;
}

/* vbc_ball_contains at voxel i of a row whose y and z squares are yy and
 * zz (dy * dy and dz * dz rounded to float, as that function rounds them;
 * contraction is off): the same expression, so the same verdict. */
static inline int row_contains(float ax, float rr, float yy, float zz, int i)
{
    float dx = ((float)i + 0.5f) - ax;
    float d2 = dx * dx + yy;
    d2 = d2 + zz;
    return d2 <= rr;
}

/* The row's run: [*lo, *hi] shrunk to the voxels of the ball in it (the
 * first and the last of them; 0 when none is). The run must contain them
 * all: the row's voxels in the ball form one interval (ball_row), so the
 * first voxel from the left that the test takes is its first, and the same
 * from the right. */
static int row_shrink(float ax, float rr, float yy, float zz, int *lo, int *hi)
{
    int l = *lo, r = *hi;
    while (l <= r && !row_contains(ax, rr, yy, zz, l))
        l++;
    while (r > l && !row_contains(ax, rr, yy, zz, r))
        r--;
    *lo = l;
    *hi = r;
    return l <= r;
}

/* The squares of a row's or plane's offset from the centre c, rounded to
 * float as vbc_ball_contains rounds them. */
static inline float offset_square(int j, float c)
{
    float d = ((float)j + 0.5f) - c;
    return d * d;
}

/* One ball's voxels in flags (the atomic bit), each row's run widening
 * the row's x ray bounds in rb; box (i0, i1, j0, j1, k0, k1, half open)
 * from vbc_box_lo and vbc_box_hi. The rows are nested: the
 * rounded square of an offset grows with its magnitude, and each rounded
 * sum of the test grows with its terms, so a row whose offsets from the
 * centre are no smaller in y and in z than another's holds no voxel that
 * the other does not. Walking out from the row nearest the centre
 * (floor(c) in y and z, clamped to the box: every row on one side of it is
 * farther by at least as much) each row's run is the last row's shrunk by
 * the test at its ends, and the first empty row ends that direction: the
 * same voxels as ball_row on every row of the box, with two tests a row. */
static void ball_mark(const float *p, const int *box, int nx, int ny, uint8_t *flags, int *rb)
{
    int i0 = box[0], i1 = box[1], j0 = box[2], j1 = box[3], k0 = box[4], k1 = box[5];
    float ax = p[0], rr = p[3] * p[3];
    int jc = (int)floorf(p[1]), kc = (int)floorf(p[2]);
    jc = jc < j0 ? j0 : jc >= j1 ? j1 - 1 : jc;
    kc = kc < k0 ? k0 : kc >= k1 ? k1 - 1 : kc;
    int l0, r0;
    if (!ball_row(p, i0, i1, jc, kc, &l0, &r0))
        return; /* the nearest row holds none: no row does */
    float yc = offset_square(jc, p[1]);
    for (int kdir = 1; kdir >= -1; kdir -= 2) {
        /* lk, rk: the centre row's run of the plane nearer the centre. */
        int lk = l0, rk = r0;
        for (int k = kdir > 0 ? kc : kc - 1; k >= k0 && k < k1; k += kdir) {
            float zz = offset_square(k, p[2]);
            if (!row_shrink(ax, rr, yc, zz, &lk, &rk))
                break;
            for (int jdir = 1; jdir >= -1; jdir -= 2) {
                int l = lk, r = rk;
                for (int j = jdir > 0 ? jc : jc - 1; j >= j0 && j < j1; j += jdir) {
                    if (j != jc && !row_shrink(ax, rr, offset_square(j, p[1]), zz, &l, &r))
                        break;
                    memset(flags + (size_t)nx * (j + (size_t)ny * k) + l, VBC_F_ATOMIC,
                           (size_t)(r - l + 1));
                    int *x = rb + 2 * (j + ny * k);
                    x[0] = l < x[0] ? l : x[0];
                    x[1] = r > x[1] ? r : x[1];
                }
            }
        }
    }
}

/* The atomic mask (flags cleared first), the x rays' bounds in rb (the
 * least and greatest voxel of the balls' runs in each row: its first and
 * last hit) and in bx the box (i0, i1, j0, j1, k0, k1, half open) of the
 * balls' voxel boxes: no voxel outside it is atomic, so none is molecular
 * either (a ray's hits and the voxels between them lie in it). */
static void atomic_mask(const vbc_grid *g, const float *atoms4, size_t natoms, uint8_t *flags,
                        int *bx, int *rb)
{
    int nx = g->nx, ny = g->ny, nz = g->nz;
    memset(flags, 0, vbc_grid_voxels(g));
    for (int s = 0; s < ny * nz; s++) {
        rb[2 * s] = nx;
        rb[2 * s + 1] = -1;
    }
    bx[0] = nx;
    bx[2] = ny;
    bx[4] = nz;
    bx[1] = bx[3] = bx[5] = 0;
    for (size_t a = 0; a < natoms; a++) {
        const float *p = atoms4 + 4 * a;
        int box[6] = {vbc_box_lo(p[0], p[3]), vbc_box_hi(p[0], p[3], nx),
                      vbc_box_lo(p[1], p[3]), vbc_box_hi(p[1], p[3], ny),
                      vbc_box_lo(p[2], p[3]), vbc_box_hi(p[2], p[3], nz)};
        if (box[0] >= box[1] || box[2] >= box[3] || box[4] >= box[5])
            continue;
        for (int d = 0; d < 3; d++) {
            bx[2 * d] = box[2 * d] < bx[2 * d] ? box[2 * d] : bx[2 * d];
            bx[2 * d + 1] = box[2 * d + 1] > bx[2 * d + 1] ? box[2 * d + 1] : bx[2 * d + 1];
        }
        ball_mark(p, box, nx, ny, flags, rb);
    }
    if (bx[0] >= bx[1] || bx[2] >= bx[3] || bx[4] >= bx[5])
        bx[0] = bx[1] = bx[2] = bx[3] = bx[4] = bx[5] = 0;
}

/* The int16s of ray_bounds' y and z rays apart (yf, yl, zf, zl in a row;
 * a channel grid's side is at most 1024, vbc_grid_fit). */
static size_t planar_size(int nx, int ny, int nz)
{
    return 2 * ((size_t)nx * (size_t)nz + (size_t)nx * (size_t)ny);
}

/* The classification of voxel v = (i,j,k) from its flag byte's atomic bit,
 * the ray bounds and the labels (vbc_classify's byte). */
static unsigned classify(const vbc_grid *g, const int32_t *labels, const uint8_t *flags,
                         const int *rb, int min_labels, int i, int j, int k, size_t v)
{
    int nx = g->nx, ny = g->ny, nz = g->nz;
    size_t sy = (size_t)nx, sz = (size_t)nx * (size_t)ny;
    /* A voxel inside the grid whose six face neighbours share its label is
     * no Voronoi edge, hence no channel: its byte is the atomic, molecular
     * and interior bits alone (what vbc_classify gives it), without the
     * label count. */
    if (min_labels > 1 && i > 0 && j > 0 && k > 0 && i + 1 < nx && j + 1 < ny && k + 1 < nz) {
        int32_t l = labels[v];
        if (labels[v - 1] == l && labels[v + 1] == l && labels[v - sy] == l && labels[v + sy] == l &&
            labels[v - sz] == l && labels[v + sz] == l) {
            unsigned f = flags[v] & VBC_F_ATOMIC;
            if (vbc_molecular(rb, nx, ny, nz, i, j, k))
                f |= f ? VBC_F_MOLECULAR : VBC_F_MOLECULAR | VBC_F_INTERIOR;
            return f;
        }
    }
    return vbc_classify(labels, flags, rb, nx, ny, nz, min_labels, i, j, k);
}

void vbc_ray_bounds_plain(const uint8_t *am, int nx, int ny, int nz, int *rb)
{
    for (int b = 0; b < nz; b++)
        for (int a = 0; a < ny; a++)
            vbc_ray_scan(am, nx, ny, nz, 0, a, b, rb);
    for (int b = 0; b < nz; b++)
        for (int a = 0; a < nx; a++)
            vbc_ray_scan(am, nx, ny, nz, 1, a, b, rb);
    for (int b = 0; b < ny; b++)
        for (int a = 0; a < nx; a++)
            vbc_ray_scan(am, nx, ny, nz, 2, a, b, rb);
}

void vbc_masks_ref(const vbc_grid *g, const float *atoms4, size_t natoms, const int32_t *labels,
                   int min_labels, int *rb, uint8_t *flags)
{
    int nx = g->nx, ny = g->ny, nz = g->nz, bx[6];
    atomic_mask(g, atoms4, natoms, flags, bx, rb);
    int16_t *yf = malloc(planar_size(nx, ny, nz) * sizeof *yf);
    if (yf) {
        int16_t *yl = yf + (size_t)nx * nz, *zf = yl + (size_t)nx * nz, *zl = zf + (size_t)nx * ny;
        ray_bounds(flags, nx, ny, nz, bx, rb, yf, yl, zf, zl);
        free(yf);
    } else { /* no room for the pass: ray by ray */
        vbc_ray_bounds_plain(flags, nx, ny, nz, rb);
    }
    /* The classification reads only the voxel's own flag byte (its atomic
     * bit), so updating in place is safe. */
    size_t v = 0;
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++, v++)
                flags[v] = (uint8_t)classify(g, labels, flags, rb, min_labels, i, j, k, v);
}

/* The interior voxels of row `row` (bytes base + i0 .. base + i1) appended
 * to (*list, *cap, *m) in order. 0, or -1 when out of memory. */
static int list_interior(const uint8_t *row, size_t base, int i0, int i1, uint32_t **list,
                         size_t *cap, size_t *m)
{
    int i = i0;
#if defined(__GNUC__) && defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    /* Eight voxels at once: the interior bits of a word, taken lowest
     * first (byte b of the word is voxel i + b), in order. */
    for (; i + 8 <= i1; i += 8) {
        uint64_t w;
        memcpy(&w, row + i, sizeof w);
        w &= 0x0808080808080808ull;
        if (w && VB_ARRAY_FIT(*list, *cap, *m + 8, 4096) != VB_OK)
            return -1;
        for (; w; w &= w - 1)
            (*list)[(*m)++] = (uint32_t)(base + (size_t)i + (size_t)(__builtin_ctzll(w) >> 3));
    }
#endif
    for (; i < i1; i++) {
        if (!(row[i] & VBC_F_INTERIOR))
            continue;
        if (VB_ARRAY_FIT(*list, *cap, *m + 1, 4096) != VB_OK)
            return -1;
        (*list)[(*m)++] = (uint32_t)(base + (size_t)i);
    }
    return 0;
}

int vbc_masks_shape(vb_ctx *ctx, const vbc_grid *g, const float *atoms4, size_t natoms, int *rb,
                    uint8_t *flags, uint32_t **interior, size_t *ninterior)
{
    int nx = g->nx, ny = g->ny, nz = g->nz, bx[6];
    uint32_t *list = NULL;
    size_t m = 0, cap = 0, ny2 = (size_t)nx * (size_t)nz, nz2 = (size_t)nx * (size_t)ny;
    *interior = NULL;
    *ninterior = 0;
    /* The y and z rays' first and last hits apart (ray_bounds leaves them:
     * the loop below reads them along i, so it runs without branches). */
    int16_t *yf = malloc(planar_size(nx, ny, nz) * sizeof *yf);
    if (!yf)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "ray bounds of %d x %d x %d", nx, ny, nz);
    int16_t *yl = yf + ny2, *zf = yl + ny2, *zl = zf + nz2;
    atomic_mask(g, atoms4, natoms, flags, bx, rb);
    ray_bounds(flags, nx, ny, nz, bx, rb, yf, yl, zf, zl);
    /* vbc_molecular row by row in the box (outside it nothing is): the x
     * ray is the row's, the y and z rays run along the row with i. Between
     * the x ray's hits [xf, xl] every voxel is molecular; outside them none
     * is atomic, and one is molecular (and then interior) when its y or z
     * ray holds it. */
    int rc = VB_OK;
    for (int k = bx[4]; k < bx[5] && rc == VB_OK; k++)
        for (int j = bx[2]; j < bx[3]; j++) {
            size_t base = (size_t)nx * ((size_t)j + (size_t)ny * (size_t)k);
            uint8_t *restrict row = flags + base;
            const int *xb = rb + 2 * (j + ny * k);
            const int16_t *restrict yfk = yf + (size_t)nx * (size_t)k, *restrict ylk = yl + (size_t)nx * (size_t)k;
            const int16_t *restrict zfj = zf + (size_t)nx * (size_t)j, *restrict zlj = zl + (size_t)nx * (size_t)j;
            int16_t j16 = (int16_t)j, k16 = (int16_t)k;
            int e1 = xb[0] < bx[0] ? bx[0] : xb[0] > bx[1] ? bx[1] : xb[0];
            int e2 = xb[1] + 1 < e1 ? e1 : xb[1] + 1 > bx[1] ? bx[1] : xb[1] + 1;
            for (int part = 0; part < 2; part++)
                for (int i = part ? e2 : bx[0], end = part ? bx[1] : e1; i < end; i++) {
                    int in = ((yfk[i] <= j16) & (j16 <= ylk[i])) | ((zfj[i] <= k16) & (k16 <= zlj[i]));
                    row[i] = (uint8_t)(in ? VBC_F_MOLECULAR | VBC_F_INTERIOR : 0u);
                }
            for (int i = e1; i < e2; i++)
                row[i] = (uint8_t)(row[i] ? VBC_F_ATOMIC | VBC_F_MOLECULAR
                                          : VBC_F_MOLECULAR | VBC_F_INTERIOR);
            if (list_interior(row, base, bx[0], bx[1], &list, &cap, &m) != 0) {
                rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "interior voxels (%zu)", m + 1);
                break;
            }
        }
    free(yf);
    if (rc != VB_OK) {
        free(list);
        return rc;
    }
    *interior = list;
    *ninterior = m;
    return VB_OK;
}

/* The coordinates of voxel v of an nx x ny x nz grid: by shifts when the
 * sides are powers of two (as the channel grids are), else by division. */
typedef struct {
    size_t sy, sz;
    int ny, lx, ly; /* lx, ly: log2 of nx and ny, -1 when no power of two */
} voxel_coords;

static int log2_exact(int n)
{
    int l = 0;
    while ((1 << l) < n)
        l++;
    return (1 << l) == n ? l : -1;
}

static voxel_coords coords_of(const vbc_grid *g)
{
    voxel_coords c = {(size_t)g->nx, (size_t)g->nx * (size_t)g->ny, g->ny, log2_exact(g->nx),
                      log2_exact(g->ny)};
    return c;
}

static void coords_at(const voxel_coords *c, size_t v, int *i, int *j, int *k)
{
    if (c->lx >= 0 && c->ly >= 0) {
        *i = (int)(v & (c->sy - 1));
        *j = (int)((v >> c->lx) & (size_t)(c->ny - 1));
        *k = (int)(v >> (c->lx + c->ly));
    } else {
        *i = (int)(v % c->sy);
        *j = (int)(v / c->sy % (size_t)c->ny);
        *k = (int)(v / c->sz);
    }
}

void vbc_masks_need(const vbc_grid *g, const uint32_t *interior, size_t n, uint8_t *need)
{
    voxel_coords vc = coords_of(g);
    int nx = g->nx, ny = g->ny, nz = g->nz;
    size_t sy = (size_t)nx, sz = (size_t)nx * (size_t)ny;
    memset(need, 0, vbc_grid_voxels(g));
    for (size_t t = 0; t < n; t++) {
        size_t v = interior[t];
        int i, j, k;
        coords_at(&vc, v, &i, &j, &k);
        need[v] = 1;
        if (i > 0)
            need[v - 1] = 1;
        if (i + 1 < nx)
            need[v + 1] = 1;
        if (j > 0)
            need[v - sy] = 1;
        if (j + 1 < ny)
            need[v + sy] = 1;
        if (k > 0)
            need[v - sz] = 1;
        if (k + 1 < nz)
            need[v + sz] = 1;
    }
}

/* vbc_classify's byte of the interior voxel v = (i,j,k) of flags from
 * vbc_masks_shape: molecular and interior; the edge bit from the labels
 * as vbc_classify counts them (a voxel inside the grid whose six face
 * neighbours share its label has one); for a channel the mouth bit from
 * its face neighbours' molecular bits in flags, which are vbc_molecular's
 * answers: vbc_masks_shape wrote them in the box of the balls, and outside
 * it, as off the grid, no voxel is molecular. */
static unsigned classify_interior(const vbc_grid *g, const int32_t *labels, const uint8_t *flags,
                                  int min_labels, int i, int j, int k, size_t v)
{
    int nx = g->nx, ny = g->ny, nz = g->nz;
    size_t sy = (size_t)nx, sz = (size_t)nx * (size_t)ny;
    unsigned f = VBC_F_MOLECULAR | VBC_F_INTERIOR;
    int32_t l0 = labels[v];
    if (min_labels > 1 && i > 0 && j > 0 && k > 0 && i + 1 < nx && j + 1 < ny && k + 1 < nz &&
        labels[v - 1] == l0 && labels[v + 1] == l0 && labels[v - sy] == l0 && labels[v + sy] == l0 &&
        labels[v - sz] == l0 && labels[v + sz] == l0)
        return f;
    int l[7], m = 0;
    l[m++] = l0;
    if (i > 0) l[m++] = labels[v - 1];
    if (i + 1 < nx) l[m++] = labels[v + 1];
    if (j > 0) l[m++] = labels[v - sy];
    if (j + 1 < ny) l[m++] = labels[v + sy];
    if (k > 0) l[m++] = labels[v - sz];
    if (k + 1 < nz) l[m++] = labels[v + sz];
    if (vbc_distinct(l, m) < min_labels)
        return f;
    f |= VBC_F_EDGE | VBC_F_CHANNEL;
    if (i == 0 || !(flags[v - 1] & VBC_F_MOLECULAR) || i + 1 == nx || !(flags[v + 1] & VBC_F_MOLECULAR) ||
        j == 0 || !(flags[v - sy] & VBC_F_MOLECULAR) || j + 1 == ny ||
        !(flags[v + sy] & VBC_F_MOLECULAR) || k == 0 || !(flags[v - sz] & VBC_F_MOLECULAR) ||
        k + 1 == nz || !(flags[v + sz] & VBC_F_MOLECULAR))
        f |= VBC_F_MOUTH;
    return f;
}

size_t vbc_masks_edges(const vbc_grid *g, const int32_t *labels, int min_labels, const int *rb,
                       uint32_t *interior, size_t n, uint8_t *flags)
{
    voxel_coords vc = coords_of(g);
    size_t m = 0;
    (void)rb; /* the flags hold the molecular bits it would give */
    for (size_t t = 0; t < n; t++) {
        size_t v = interior[t];
        int i, j, k;
        coords_at(&vc, v, &i, &j, &k);
        unsigned f = classify_interior(g, labels, flags, min_labels, i, j, k, v);
        flags[v] = (uint8_t)f;
        if (f & VBC_F_CHANNEL)
            interior[m++] = (uint32_t)v | ((f & VBC_F_MOUTH) ? VBC_MOUTH_BIT : 0u);
    }
    return m;
}

int vbc_flags_compact(vb_ctx *ctx, const vbc_grid *g, const uint8_t *flags, uint32_t **out,
                      size_t *count)
{
    size_t nv = vbc_grid_voxels(g), m = 0;
    *out = NULL;
    *count = 0;
    for (size_t v = 0; v < nv; v++)
        m += (flags[v] & VBC_F_CHANNEL) != 0;
    if (m == 0)
        return VB_OK;
    uint32_t *list = malloc(m * sizeof *list);
    if (!list)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "channel voxel list (%zu)", m);
    m = 0;
    for (size_t v = 0; v < nv; v++)
        if (flags[v] & VBC_F_CHANNEL)
            list[m++] = (uint32_t)v | ((flags[v] & VBC_F_MOUTH) ? VBC_MOUTH_BIT : 0u);
    *out = list;
    *count = m;
    return VB_OK;
}
