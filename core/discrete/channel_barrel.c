/* The axis of a beta-barrel (vbc_axis_barrel, vbc_pore.h): the cylinder
 * that the C-alpha atoms of its strands lie on. A porin's principal axis
 * can lie 40 degrees off its barrel (the loops and the membrane belt are
 * not symmetric about it); the strands are. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vbc_pore.h"

typedef struct {
    double spread; /* rms of the radii over their mean */
    double radius;
    double centre[2];
} circle_fit;

/* Two unit vectors normal to u and to each other. */
static void plane_basis(const double u[3], double e1[3], double e2[3])
{
    double a[3] = {0.0, 0.0, 0.0};
    a[fabs(u[0]) < 0.6 ? 0 : fabs(u[1]) < 0.6 ? 1 : 2] = 1.0;
    double d = a[0] * u[0] + a[1] * u[1] + a[2] * u[2], n = 0.0;
    for (int k = 0; k < 3; k++) {
        e1[k] = a[k] - d * u[k];
        n += e1[k] * e1[k];
    }
    n = sqrt(n);
    for (int k = 0; k < 3; k++)
        e1[k] /= n;
    e2[0] = u[1] * e1[2] - u[2] * e1[1];
    e2[1] = u[2] * e1[0] - u[0] * e1[2];
    e2[2] = u[0] * e1[1] - u[1] * e1[0];
}

/* Solves the 3x3 system a x = b by Gaussian elimination with pivoting;
 * 0 when singular. */
static int solve3(double a[3][3], double b[3], double x[3])
{
    for (int c = 0; c < 3; c++) {
        int p = c;
        for (int r = c + 1; r < 3; r++)
            if (fabs(a[r][c]) > fabs(a[p][c]))
                p = r;
        if (!(fabs(a[p][c]) > 1e-12))
            return 0;
        for (int k = 0; k < 3; k++) {
            double t = a[c][k];
            a[c][k] = a[p][k];
            a[p][k] = t;
        }
        double t = b[c];
        b[c] = b[p];
        b[p] = t;
        for (int r = c + 1; r < 3; r++) {
            double f = a[r][c] / a[c][c];
            for (int k = c; k < 3; k++)
                a[r][k] -= f * a[c][k];
            b[r] -= f * b[c];
        }
    }
    for (int r = 2; r >= 0; r--) {
        double t = b[r];
        for (int k = r + 1; k < 3; k++)
            t -= a[r][k] * x[k];
        x[r] = t / a[r][r];
    }
    return 1;
}

/* The normal equations of Kasa's algebraic fit (x^2 + y^2 + D x + E y + F
 * = 0 in least squares) of the n points p (xyz triples) projected on the
 * plane (e1, e2), summed in point order. */
static void normal_sums(const double *p, size_t n, const double e1[3], const double e2[3],
                        double a[3][3], double b[3])
{
    memset(a, 0, 9 * sizeof **a);
    memset(b, 0, 3 * sizeof *b);
    for (size_t i = 0; i < n; i++) {
        const double *q = p + 3 * i;
        double X = q[0] * e1[0] + q[1] * e1[1] + q[2] * e1[2];
        double Y = q[0] * e2[0] + q[1] * e2[1] + q[2] * e2[2];
        double row[3] = {X, Y, 1.0}, rhs = -(X * X + Y * Y);
        for (int r = 0; r < 3; r++) {
            for (int c = 0; c < 3; c++)
                a[r][c] += row[r] * row[c];
            b[r] += row[r] * rhs;
        }
    }
}

/* normal_sums of two planes at once: with GNU C vectors each plane is a
 * lane that takes normal_sums' operations in its order (IEEE double, no
 * contraction; a product by 1.0 is exact either way), so the same sums. */
