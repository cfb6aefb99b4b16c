/* The C_n symmetry axis of an oligomer (vbc_axis_symmetry, vbc_pore.h):
 * chains of one sequence superposed onto their neighbours by one rotation
 * about one axis, as a structural biologist reads a pentamer or a porin
 * trimer. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vbc_pore.h"

#define SYM_MAX_CHAINS 64

typedef struct {
    char name[8];
    size_t nca;      /* C-alpha atoms */
    size_t *ca;      /* their indices in s, in file order */
    uint64_t seq;    /* FNV-1a of their residue names in order */
    double m[3];     /* centroid of the C-alpha atoms */
    double angle;    /* about the first guess of the axis */
} sym_chain;

static int is_ca(const vb_atom_info *a)
{
    return strcmp(a->name, "CA") == 0 && (a->element[0] == 'C' && a->element[1] == '\0');
}

/* The chains of s with their C-alpha atoms; -1 out of memory or too many
 * chains (a large assembly: no single axis to trust). */
static int collect(const vb_sphere_set *s, sym_chain *ch, size_t *idx)
{
    int nc = 0;
    size_t used = 0;
    /* Two passes: count per chain, then fill (the chains' atoms may interleave). */
    for (size_t i = 0; i < s->n; i++) {
        if (!is_ca(&s->info[i]))
            continue;
        int c = 0;
        while (c < nc && strcmp(ch[c].name, s->info[i].chain) != 0)
            c++;
        if (c == nc) {
            if (nc == SYM_MAX_CHAINS)
                return -1;
            memset(&ch[nc], 0, sizeof ch[nc]);
            snprintf(ch[nc].name, sizeof ch[nc].name, "%s", s->info[i].chain);
            ch[nc].seq = 1469598103934665603ull;
            nc++;
        }
        ch[c].nca++;
    }
    for (int c = 0; c < nc; c++) {
        ch[c].ca = idx + used;
        used += ch[c].nca;
        ch[c].nca = 0;
    }
    for (size_t i = 0; i < s->n; i++) {
        if (!is_ca(&s->info[i]))
            continue;
        int c = 0;
        while (strcmp(ch[c].name, s->info[i].chain) != 0)
            c++;
        sym_chain *C = &ch[c];
        C->ca[C->nca++] = i;
        for (const char *p = s->info[i].resname; *p; p++)
            C->seq = (C->seq ^ (uint8_t)*p) * 1099511628211ull;
        C->seq = (C->seq ^ 0xffu) * 1099511628211ull;
        C->m[0] += s->x[i];
        C->m[1] += s->y[i];
        C->m[2] += s->z[i];
    }
    for (int c = 0; c < nc; c++)
        for (int k = 0; k < 3; k++)
            ch[c].m[k] /= (double)(ch[c].nca ? ch[c].nca : 1);
    return nc;
}

