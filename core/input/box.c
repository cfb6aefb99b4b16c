/* Periodic boxes from vectors, from lengths and angles, and from --box. */
#include "vb_box.h"

#include <gmp.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_decimal_mpz.h"


/* 0: a box; 1: a component out of range; 2: flat (decided exactly). */
static int box_check(const vb_decimal ev[9])
{
    int32_t emin = INT32_MAX;
    for (int k = 0; k < 9; k++) {
        if (ev[k].mant == 0)
            continue;
        emin = ev[k].exp10 < emin ? ev[k].exp10 : emin;
        /* An image coordinate adds a few multiples of these to an atom's:
         * both must fit vb_decimal's 18 digits at a common exponent. */
        if (ev[k].exp10 > 12 || ev[k].exp10 < -12)
            return 1;
    }
    if (emin == INT32_MAX)
        return 2;
    /* The determinant, exactly, on the integers ev * 10^-emin. */
    mpz_t m[9], t, u, det;
    for (int k = 0; k < 9; k++)
        mpz_init(m[k]);
    mpz_inits(t, u, det, NULL);
    for (int k = 0; k < 9; k++)
        if (ev[k].mant != 0)
            vb_decimal_to_mpz(m[k], ev[k], emin, t);
    static const int perm[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                   {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
    for (int p = 0; p < 6; p++) {
        mpz_mul(u, m[0 + perm[p][0]], m[3 + perm[p][1]]);
        mpz_mul(u, u, m[6 + perm[p][2]]);
        if (p < 3)
            mpz_add(det, det, u);
        else
            mpz_sub(det, det, u);
    }
    int sign = mpz_sgn(det);
    for (int k = 0; k < 9; k++)
        mpz_clear(m[k]);
    mpz_clears(t, u, det, NULL);
    return sign == 0 ? 2 : 0;
}

static void box_set(const vb_decimal ev[9], vb_box *out)
{
    for (int k = 0; k < 9; k++) {
        out->ev[k] = ev[k];
        out->v[k] = vb_decimal_double(ev[k]);
    }
}

int vb_box_try(const vb_decimal ev[9], vb_box *out)
{
    if (box_check(ev) != 0)
        return 0;
    box_set(ev, out);
    return 1;
}

int vb_box_from_vectors(vb_ctx *ctx, const vb_decimal ev[9], const char *file, long line,
                        vb_box *out)
{
    int c = box_check(ev);
    if (c == 1)
        return vb_error(ctx, VB_EINPUT_BOX, file, line,
                        "a box component has an exponent beyond 1e-12 .. 1e12");
    if (c == 2)
        return vb_error(ctx, VB_EINPUT_BOX, file, line,
                        "the box vectors are linearly dependent (a flat box)");
    box_set(ev, out);
    return VB_OK;
}

/* The decimal of 6 places nearest a double (the derived vectors of a box
 * given by angles). */
static int six_places(double v, vb_decimal *out)
{
    char buf[64];
    snprintf(buf, sizeof buf, "%.6f", v == 0.0 ? 0.0 : v);
    return vb_decimal_parse(buf, strlen(buf), out, NULL);
}

int vb_box_from_cell(vb_ctx *ctx, const vb_decimal len[3], const vb_decimal deg[3],
                     const char *file, long line, vb_box *out)
{
    const vb_decimal zero = {0, 0}, right = {9, 1}, straight = {18, 1};
    for (int k = 0; k < 3; k++) {
        if (vb_decimal_cmp(len[k], zero) <= 0)
            return vb_error(ctx, VB_EINPUT_BOX, file, line, "box edge length <= 0");
        if (vb_decimal_cmp(deg[k], zero) <= 0 || vb_decimal_cmp(deg[k], straight) >= 0)
            return vb_error(ctx, VB_EINPUT_BOX, file, line, "box angle outside (0, 180) degrees");
    }
    vb_decimal ev[9];
    for (int k = 0; k < 9; k++)
        ev[k] = zero;
    if (vb_decimal_cmp(deg[0], right) == 0 && vb_decimal_cmp(deg[1], right) == 0 &&
        vb_decimal_cmp(deg[2], right) == 0) {
        ev[0] = len[0];
        ev[4] = len[1];
        ev[8] = len[2];
        return vb_box_from_vectors(ctx, ev, file, line, out);
    }
    double a = vb_decimal_double(len[0]), b = vb_decimal_double(len[1]), c = vb_decimal_double(len[2]);
    const double rad = 3.14159265358979323846 / 180.0;
    double ca = cos(vb_decimal_double(deg[0]) * rad), cb = cos(vb_decimal_double(deg[1]) * rad);
    double cg = cos(vb_decimal_double(deg[2]) * rad), sg = sin(vb_decimal_double(deg[2]) * rad);
    double cy = (ca - cb * cg) / sg, zz = 1.0 - cb * cb - cy * cy;
    if (!(zz > 0.0))
        return vb_error(ctx, VB_EINPUT_BOX, file, line, "box angles that make no cell");
    double v[9] = {a, 0.0, 0.0, b * cg, b * sg, 0.0, c * cb, c * cy, c * sqrt(zz)};
    for (int k = 0; k < 9; k++)
        if (six_places(v[k], &ev[k]) != VB_OK)
            return vb_error(ctx, VB_EINPUT_BOX, file, line, "box component %g out of range", v[k]);
    return vb_box_from_vectors(ctx, ev, file, line, out);
}

int vb_box_parse_args(vb_ctx *ctx, const char *const *tok, int n, vb_box *out)
{
    if (n != 3 && n != 6 && n != 9)
        return vb_error(ctx, VB_EINPUT_BOX, NULL, 0,
                        "--box takes 3 numbers (a b c), 6 (a b c alpha beta gamma) or 9 "
                        "(the vectors a, b, c), not %d",
                        n);
    vb_decimal d[9];
    for (int k = 0; k < n; k++)
        if (vb_decimal_parse(tok[k], strlen(tok[k]), &d[k], NULL) != VB_OK)
            return vb_error(ctx, VB_EINPUT_BOX, NULL, 0, "--box: '%s' is not a number", tok[k]);
    if (n == 9)
        return vb_box_from_vectors(ctx, d, "--box", 0, out);
    vb_decimal ang[3] = {{9, 1}, {9, 1}, {9, 1}};
    if (n == 6)
        memcpy(ang, d + 3, sizeof ang);
    return vb_box_from_cell(ctx, d, ang, "--box", 0, out);
}

void vb_box_inverse(const vb_box *box, double inv[9])
{
    /* Rows a, b, c: p = f A with A's rows the vectors, so f = p A^-1. */
    const double *m = box->v;
    double c00 = m[4] * m[8] - m[5] * m[7], c01 = m[5] * m[6] - m[3] * m[8];
    double c02 = m[3] * m[7] - m[4] * m[6];
    double det = m[0] * c00 + m[1] * c01 + m[2] * c02;
    inv[0] = c00 / det;
    inv[3] = c01 / det;
    inv[6] = c02 / det;
    inv[1] = (m[2] * m[7] - m[1] * m[8]) / det;
    inv[4] = (m[0] * m[8] - m[2] * m[6]) / det;
    inv[7] = (m[1] * m[6] - m[0] * m[7]) / det;
    inv[2] = (m[1] * m[5] - m[2] * m[4]) / det;
    inv[5] = (m[2] * m[3] - m[0] * m[5]) / det;
    inv[8] = (m[0] * m[4] - m[1] * m[3]) / det;
}