static void normal_sums2(const double *p, size_t n, const double e1[2][3], const double e2[2][3],
                         double a[2][3][3], double b[2][3])
{
#if defined(__GNUC__)
    typedef double v2 __attribute__((vector_size(16)));
    v2 A[3][3], B[3], E1[3], E2[3];
    for (int r = 0; r < 3; r++) {
        B[r] = (v2){0.0, 0.0};
        E1[r] = (v2){e1[0][r], e1[1][r]};
        E2[r] = (v2){e2[0][r], e2[1][r]};
        for (int c = 0; c < 3; c++)
            A[r][c] = (v2){0.0, 0.0};
    }
    for (size_t i = 0; i < n; i++) {
        const double *q = p + 3 * i;
        v2 X = q[0] * E1[0] + q[1] * E1[1] + q[2] * E1[2];
        v2 Y = q[0] * E2[0] + q[1] * E2[1] + q[2] * E2[2];
        v2 row[3] = {X, Y, {1.0, 1.0}}, rhs = -(X * X + Y * Y);
        for (int r = 0; r < 3; r++) {
            for (int c = 0; c < 3; c++)
                A[r][c] += row[r] * row[c];
            B[r] += row[r] * rhs;
        }
    }
    for (int l = 0; l < 2; l++)
        for (int r = 0; r < 3; r++) {
            b[l][r] = B[r][l];
            for (int c = 0; c < 3; c++)
                a[l][r][c] = A[r][c][l];
        }
#else
    for (int l = 0; l < 2; l++)
        normal_sums(p, n, e1[l], e2[l], a[l], b[l]);
#endif
}

/* The circle closest to the projections of the n points p (xyz triples,
 * relative to their mean) on the plane (e1, e2) normal to a direction,
 * from its normal sums a, b (normal_sums). spread INFINITY when
 * degenerate or when the points leave a 45-degree sector of the circle
 * empty (a sheet, not a barrel), and also when the spread is not below
 * `beat` (the sectors then go unchecked: the caller keeps only a fit that
 * beats its best, so it takes the same fits; the search spent 8% of the
 * maltoporin trimer's CPU on their atan2 before, issue 32). */
static circle_fit circle_finish(const double *p, size_t n, const double e1[3], const double e2[3],
                                double a[3][3], double b[3], double beat)
{
    circle_fit f = {INFINITY, 0.0, {0.0, 0.0}};
    double x[3];
    if (!solve3(a, b, x))
        return f;
    double cx = -x[0] / 2.0, cy = -x[1] / 2.0;
    double sum = 0.0, sum2 = 0.0;
    for (size_t i = 0; i < n; i++) {
        const double *q = p + 3 * i;
        double X = q[0] * e1[0] + q[1] * e1[1] + q[2] * e1[2] - cx;
        double Y = q[0] * e2[0] + q[1] * e2[1] + q[2] * e2[2] - cy;
        double r = sqrt(X * X + Y * Y);
        sum += r;
        sum2 += r * r;
    }
    double mean = sum / (double)n, var = sum2 / (double)n - mean * mean;
    if (!(mean > 0.0))
        return f;
    double spread = sqrt(fmax(var, 0.0)) / mean;
    if (!(spread < beat))
        return f;
    unsigned sectors = 0;
    for (size_t i = 0; i < n && sectors != 0xffu; i++) {
        const double *q = p + 3 * i;
        double X = q[0] * e1[0] + q[1] * e1[1] + q[2] * e1[2] - cx;
        double Y = q[0] * e2[0] + q[1] * e2[1] + q[2] * e2[2] - cy;
        int sec = (int)floor((atan2(Y, X) + acos(-1.0)) / (acos(-1.0) / 4.0));
        sectors |= 1u << (sec & 7);
    }
    if (sectors != 0xffu)
        return f;
    f.spread = spread;
    f.radius = mean;
    f.centre[0] = cx;
    f.centre[1] = cy;
    return f;
}