/* p rotated by angle t about the axis through c along u (unit). */
static void rotate(const double p[3], const double c[3], const double u[3], double t, double q[3])
{
    double d[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
    double ud = u[0] * d[0] + u[1] * d[1] + u[2] * d[2];
    double x[3] = {u[1] * d[2] - u[2] * d[1], u[2] * d[0] - u[0] * d[2], u[0] * d[1] - u[1] * d[0]};
    double ct = cos(t), st = sin(t);
    for (int k = 0; k < 3; k++)
        q[k] = c[k] + d[k] * ct + x[k] * st + u[k] * ud * (1.0 - ct);
}

static int by_angle(const void *a, const void *b)
{
    const sym_chain *x = *(const sym_chain *const *)a, *y = *(const sym_chain *const *)b;
    return (x->angle > y->angle) - (x->angle < y->angle);
}

/* Fits and checks the axis of the n chains g (equal sequences). */
static int fit(const vb_sphere_set *s, sym_chain **g, int n, vbc_axis *out)
{
    double m[3] = {0.0, 0.0, 0.0}, cov[3][3] = {{0.0}}, w[3], v[3][3];
    for (int c = 0; c < n; c++)
        for (int k = 0; k < 3; k++)
            m[k] += g[c]->m[k] / n;
    for (int c = 0; c < n; c++)
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                cov[a][b] += (g[c]->m[a] - m[a]) * (g[c]->m[b] - m[b]);
    vbc_eigen3((const double (*)[3])cov, w, v);
    double u[3] = {v[0][2], v[1][2], v[2][2]};
    if (!(w[1] > 1e-6 * (w[0] + 1e-300)))
        return 0; /* centroids on a line: no ring */
    /* The chains in their order around the first guess. */
    double e1[3] = {v[0][0], v[1][0], v[2][0]};
    double e2[3] = {u[1] * e1[2] - u[2] * e1[1], u[2] * e1[0] - u[0] * e1[2], u[0] * e1[1] - u[1] * e1[0]};
    for (int c = 0; c < n; c++) {
        double d[3] = {g[c]->m[0] - m[0], g[c]->m[1] - m[1], g[c]->m[2] - m[2]};
        g[c]->angle = atan2(d[0] * e2[0] + d[1] * e2[1] + d[2] * e2[2],
                            d[0] * e1[0] + d[1] * e1[1] + d[2] * e1[2]);
    }
    qsort(g, (size_t)n, sizeof *g, by_angle);
    /* Displacements of corresponding atoms, chain to next: all normal to the axis. */
    double sc[3][3] = {{0.0}};
    size_t na = g[0]->nca;
    for (int c = 0; c < n; c++) {
        const sym_chain *A = g[c], *B = g[(c + 1) % n];
        for (size_t i = 0; i < na; i++) {
            size_t p = A->ca[i], q = B->ca[i];
            double d[3] = {s->x[q] - s->x[p], s->y[q] - s->y[p], s->z[q] - s->z[p]};
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++)
                    sc[a][b] += d[a] * d[b];
        }
    }
    vbc_eigen3((const double (*)[3])sc, w, v);
    double ax[3] = {v[0][2], v[1][2], v[2][2]};
    if (ax[0] * u[0] + ax[1] * u[1] + ax[2] * u[2] < 0)
        for (int k = 0; k < 3; k++)
            ax[k] = -ax[k];
    /* The check: each chain turned by 360/n degrees lands on the next. The
     * sense of the turn is the one the centroids go round. */
    double t = 2.0 * acos(-1.0) / n;
    for (int sense = 0; sense < 2; sense++) {
        double tt = sense ? -t : t, sum = 0.0;
        for (int c = 0; c < n; c++) {
            const sym_chain *A = g[c], *B = g[(c + 1) % n];
            for (size_t i = 0; i < na; i++) {
                double p[3] = {s->x[A->ca[i]], s->y[A->ca[i]], s->z[A->ca[i]]}, q[3];
                rotate(p, m, ax, tt, q);
                double dx = q[0] - s->x[B->ca[i]], dy = q[1] - s->y[B->ca[i]], dz = q[2] - s->z[B->ca[i]];
                sum += dx * dx + dy * dy + dz * dz;
            }
        }
        double rms = sqrt(sum / (double)(na * (size_t)n));
        if (rms < VBC_SYM_MAX_RMS) {
            memset(out, 0, sizeof *out);
            memcpy(out->u, ax, sizeof ax);
            vbc_axis_orient(out->u);
            memcpy(out->c, m, sizeof m);
            out->source = VBC_AXIS_SYMMETRY;
            out->chains = n;
            int o = snprintf(out->why, sizeof out->why, "C%d symmetry of chains ", n);
            for (int c = 0; c < n && o < (int)sizeof out->why - 12; c++)
                o += snprintf(out->why + o, sizeof out->why - (size_t)o, "%s%s", c ? "," : "",
                              g[c]->name[0] ? g[c]->name : "_");
            snprintf(out->why + o, sizeof out->why - (size_t)o, " (rms %.2f A)", rms);
            return 1;
        }
    }
    return 0;
}

/* Whether the C-alpha atoms of chain x are in increasing residue order
 * (number, then insertion code): the merge below needs it. */
static int increasing(const vb_sphere_set *s, const sym_chain *x)
{
    for (size_t i = 1; i < x->nca; i++) {
        const vb_atom_info *p = &s->info[x->ca[i - 1]], *q = &s->info[x->ca[i]];
        if (q->resseq < p->resseq || (q->resseq == p->resseq && q->icode <= p->icode))
            return 0;
    }
    return 1;
}

static int res_cmp(const vb_atom_info *p, const vb_atom_info *q)
{
    if (p->resseq != q->resseq)
        return p->resseq < q->resseq ? -1 : 1;
    return (p->icode > q->icode) - (p->icode < q->icode);
}

/* How many C-alpha atoms of x find one in y with the same residue number,
 * insertion code and name (both increasing); in at[i] (when not NULL) the
 * index into y of x's i-th match, or SIZE_MAX. */
static size_t matches(const vb_sphere_set *s, const sym_chain *x, const sym_chain *y, size_t *at)
{
    size_t n = 0, j = 0;
    for (size_t i = 0; i < x->nca; i++) {
        const vb_atom_info *p = &s->info[x->ca[i]];
        while (j < y->nca && res_cmp(&s->info[y->ca[j]], p) < 0)
            j++;
        int hit = j < y->nca && res_cmp(&s->info[y->ca[j]], p) == 0 &&
                  strcmp(s->info[y->ca[j]].resname, p->resname) == 0;
        if (at)
            at[i] = hit ? j : SIZE_MAX;
        n += (size_t)hit;
    }
    return n;
}

