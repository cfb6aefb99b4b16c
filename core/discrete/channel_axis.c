/* Where a pore's axis lies when the user does not say: the symmetry of the
 * chains, or the principal axes of the atoms (vbc_pore.h). */
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "vbc_pore.h"

const char *vbc_axis_source_name(int source)
{
    switch (source) {
    case VBC_AXIS_GIVEN: return "given";
    case VBC_AXIS_CHAINS: return "chains";
    case VBC_AXIS_CHANNEL: return "channel";
    case VBC_AXIS_PRINCIPAL: return "principal";
    case VBC_AXIS_SUBUNIT: return "subunit";
    case VBC_AXIS_SYMMETRY: return "symmetry";
    case VBC_AXIS_BARREL: return "barrel";
    case VBC_AXIS_MEMBRANE: return "membrane";
    default: return "none";
    }
}

void vbc_eigen3(const double a_in[3][3], double w[3], double v[3][3])
{
    double a[3][3];
    memcpy(a, a_in, sizeof a);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            v[i][j] = i == j;
    for (int sweep = 0; sweep < 64; sweep++) {
        double off = fabs(a[0][1]) + fabs(a[0][2]) + fabs(a[1][2]);
        if (off < 1e-15 * (fabs(a[0][0]) + fabs(a[1][1]) + fabs(a[2][2])) || off == 0.0)
            break;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                if (a[p][q] == 0.0)
                    continue;
                double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                double t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
                double cs = 1.0 / sqrt(t * t + 1.0), sn = t * cs;
                for (int k = 0; k < 3; k++) { /* A <- A J */
                    double akp = a[k][p], akq = a[k][q];
                    a[k][p] = cs * akp - sn * akq;
                    a[k][q] = sn * akp + cs * akq;
                }
                for (int k = 0; k < 3; k++) { /* A <- J^T A */
                    double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = cs * apk - sn * aqk;
                    a[q][k] = sn * apk + cs * aqk;
                }
                for (int k = 0; k < 3; k++) {
                    double vkp = v[k][p], vkq = v[k][q];
                    v[k][p] = cs * vkp - sn * vkq;
                    v[k][q] = sn * vkp + cs * vkq;
                }
            }
    }
    int idx[3] = {0, 1, 2};
    for (int i = 0; i < 3; i++)
        for (int j = i + 1; j < 3; j++)
            if (a[idx[j]][idx[j]] > a[idx[i]][idx[i]]) {
                int t = idx[i];
                idx[i] = idx[j];
                idx[j] = t;
            }
    double vv[3][3];
    for (int i = 0; i < 3; i++) {
        w[i] = a[idx[i]][idx[i]];
        for (int k = 0; k < 3; k++)
            vv[k][i] = v[k][idx[i]];
    }
    memcpy(v, vv, sizeof vv);
}

void vbc_axis_orient(double u[3])
{
    int k = 0;
    for (int i = 1; i < 3; i++)
        if (fabs(u[i]) > fabs(u[k]))
            k = i;
    if (u[k] < 0)
        for (int i = 0; i < 3; i++)
            u[i] = -u[i];
}

/* Covariance of n points (x, y, z arrays or centroids) and their mean. */
static void covariance(size_t n, const double *x, const double *y, const double *z, double m[3],
                       double cov[3][3])
{
    m[0] = m[1] = m[2] = 0.0;
    for (size_t i = 0; i < n; i++) {
        m[0] += x[i];
        m[1] += y[i];
        m[2] += z[i];
    }
    for (int k = 0; k < 3; k++)
        m[k] /= (double)n;
    memset(cov, 0, 9 * sizeof(double));
    for (size_t i = 0; i < n; i++) {
        double d[3] = {x[i] - m[0], y[i] - m[1], z[i] - m[2]};
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                cov[a][b] += d[a] * d[b];
    }
}

