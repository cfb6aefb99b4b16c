/* Open roots at one tie vertex, grouped before their exact paths.
 *
 * On exact crystals most open roots are a vertex of degree > 4 met again
 * through another quadruple of its members. vb_certify_quads solves the
 * first root of each group exactly; a later root of the group skips its
 * exact path when its quadruple lies within the members of the vertex the
 * first one certified (vbx_quad_within): that vertex is then exactly a root
 * of the quadruple, and not the other root, which a filter refused or
 * certified with four members (or which does not exist: delta = 0). The
 * grouping only proposes which vertex to try; the subset proves it, so a
 * wrong group costs an exact path, never a wrong vertex.
 *
 * Enclosures of one exact point meet. They are far narrower than a cell of
 * the grid, so a box covers at most two cells per axis; a leader is entered
 * in every cell its box covers, and a later box looks in every cell it
 * covers, which finds each leader it meets. */
#include <math.h>
#include <stdlib.h>

#include "vb_array.h"
#include "vb_hash.h"
#include "vbx_qties.h"

/* A leader entered in one cell; the cells' lists run newest first. */
typedef struct cell_entry {
    int64_t c[3];
    size_t tie, next; /* next: the entry before it in this cell, SIZE_MAX: none */
} cell_entry;

typedef struct grid {
    cell_entry *e;
    size_t n, cap;
    vb_hash tab; /* a cell's newest entry */
} grid;

typedef struct cell_probe {
    const grid *g;
    uint64_t hash;
    const int64_t *c;
} cell_probe;

static uint64_t cell_hash(const int64_t c[3])
{
    uint64_t h = vb_hash_mix(0, (uint64_t)c[0]);
    h = vb_hash_mix(h, (uint64_t)c[1]);
    return vb_hash_mix(h, (uint64_t)c[2]);
}

static uint64_t entry_hash(const void *arg, size_t k)
{
    const grid *g = arg;
    return cell_hash(g->e[k].c);
}

static int cell_same(const void *key, size_t k)
{
    const cell_probe *p = key;
    const int64_t *c = p->g->e[k].c;
    return c[0] == p->c[0] && c[1] == p->c[1] && c[2] == p->c[2];
}

/* Cells lo[a] .. hi[a] per axis of box b (cell size h); 0 when the box is
 * wider than a cell or out of the grid's reach. */
static int cells_of(const vbx_qtie *b, double h, int64_t lo[3], int64_t hi[3])
{
    for (int a = 0; a < 3; a++) {
        if (!(b->hi[a] - b->lo[a] <= h))
            return 0;
        double l = floor(b->lo[a] / h), u = floor(b->hi[a] / h);
        if (!(fabs(l) < 0x1p52 && fabs(u) < 0x1p52))
            return 0;
        lo[a] = (int64_t)l;
        hi[a] = (int64_t)u;
    }
    return 1;
}

static int meets(const vbx_qtie *a, const vbx_qtie *b)
{
    for (int k = 0; k < 3; k++)
        if (a->hi[k] < b->lo[k] || b->hi[k] < a->lo[k])
            return 0;
    return 1;
}

/* The first leader that meets tie i in cell c (SIZE_MAX: none). */
static size_t leader_in(const grid *g, const vbx_qtie *t, size_t i, const int64_t c[3])
{
    cell_probe p = {g, cell_hash(c), c};
    size_t best = SIZE_MAX;
    for (size_t k = vb_hash_get(&g->tab, p.hash, cell_same, &p); k != SIZE_MAX;
         k = g->e[k].next)
        if (g->e[k].tie < best && meets(&t[g->e[k].tie], &t[i]))
            best = g->e[k].tie;
    return best;
}

static int enter(grid *g, size_t tie, const int64_t c[3])
{
    if (VB_ARRAY_FIT(g->e, g->cap, g->n + 1, 256) != VB_OK)
        return VB_ENOMEM;
    cell_probe p = {g, cell_hash(c), c};
    size_t *slot = vb_hash_slot(&g->tab, p.hash, cell_same, &p);
    cell_entry *e = &g->e[g->n];
    e->c[0] = c[0];
    e->c[1] = c[1];
    e->c[2] = c[2];
    e->tie = tie;
    e->next = *slot ? *slot - 1 : SIZE_MAX;
    return vb_hash_put(&g->tab, slot, g->n++, entry_hash, g);
}

/* A power of two at least 2^-24 of the largest centre coordinate plus
 * radius (1 for an empty or all-zero input). */
static double cell_size(const vb_certifier *c)
{
    double m = 0.0;
    for (size_t j = 0; j < c->set->n; j++) {
        const double *s = &c->d.near[4 * j];
        double r = fabs(s[3]);
        for (int a = 0; a < 3; a++)
            if (fabs(s[a]) + r > m)
                m = fabs(s[a]) + r;
    }
    if (!(m > 0.0) || !isfinite(m))
        return 1.0;
    return ldexp(1.0, ilogb(m) + 1 - 24);
}

int vbx_ties_group(vb_ctx *ctx, const vb_certifier *c, vbx_qtie *t, size_t n)
{
    grid g = {0};
    int rc = n ? vb_hash_fit(&g.tab, 0, entry_hash, &g) : VB_OK;
    double h = cell_size(c);
    for (size_t i = 0; i < n && rc == VB_OK; i++) {
        int64_t lo[3], hi[3], cc[3];
        t[i].leader = i;
        if (!cells_of(&t[i], h, lo, hi))
            continue;
        size_t best = SIZE_MAX;
        for (cc[0] = lo[0]; cc[0] <= hi[0]; cc[0]++)
            for (cc[1] = lo[1]; cc[1] <= hi[1]; cc[1]++)
                for (cc[2] = lo[2]; cc[2] <= hi[2]; cc[2]++) {
                    size_t k = leader_in(&g, t, i, cc);
                    if (k < best)
                        best = k;
                }
        if (best != SIZE_MAX) {
            t[i].leader = best;
            continue;
        }
        for (cc[0] = lo[0]; cc[0] <= hi[0] && rc == VB_OK; cc[0]++)
            for (cc[1] = lo[1]; cc[1] <= hi[1] && rc == VB_OK; cc[1]++)
                for (cc[2] = lo[2]; cc[2] <= hi[2] && rc == VB_OK; cc[2]++)
                    rc = enter(&g, i, cc);
    }
    free(g.e);
    vb_hash_free(&g.tab);
    if (rc != VB_OK)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (tie vertices)");
    return VB_OK;
}

int vbx_quad_within(const uint32_t q[4], const uint32_t *m, size_t nm)
{
    size_t j = 0;
    for (int i = 0; i < 4; i++) {
        while (j < nm && m[j] < q[i])
            j++;
        if (j == nm || m[j] != q[i])
            return 0;
        j++;
    }
    return 1;
}