/* Chains of one protein: the same C-alpha sequence (the same count and
 * residue names in order), or, for chains resolved over different
 * stretches (a tetrameric channel's loops missing in some subunits), both
 * in increasing residue order with at least VBC_SYM_MIN_SHARED of the
 * longer one's C-alpha atoms matched by number and name. */
static int same_protein(const vb_sphere_set *s, const sym_chain *x, const sym_chain *y)
{
    if (x->nca == y->nca && x->seq == y->seq)
        return 1;
    if (!increasing(s, x) || !increasing(s, y))
        return 0;
    size_t big = x->nca > y->nca ? x->nca : y->nca;
    return (double)matches(s, x, y, NULL) >= VBC_SYM_MIN_SHARED * (double)big;
}

/* Restricts the chains g[0..n) to the residues all of them hold (when
 * they are not all the same sequence): each chain's C-alpha list becomes
 * those residues in g[0]'s order (written over idx2, s->n entries), its
 * centroid theirs. Returns the residues kept. */
static size_t common_residues(const vb_sphere_set *s, sym_chain **g, int n, size_t *idx2,
                              size_t *at)
{
    int same = 1;
    for (int c = 1; c < n; c++)
        same &= g[c]->nca == g[0]->nca && g[c]->seq == g[0]->seq;
    if (same)
        return g[0]->nca;
    size_t na = g[0]->nca;
    uint8_t *keep = (uint8_t *)(at + na); /* the caller's room: na more */
    memset(keep, 1, na);
    for (int c = 1; c < n; c++) {
        matches(s, g[0], g[c], at);
        for (size_t i = 0; i < na; i++)
            keep[i] &= at[i] != SIZE_MAX;
    }
    size_t m = 0;
    for (size_t i = 0; i < na; i++)
        m += keep[i];
    for (int c = 0; c < n; c++) {
        size_t *list = idx2 + (size_t)c * m, k = 0;
        if (c > 0)
            matches(s, g[0], g[c], at);
        for (size_t i = 0; i < na; i++)
            if (keep[i])
                list[k++] = c > 0 ? g[c]->ca[at[i]] : g[0]->ca[i];
    }
    for (int c = 0; c < n; c++) {
        g[c]->ca = idx2 + (size_t)c * m;
        g[c]->nca = m;
        double mm[3] = {0.0, 0.0, 0.0};
        for (size_t i = 0; i < m; i++) {
            mm[0] += s->x[g[c]->ca[i]];
            mm[1] += s->y[g[c]->ca[i]];
            mm[2] += s->z[g[c]->ca[i]];
        }
        for (int k = 0; k < 3; k++)
            g[c]->m[k] = m ? mm[k] / (double)m : 0.0;
    }
    return m;
}

int vbc_axis_symmetry(const vb_sphere_set *s, vbc_axis *out)
{
    if (!s->info || s->n == 0)
        return 0;
    sym_chain ch[SYM_MAX_CHAINS];
    /* idx: the chains' C-alpha lists; then the common residues' lists (at
     * most s->n in all: each chain keeps at most its own), and the merge's
     * room (2 s->n). */
    size_t *idx = malloc(4 * s->n * sizeof *idx);
    if (!idx)
        return 0;
    int nc = collect(s, ch, idx), found = 0;
    /* The largest group of chains of one protein first; ties to the
     * earlier chain. */
    int done[SYM_MAX_CHAINS] = {0};
    sym_chain *best[SYM_MAX_CHAINS];
    int nbest = 0;
    for (int c = 0; c < nc; c++) {
        if (done[c] || ch[c].nca < VBC_SYM_MIN_CA)
            continue;
        sym_chain *grp[SYM_MAX_CHAINS];
        int n = 0;
        for (int d = c; d < nc; d++)
            if (!done[d] && ch[d].nca >= VBC_SYM_MIN_CA && same_protein(s, &ch[c], &ch[d])) {
                done[d] = 1;
                grp[n++] = &ch[d];
            }
        if (n > nbest) {
            nbest = n;
            memcpy(best, grp, (size_t)n * sizeof *grp);
        }
    }
    if (nbest >= 3 && common_residues(s, best, nbest, idx + s->n, idx + 2 * s->n) >= VBC_SYM_MIN_CA)
        found = fit(s, best, nbest, out);
    free(idx);
    return found;
}