/* The fit along u (circle_finish of the plane normal to it). */
static circle_fit circle_along(const double *p, size_t n, const double u[3], double beat)
{
    double e1[3], e2[3], a[3][3], b[3];
    plane_basis(u, e1, e2);
    normal_sums(p, n, e1, e2, a, b);
    return circle_finish(p, n, e1, e2, a, b, beat);
}

/* circle_along of two directions with one beat: their sums side by side. */
static void circle_along2(const double *p, size_t n, const double u[2][3], double beat,
                          circle_fit f[2])
{
    double e1[2][3], e2[2][3], a[2][3][3], b[2][3];
    for (int l = 0; l < 2; l++)
        plane_basis(u[l], e1[l], e2[l]);
    normal_sums2(p, n, (const double (*)[3])e1, (const double (*)[3])e2, a, b);
    for (int l = 0; l < 2; l++)
        f[l] = circle_finish(p, n, e1[l], e2[l], a[l], b[l], beat);
}

/* The chain with most C-alpha atoms, written to name; 0 when none. */
static int largest_chain(const vb_sphere_set *s, char name[8])
{
    char names[64][8];
    size_t count[64];
    int nc = 0, best = -1;
    for (size_t i = 0; i < s->n; i++) {
        if (strcmp(s->info[i].name, "CA") != 0)
            continue;
        int c = 0;
        while (c < nc && strcmp(names[c], s->info[i].chain) != 0)
            c++;
        if (c == nc) {
            if (nc == 64)
                return 0;
            snprintf(names[nc], sizeof names[nc], "%s", s->info[i].chain);
            count[nc++] = 0;
        }
        count[c]++;
    }
    for (int c = 0; c < nc; c++)
        if (best < 0 || count[c] > count[best])
            best = c;
    if (best < 0)
        return 0;
    memcpy(name, names[best], 8);
    return 1;
}

/* The extended C-alpha atoms of the chain (xyz triples relative to their
 * mean, in *mean); returns how many, or 0. */
static size_t strand_atoms(const vb_sphere_set *s, const char *chain, double **out, double mean[3])
{
    size_t nca = 0, n = 0;
    for (size_t i = 0; i < s->n; i++)
        nca += strcmp(s->info[i].name, "CA") == 0 && strcmp(s->info[i].chain, chain) == 0;
    size_t *ca = malloc((nca + 1) * sizeof *ca);
    double *p = malloc(3 * (nca + 1) * sizeof *p);
    if (!ca || !p) {
        free(ca);
        free(p);
        return 0;
    }
    nca = 0;
    for (size_t i = 0; i < s->n; i++)
        if (strcmp(s->info[i].name, "CA") == 0 && strcmp(s->info[i].chain, chain) == 0)
            ca[nca++] = i;
    mean[0] = mean[1] = mean[2] = 0.0;
    /* Runs of at least VBC_BARREL_MIN_RUN extended atoms: the strands, not
     * the extended turns of the loops. */
    size_t run = 0;
    for (size_t k = 1; k <= nca; k++) {
        int ext = 0;
        if (k + 1 < nca) {
            size_t a = ca[k - 1], b = ca[k + 1];
            double dx = s->x[b] - s->x[a], dy = s->y[b] - s->y[a], dz = s->z[b] - s->z[a];
            /* i-1 to i+1 across a chain break is no strand. */
            ext = s->info[b].resseq - s->info[a].resseq == 2 &&
                  sqrt(dx * dx + dy * dy + dz * dz) > VBC_BARREL_EXTENDED;
        }
        if (ext) {
            run++;
            continue;
        }
        for (size_t j = k - run; run >= VBC_BARREL_MIN_RUN && j < k; j++) {
            size_t i = ca[j];
            p[3 * n] = s->x[i];
            p[3 * n + 1] = s->y[i];
            p[3 * n + 2] = s->z[i];
            for (int d = 0; d < 3; d++)
                mean[d] += p[3 * n + d];
            n++;
        }
        run = 0;
    }
    free(ca);
    for (int d = 0; d < 3 && n; d++)
        mean[d] /= (double)n;
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 3; d++)
            p[3 * i + d] -= mean[d];
    *out = p;
    return n;
}

