/* The spatial index of sphere centres (see vbx_sindex.h for why it is
 * conservative). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vbx_sindex.h"

/* Grid cells are at most this many per sphere (plus a constant), whatever
 * the density estimate asks: memory stays linear in the input. */
#define VBX_CELLS_PER_SPHERE 4
/* Centres per occupied cell the density estimate aims at. */
#define VBX_PER_CELL 2.0
#define VBX_AXIS_MAX 2097151 /* 21-bit cell coordinates */

static void node_bounds(vbx_sindex *t, vbx_bvh_node *nd, size_t lo, size_t hi)
{
    for (int k = 0; k < 3; k++) {
        nd->lo[k] = INFINITY;
        nd->hi[k] = -INFINITY;
    }
    nd->rmax = -INFINITY;
    for (size_t s = lo; s < hi; s++) {
        const vbx_ia *b = &t->box[4 * s];
        for (int k = 0; k < 3; k++) {
            /* A NaN end (never from vbx_data) is kept: the node is then
             * never skipped. */
            nd->lo[k] = b[k].lo < nd->lo[k] || b[k].lo != b[k].lo ? b[k].lo : nd->lo[k];
            nd->hi[k] = b[k].hi > nd->hi[k] || b[k].hi != b[k].hi ? b[k].hi : nd->hi[k];
        }
        nd->rmax = b[3].hi > nd->rmax || b[3].hi != b[3].hi ? b[3].hi : nd->rmax;
    }
}

/* Spreads the low 21 bits of x to every third bit. */
static uint64_t spread3(uint64_t x)
{
    x &= 0x1fffffull;
    x = (x | x << 32) & 0x1f00000000ffffull;
    x = (x | x << 16) & 0x1f0000ff0000ffull;
    x = (x | x << 8) & 0x100f00f00f00f00full;
    x = (x | x << 4) & 0x10c30c30c30c30c3ull;
    x = (x | x << 2) & 0x1249249249249249ull;
    return x;
}

static void node_union(vbx_bvh_node *nd, const vbx_bvh_node *a, const vbx_bvh_node *b)
{
    for (int k = 0; k < 3; k++) {
        nd->lo[k] = a->lo[k] < b->lo[k] || a->lo[k] != a->lo[k] ? a->lo[k] : b->lo[k];
        nd->hi[k] = a->hi[k] > b->hi[k] || a->hi[k] != a->hi[k] ? a->hi[k] : b->hi[k];
    }
    nd->rmax = a->rmax > b->rmax || a->rmax != a->rmax ? a->rmax : b->rmax;
}

/* Node over the occupied cells cells[lo, hi) (sorted by their distinct
 * Morton codes `code`), one cell per leaf, split where the codes' highest
 * differing bit changes: depth at most 63. Returns the node's index. */
static uint32_t make(vbx_sindex *t, const uint64_t *code, const uint32_t *cells, size_t lo,
                     size_t hi)
{
    uint32_t me = (uint32_t)t->nnodes++;
    if (hi - lo == 1) {
        vbx_bvh_node *nd = &t->node[me];
        uint32_t c = cells[lo];
        nd->first = t->cell[c];
        nd->count = t->cell[c + 1] - t->cell[c];
        node_bounds(t, nd, nd->first, (size_t)nd->first + nd->count);
        return me;
    }
    uint64_t bit = (uint64_t)1 << (63 - __builtin_clzll(code[lo] ^ code[hi - 1]));
    size_t l = lo, h = hi - 1;
    while (l < h) {
        size_t m = l + (h - l) / 2;
        if (code[m] & bit)
            h = m;
        else
            l = m + 1;
    }
    uint32_t left = make(t, code, cells, lo, l);
    uint32_t right = make(t, code, cells, l, hi);
    vbx_bvh_node *nd = &t->node[me];
    node_union(nd, &t->node[left], &t->node[right]);
    nd->first = right;
    nd->count = 0;
    return me;
}