void vbc_axis_principal(const vb_sphere_set *s, vbc_axis out[3])
{
    double m[3], cov[3][3], w[3], v[3][3];
    covariance(s->n, s->x, s->y, s->z, m, cov);
    vbc_eigen3((const double (*)[3])cov, w, v);
    for (int i = 0; i < 3; i++) {
        memset(&out[i], 0, sizeof out[i]);
        for (int k = 0; k < 3; k++) {
            out[i].u[k] = v[k][i];
            out[i].c[k] = m[k];
        }
        vbc_axis_orient(out[i].u);
        out[i].source = VBC_AXIS_PRINCIPAL;
        snprintf(out[i].why, sizeof out[i].why, "principal axis %d of the atom centres (%s variance)",
                 i + 1, i == 0 ? "largest" : i == 1 ? "middle" : "smallest");
    }
}

#define MAX_CHAINS 64

/* The centroids of the chains of at least 8 atoms (fewer are ions or
 * ligands, not subunits), in the order of their first atoms, and the
 * smallest and largest such chain. Returns how many, -1 for more than
 * MAX_CHAINS chains (a large assembly: no single symmetry axis to trust). */
static int chain_centroids(const vb_sphere_set *s, double *cx, double *cy, double *cz,
                           size_t *count, size_t *lo_out, size_t *hi_out, char names[][8])
{
    int nc = 0;
    for (size_t i = 0; i < s->n; i++) {
        int c = 0;
        while (c < nc && strcmp(names[c], s->info[i].chain) != 0)
            c++;
        if (c == nc) {
            if (nc == MAX_CHAINS)
                return -1;
            snprintf(names[nc], sizeof names[nc], "%s", s->info[i].chain);
            cx[nc] = cy[nc] = cz[nc] = 0.0;
            count[nc++] = 0;
        }
        cx[c] += s->x[i];
        cy[c] += s->y[i];
        cz[c] += s->z[i];
        count[c]++;
    }
    int k = 0;
    size_t lo = (size_t)-1, hi = 0;
    for (int c = 0; c < nc; c++) {
        if (count[c] < 8)
            continue;
        cx[k] = cx[c] / (double)count[c];
        cy[k] = cy[c] / (double)count[c];
        cz[k] = cz[c] / (double)count[c];
        count[k] = count[c];
        memmove(names[k], names[c], 8);
        lo = count[k] < lo ? count[k] : lo;
        hi = count[k] > hi ? count[k] : hi;
        k++;
    }
    *lo_out = lo;
    *hi_out = hi;
    return k;
}

int vbc_axis_subunits(const vb_sphere_set *s, const vbc_axis *sym, vbc_axis *out, int max)
{
    double cx[MAX_CHAINS], cy[MAX_CHAINS], cz[MAX_CHAINS];
    size_t count[MAX_CHAINS], lo, hi;
    char names[MAX_CHAINS][8];
    if (!s->info || s->n == 0 || (sym->source != VBC_AXIS_CHAINS && sym->source != VBC_AXIS_SYMMETRY) ||
        sym->chains < 3)
        return 0;
    int k = chain_centroids(s, cx, cy, cz, count, &lo, &hi, names), n = 0;
    for (int c = 0; c < k && n < max; c++, n++) {
        vbc_axis b;
        out[n] = *sym;
        out[n].c[0] = cx[c];
        out[n].c[1] = cy[c];
        out[n].c[2] = cz[c];
        snprintf(out[n].why, sizeof out[n].why, "chain %.7s's centroid, parallel to the %.16s axis",
                 names[c][0] ? names[c] : "_", vbc_axis_source_name(sym->source));
        /* A subunit that is a barrel (a porin monomer): its own axis, when
         * it runs along the oligomer's (within 30 degrees). */
        if (vbc_axis_barrel(s, names[c], &b) &&
            fabs(b.u[0] * sym->u[0] + b.u[1] * sym->u[1] + b.u[2] * sym->u[2]) > cos(acos(-1.0) / 6.0))
        {
            out[n] = b;
            size_t w = strlen(out[n].why);
            snprintf(out[n].why + w, sizeof out[n].why - w, ", a subunit on the %s axis",
                     vbc_axis_source_name(sym->source));
        }
        out[n].source = VBC_AXIS_SUBUNIT;
        out[n].chains = c + 1;
    }
    return n;
}