/* Direction i of a Fibonacci lattice of m points on the upper hemisphere. */
static void lattice_direction(size_t i, size_t m, double u[3])
{
    double z = 1.0 - ((double)i + 0.5) / (double)m;
    double r = sqrt(fmax(0.0, 1.0 - z * z)), phi = (double)i * 2.399963229728653;
    u[0] = r * cos(phi);
    u[1] = r * sin(phi);
    u[2] = z;
}

int vbc_axis_barrel(const vb_sphere_set *s, const char *chain, vbc_axis *out)
{
    char name[8];
    if (!s->info || s->n == 0)
        return 0;
    if (chain)
        snprintf(name, sizeof name, "%s", chain);
    else if (!largest_chain(s, name))
        return 0;
    double *p = NULL, mean[3];
    size_t n = strand_atoms(s, name, &p, mean);
    if (n < VBC_BARREL_MIN_CA) {
        free(p);
        return 0;
    }
    /* A coarse search (about 3 degrees apart), then steps halving to 0.001
     * degree around the best: deterministic, no start to get wrong. */
    double best[3] = {0.0, 0.0, 1.0};
    circle_fit bf = {INFINITY, 0.0, {0.0, 0.0}};
    const size_t m = 2400;
    /* Two directions at a time, judged in order. The second's fit is
     * made with the best spread before the first's: a beat only spares
     * the sectors of a fit no better than it, and the test below turns
     * down every fit not better than the best at its turn, so the same
     * fits win as one at a time. */
    for (size_t i = 0; i < m; i += 2) {
        double u[2][3];
        circle_fit f[2];
        int two = i + 1 < m;
        lattice_direction(i, m, u[0]);
        if (two) {
            lattice_direction(i + 1, m, u[1]);
            circle_along2(p, n, (const double (*)[3])u, bf.spread, f);
        } else {
            f[0] = circle_along(p, n, u[0], bf.spread);
        }
        for (int l = 0; l <= two; l++)
            if (f[l].spread < bf.spread) {
                bf = f[l];
                memcpy(best, u[l], sizeof best);
            }
    }
    for (double step = 0.05; step > 2e-5 && isfinite(bf.spread); step *= 0.5) {
        int moved = 1;
        while (moved) {
            moved = 0;
            double e1[3], e2[3];
            plane_basis(best, e1, e2);
            for (int k = 0; k < 4; k++) {
                const double *e = k < 2 ? e1 : e2;
                double sg = k % 2 ? -step : step, u[3], len = 0.0;
                for (int d = 0; d < 3; d++) {
                    u[d] = best[d] + sg * e[d];
                    len += u[d] * u[d];
                }
                for (int d = 0; d < 3; d++)
                    u[d] /= sqrt(len);
                circle_fit f = circle_along(p, n, u, bf.spread - 1e-12);
                if (f.spread < bf.spread - 1e-12) {
                    bf = f;
                    memcpy(best, u, sizeof best);
                    moved = 1;
                    break;
                }
            }
        }
    }
    free(p);
    if (!(bf.spread < VBC_BARREL_MAX_SPREAD) || bf.radius < 5.0 || bf.radius > 40.0)
        return 0;
    memset(out, 0, sizeof *out);
    double e1[3], e2[3];
    plane_basis(best, e1, e2);
    for (int d = 0; d < 3; d++)
        out->c[d] = mean[d] + bf.centre[0] * e1[d] + bf.centre[1] * e2[d];
    memcpy(out->u, best, sizeof best);
    vbc_axis_orient(out->u);
    out->source = VBC_AXIS_BARREL;
    snprintf(out->why, sizeof out->why, "beta-barrel of chain %s (%zu strand CA, radius %.1f A, spread %.2f)",
             name[0] ? name : "_", n, bf.radius, bf.spread);
    return 1;
}