/* The hierarchy over the occupied cells. 0, or -1 when out of memory. */
static int build_tree(vbx_sindex *t, size_t cells)
{
    size_t m = 0;
    for (size_t c = 0; c < cells; c++)
        m += t->cell[c + 1] > t->cell[c];
    size_t m1 = m ? m : 1;
    uint64_t *code = malloc(m1 * sizeof *code), *tcode = malloc(m1 * sizeof *tcode);
    uint32_t *cl = malloc(m1 * sizeof *cl), *tcl = malloc(m1 * sizeof *tcl);
    int rc = code && tcode && cl && tcl ? 0 : -1;
    if (rc == 0) {
        size_t k = 0, nx = (size_t)t->nc[0], ny = (size_t)t->nc[1];
        for (size_t c = 0; c < cells; c++)
            if (t->cell[c + 1] > t->cell[c]) {
                uint64_t x = c % nx, y = (c / nx) % ny, z = c / (nx * ny);
                code[k] = spread3(x) | spread3(y) << 1 | spread3(z) << 2;
                cl[k++] = (uint32_t)c;
            }
        /* LSD radix sort on 63 bits, 9 passes of 7 (the codes are distinct). */
        for (int pass = 0; pass < 9; pass++) {
            size_t cnt[129] = {0};
            int sh = 7 * pass;
            for (size_t i = 0; i < m; i++)
                cnt[((code[i] >> sh) & 127) + 1]++;
            for (int b = 0; b < 128; b++)
                cnt[b + 1] += cnt[b];
            for (size_t i = 0; i < m; i++) {
                size_t at = cnt[(code[i] >> sh) & 127]++;
                tcode[at] = code[i];
                tcl[at] = cl[i];
            }
            uint64_t *sw = code;
            code = tcode;
            tcode = sw;
            uint32_t *sc = cl;
            cl = tcl;
            tcl = sc;
        }
        if (m)
            make(t, code, cl, 0, m);
    }
    free(code);
    free(tcode);
    free(cl);
    free(tcl);
    return rc;
}

/* Cells per axis for side h, or 0 when the grid would exceed `cap` cells. */
static size_t grid_cells(const double ext[3], double h, size_t cap, int nc[3])
{
    size_t total = 1;
    for (int k = 0; k < 3; k++) {
        double c = floor(ext[k] / h) + 1.0;
        if (!(c <= (double)VBX_AXIS_MAX) || (double)total * c > (double)cap)
            return 0;
        nc[k] = (int)c;
        total *= (size_t)c;
    }
    return total;
}

/* Occupied cells of the grid with side h (cells fit cap), counted with
 * the scratch array mark (cap entries). */
static size_t occupied(const vbx_sindex *t, const double *near, size_t n, uint8_t *mark,
                       size_t cells)
{
    memset(mark, 0, cells);
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        size_t c = ((size_t)vbx_sindex_axis(t, 2, near[4 * i + 2]) * (size_t)t->nc[1] +
                    (size_t)vbx_sindex_axis(t, 1, near[4 * i + 1])) *
                       (size_t)t->nc[0] +
                   (size_t)vbx_sindex_axis(t, 0, near[4 * i]);
        m += !mark[c];
        mark[c] = 1;
    }
    return m;
}

/* The cell side: about VBX_PER_CELL centres per occupied cell, from the
 * density of the occupied cells of a trial grid (twice: a first grid from
 * the bounding box is too coarse for a thin shell), never more than the
 * cap of cells. Any side is correct; this one makes the scans cheap. */
static int choose_side(vbx_sindex *t, const double *near, size_t n, const double ext[3],
                       size_t cap)
{
    double emax = fmax(ext[0], fmax(ext[1], ext[2]));
    if (!(emax > 0.0) || !(emax < INFINITY)) {
        t->h = emax > 0.0 && emax < INFINITY ? emax : 1.0;
        return 0;
    }
    /* Side of a grid with about n cells over the box (flat boxes count
     * their thin axes as emax / n^(1/3)). */
    double vol = 1.0, floor_ext = emax / cbrt((double)n);
    for (int k = 0; k < 3; k++)
        vol *= fmax(ext[k], floor_ext);
    double h = cbrt(vol / (double)n);
    uint8_t *mark = malloc(cap);
    if (!mark)
        return -1;
    for (int pass = 0; pass < 2; pass++) {
        /* Grow until the grid fits the cap. */
        while (!grid_cells(ext, h, cap, t->nc))
            h *= 1.25;
        t->h = h;
        t->ih = 1.0 / h;
        size_t m = occupied(t, near, n, mark, (size_t)t->nc[0] * t->nc[1] * t->nc[2]);
        h = h * cbrt(VBX_PER_CELL * (double)m / (double)n);
    }
    while (!grid_cells(ext, h, cap, t->nc))
        h *= 1.25;
    t->h = h;
    free(mark);
    return 0;
}

