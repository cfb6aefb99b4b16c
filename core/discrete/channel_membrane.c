/* The membrane's normal as the pore's first axis candidate (vbc_pore.h):
 * from the membrane atoms that --membrane leaves out, before they go. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "vbc_pore.h"

/* Which of the membrane's atoms give its planes: OPM's dummy atoms, else
 * the lipids' head-group phosphorus, else every membrane atom. */
enum { PICK_DUM, PICK_P, PICK_ALL };

static int is_membrane(const vb_atom_info *a, const char *const *names, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (strcasecmp(a->resname, names[k]) == 0)
            return 1;
    return 0;
}

static int picked(const vb_atom_info *a, int pick)
{
    return pick == PICK_ALL ||
           (pick == PICK_DUM ? strcasecmp(a->resname, "DUM") == 0 : strcmp(a->name, "P") == 0);
}

/* Adds to cov the scatter about their own mean of the n points p (xyz)
 * on side `side` of the plane through m normal to d (side 0: all). */
static void half_scatter(const double *p, size_t n, const double m[3], const double d[3], int side,
                         double mean[3], double cov[3][3])
{
    size_t k = 0;
    mean[0] = mean[1] = mean[2] = 0.0;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t i = 0; i < n; i++) {
            const double *q = p + 3 * i;
            double t = (q[0] - m[0]) * d[0] + (q[1] - m[1]) * d[1] + (q[2] - m[2]) * d[2];
            if (side != 0 && (side > 0 ? !(t >= 0.0) : !(t < 0.0)))
                continue;
            if (pass == 0) {
                k++;
                for (int a = 0; a < 3; a++)
                    mean[a] += q[a];
            } else {
                for (int a = 0; a < 3; a++)
                    for (int b = 0; b < 3; b++)
                        cov[a][b] += (q[a] - mean[a]) * (q[b] - mean[b]);
            }
        }
        if (k == 0)
            return;
        if (pass == 0)
            for (int a = 0; a < 3; a++)
                mean[a] /= (double)k;
    }
}

int vbc_membrane_normal(const vb_sphere_set *s, const char *const *names, size_t n, vbc_axis *out)
{
    if (!s->info || n == 0)
        return 0;
    size_t count[3] = {0, 0, 0};
    uint8_t *mem = calloc(s->n ? s->n : 1, 1);
    if (!mem)
        return -1;
    for (size_t i = 0; i < s->n; i++)
        if ((mem[i] = (uint8_t)is_membrane(&s->info[i], names, n)))
            for (int pick = 0; pick < 3; pick++)
                count[pick] += (size_t)picked(&s->info[i], pick);
    int pick = count[PICK_DUM] >= VBC_MEMBRANE_MIN_ATOMS ? PICK_DUM
             : count[PICK_P] >= VBC_MEMBRANE_MIN_ATOMS   ? PICK_P
                                                         : PICK_ALL;
    size_t np = count[pick];
    double *p = np >= VBC_MEMBRANE_MIN_ATOMS ? malloc(3 * np * sizeof *p) : NULL;
    if (!p) {
        free(mem);
        return np >= VBC_MEMBRANE_MIN_ATOMS ? -1 : 0;
    }
    for (size_t i = 0, k = 0; i < s->n; i++)
        if (mem[i] && picked(&s->info[i], pick)) {
            p[3 * k] = s->x[i];
            p[3 * k + 1] = s->y[i];
            p[3 * k + 2] = s->z[i];
            k++;
        }
    free(mem);
    /* Each principal axis of the points splits them through their mean;
     * the split whose two halves (the leaflets) are flattest gives the
     * normal: their least axis (one plane of atoms stays flat whatever
     * the split). */
    double zero[3] = {0.0, 0.0, 0.0}, mean[3], cov[3][3] = {{0.0}}, w[3], v[3][3];
    half_scatter(p, np, zero, zero, 0, mean, cov);
    vbc_eigen3((const double(*)[3])cov, w, v);
    double bw[3] = {INFINITY, INFINITY, INFINITY}, bu[3] = {0.0, 0.0, 1.0};
    for (int j = 0; j < 3; j++) {
        double d[3] = {v[0][j], v[1][j], v[2][j]}, c[3][3] = {{0.0}}, m2[3], wj[3], vj[3][3];
        half_scatter(p, np, mean, d, -1, m2, c);
        half_scatter(p, np, mean, d, 1, m2, c);
        vbc_eigen3((const double(*)[3])c, wj, vj);
        if (wj[2] < bw[2]) {
            memcpy(bw, wj, sizeof bw);
            for (int a = 0; a < 3; a++)
                bu[a] = vj[a][2];
        }
    }
    free(p);
    /* Flat: the leaflets' spread along the normal well below their spread
     * along the plane; wide: a patch, not a few lipids bound to a protein. */
    if (!(bw[2] < VBC_MEMBRANE_FLAT * bw[1]) ||
        !(bw[1] >= VBC_MEMBRANE_MIN_RMS * VBC_MEMBRANE_MIN_RMS * (double)np))
        return 0;
    memset(out, 0, sizeof *out);
    /* The Jacobi rotations' round-off (1e-17) off the axes' zeros: a
     * membrane normal to z reads 0, 0, 1 (not -0.00000). */
    double nn = 0.0;
    for (int a = 0; a < 3; a++) {
        out->u[a] = fabs(bu[a]) < 1e-12 ? 0.0 : bu[a];
        nn += out->u[a] * out->u[a];
    }
    for (int a = 0; a < 3; a++)
        out->u[a] /= sqrt(nn);
    vbc_axis_orient(out->u);
    out->source = VBC_AXIS_MEMBRANE;
    snprintf(out->why, sizeof out->why, "membrane normal (%zu %s atoms; leaflets' rms %.1f A)", np,
             pick == PICK_DUM ? "DUM" : pick == PICK_P ? "lipid P" : "membrane",
             sqrt(bw[2] / (double)np));
    return 1;
}