int vbc_axis_from_chains(const vb_sphere_set *s, vbc_axis *out)
{
    double cx[MAX_CHAINS], cy[MAX_CHAINS], cz[MAX_CHAINS];
    size_t count[MAX_CHAINS], lo, hi;
    char names[MAX_CHAINS][8];
    if (!s->info || s->n == 0)
        return 0;
    int k = chain_centroids(s, cx, cy, cz, count, &lo, &hi, names);
    if (k < 2 || (double)hi > 1.25 * (double)lo)
        return 0;
    double m[3], cov[3][3], w[3], v[3][3];
    covariance((size_t)k, cx, cy, cz, m, cov);
    memset(out, 0, sizeof *out);
    out->source = VBC_AXIS_CHAINS;
    out->chains = k;
    memcpy(out->c, m, sizeof m);
    if (k == 2) {
        double d[3] = {cx[1] - cx[0], cy[1] - cy[0], cz[1] - cz[0]};
        double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(len > 0.0))
            return 0;
        for (int a = 0; a < 3; a++)
            out->u[a] = d[a] / len;
        /* Stacked, not side by side: the centroids are far apart along the line. */
        double elo = INFINITY, ehi = -INFINITY;
        for (size_t i = 0; i < s->n; i++) {
            double t = s->x[i] * out->u[0] + s->y[i] * out->u[1] + s->z[i] * out->u[2];
            elo = fmin(elo, t);
            ehi = fmax(ehi, t);
        }
        if (len < 0.4 * (ehi - elo))
            return 0;
        vbc_axis_orient(out->u);
        snprintf(out->why, sizeof out->why, "line through the centroids of 2 stacked chains %s,%s",
                 names[0][0] ? names[0] : "_", names[1][0] ? names[1] : "_");
        return 1;
    }
    double dmin = INFINITY, dmax = 0.0;
    for (int c = 0; c < k; c++) {
        double d = sqrt((cx[c] - m[0]) * (cx[c] - m[0]) + (cy[c] - m[1]) * (cy[c] - m[1]) +
                        (cz[c] - m[2]) * (cz[c] - m[2]));
        dmin = fmin(dmin, d);
        dmax = fmax(dmax, d);
    }
    if (!(dmin > 0.0) || dmax > 1.35 * dmin)
        return 0;
    vbc_eigen3((const double (*)[3])cov, w, v);
    for (int a = 0; a < 3; a++)
        out->u[a] = v[a][2];
    vbc_axis_orient(out->u);
    snprintf(out->why, sizeof out->why, "normal of the centroids of %d chains of similar size", k);
    return 1;
}

int vbc_axis_refit(const vb_sphere_set *s, const vbc_axis *first, vbc_axis *out)
{
    int ok = 0;
    switch (first->source) {
    case VBC_AXIS_SYMMETRY: ok = vbc_axis_symmetry(s, out); break;
    case VBC_AXIS_CHAINS: ok = vbc_axis_from_chains(s, out); break;
    case VBC_AXIS_BARREL: ok = vbc_axis_barrel(s, NULL, out); break;
    case VBC_AXIS_SUBUNIT: {
        vbc_axis sym, sub[16];
        if (vbc_axis_symmetry(s, &sym) || vbc_axis_from_chains(s, &sym)) {
            int n = vbc_axis_subunits(s, &sym, sub, 16);
            if (first->chains >= 1 && first->chains <= n) {
                *out = sub[first->chains - 1];
                ok = 1;
            }
        }
        break;
    }
    case VBC_AXIS_PRINCIPAL: {
        vbc_axis p[3];
        vbc_axis_principal(s, p);
        int best = 0;
        for (int k = 1; k < 3; k++)
            if (fabs(p[k].u[0] * first->u[0] + p[k].u[1] * first->u[1] + p[k].u[2] * first->u[2]) >
                fabs(p[best].u[0] * first->u[0] + p[best].u[1] * first->u[1] + p[best].u[2] * first->u[2]))
                best = k;
        *out = p[best];
        ok = 1;
        break;
    }
    default: break;
    }
    if (!ok)
        return 0;
    if (out->u[0] * first->u[0] + out->u[1] * first->u[1] + out->u[2] * first->u[2] < 0.0)
        for (int k = 0; k < 3; k++)
            out->u[k] = -out->u[k];
    return 1;
}