static size_t cell_of(const vbx_sindex *t, const double *c)
{
    return ((size_t)vbx_sindex_axis(t, 2, c[2]) * (size_t)t->nc[1] +
            (size_t)vbx_sindex_axis(t, 1, c[1])) *
               (size_t)t->nc[0] +
           (size_t)vbx_sindex_axis(t, 0, c[0]);
}

int vbx_sindex_build(vbx_sindex *t, const vbx_ia *box, const double *near, size_t n)
{
    memset(t, 0, sizeof *t);
    /* Node indices are 32-bit: fewer than 2n nodes. */
    if (n >= ((size_t)1 << 31))
        return -1;
    size_t n1 = n ? n : 1, cap = VBX_CELLS_PER_SPHERE * n1 + 64;
    t->node = malloc(2 * n1 * sizeof *t->node);
    t->ids = malloc(n1 * sizeof *t->ids);
    t->box = malloc(4 * n1 * sizeof *t->box);
    t->mid = malloc(4 * n1 * sizeof *t->mid);
    int rc = t->node && t->ids && t->box && t->mid ? 0 : -1;
    double ext[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < 3 && rc == 0; k++) {
        double l = INFINITY, h = -INFINITY;
        for (size_t i = 0; i < n; i++) {
            l = fmin(l, near[4 * i + k]);
            h = fmax(h, near[4 * i + k]);
        }
        t->x0[k] = n ? l : 0.0;
        ext[k] = n ? h - l : 0.0;
    }
    if (rc == 0)
        rc = choose_side(t, near, n, ext, cap);
    if (rc == 0 && !grid_cells(ext, t->h, cap, t->nc))
        t->nc[0] = t->nc[1] = t->nc[2] = 1;
    size_t cells = (size_t)t->nc[0] * t->nc[1] * t->nc[2];
    t->ih = 1.0 / t->h;
    for (int k = 0; k < 3; k++)
        t->eps[k] = 0x1p-45 * (fabs(t->x0[k]) + (double)t->nc[k] * t->h) + 0x1p-1000;
    if (rc == 0 && !(t->cell = calloc(cells + 1, sizeof *t->cell)))
        rc = -1;
    if (rc != 0) {
        vbx_sindex_free(t);
        return -1;
    }
    t->n = n;
    /* Counting sort by cell, stable: ids increase within a cell. */
    for (size_t i = 0; i < n; i++)
        t->cell[cell_of(t, &near[4 * i]) + 1]++;
    for (size_t c = 0; c < cells; c++)
        t->cell[c + 1] += t->cell[c];
    for (size_t i = 0; i < n; i++) {
        size_t c = cell_of(t, &near[4 * i]);
        /* cell[c] counts up to the start of cell c + 1, then is restored. */
        t->ids[t->cell[c]++] = (uint32_t)i;
    }
    for (size_t c = cells; c > 0; c--)
        t->cell[c] = t->cell[c - 1];
    t->cell[0] = 0;
    t->rmax = 0.0;
    t->rmin = n ? INFINITY : 0.0;
    t->wc = 0.0;
    for (size_t s = 0; s < n; s++) {
        size_t i = t->ids[s];
        memcpy(&t->box[4 * s], &box[4 * i], 4 * sizeof *t->box);
        if (!(t->box[4 * s + 3].hi <= t->rmax))
            t->rmax = t->box[4 * s + 3].hi;
        if (t->rmin == t->rmin && !(t->box[4 * s + 3].lo >= t->rmin))
            t->rmin = t->box[4 * s + 3].lo;
        for (int k = 0; k < 3; k++) {
            /* The nearest double and the exact centre both lie in the
             * enclosure, so they differ by at most its width (rounded up). */
            t->mid[4 * s + k] = near[4 * i + k];
            double wd = vbx_succ(box[4 * i + k].hi - box[4 * i + k].lo);
            if (!(wd <= t->wc))
                t->wc = wd;
        }
        t->mid[4 * s + 3] = box[4 * i + 3].hi;
    }
    if (build_tree(t, cells) != 0) {
        vbx_sindex_free(t);
        return -1;
    }
    return 0;
}

void vbx_sindex_free(vbx_sindex *t)
{
    free(t->node);
    free(t->ids);
    free(t->box);
    free(t->mid);
    free(t->cell);
    memset(t, 0, sizeof *t);
}
