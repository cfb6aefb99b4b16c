/* The caps stage's point filters (verify/measures/vbm_caps_cut.h) against
 * exact values and against the interval tests they stand before, on
 * random caps built as stokes_cell.c builds them and on bisector caps and
 * cap pairs placed at a relative distance 2^-60 .. 2^-20 from the tests'
 * boundaries (both sides) and further off:
 * - where vbm_cut_keep_fast says 1, at its point p (the inputs' lower
 *   ends) the larger gap G is <= 0 or G^2 <= sa2 (nn - (e.n)^2) exactly
 *   (MPFR, 8000 bits: every product and sum of these doubles exact), and
 *   vbm_cut_test returns 0 (the same decision: stokes_cell.c's bytes);
 * - where vbm_caps_meet_fast says 1, at p sin(r1 + r2) <= 0 or e1.e2 >=
 *   cos(r1 + r2) exactly, and vbm_caps_apart returns 0;
 * - the filters decide at least 99 % of the cases at 2^-30 or further off
 *   where the interval test fails (a filter that never decides would keep
 *   the bytes and lose the point of it).
 * A margin 2^-60 in place of 2^-40 (VBM_CUT_MARGIN) fails the exact
 * checks on the cases next to the boundaries. */
#include <math.h>
#include <mpfr.h>
#include <stdint.h>

#include "vbm_caps_cut.h"
#include "vb_test.h"

#define PREC 8000

static uint64_t seed = 54321;

static double rnd(void)
{
    seed = seed * 6364136223846793005u + 1442695040888963407u;
    return (double)(seed >> 11) / 9007199254740992.0;
}

/* An interval around v: a point, or a few ulps wide. */
static vbx_ia around(double v)
{
    if (rnd() < 0.5)
        return vbx_ia_point(v);
    vbx_ia r = {vbx_pred(vbx_pred(v)), vbx_succ(v)};
    return r;
}

/* A cap as vbm_cell_stokes makes one: d a random vector of length D in
 * (1, 8), k in (-D, D): e = d / D, ca = k / D, sa = sqrt(1 - ca^2). */
static void random_cap(vbx_ia *e, vbx_ia *ca, vbx_ia *sa)
{
    vbx_ia d[3];
    for (int i = 0; i < 3; i++)
        d[i] = around((rnd() * 2.0 - 1.0) * 8.0);
    vbx_ia D = vbx_ia_sqrt(vbm_dot3(d, d));
    if (!(D.lo > 0.5)) {
        d[0] = vbx_ia_point(3.0);
        D = vbx_ia_sqrt(vbm_dot3(d, d));
    }
    vbx_ia k = vbx_ia_mul(D, around(rnd() * 1.9 - 0.95));
    for (int i = 0; i < 3; i++)
        e[i] = vbx_ia_div(d[i], D);
    *ca = vbx_ia_div(k, D);
    *sa = vbx_ia_sqrt(vbx_ia_sub(vbx_ia_point(1.0), vbx_ia_sqr(*ca)));
}

/* A relative offset from a boundary: +-2^-j, j in 20 .. 60, or 0.3. */
static double offset(int *far)
{
    double s = rnd() < 0.5 ? -1.0 : 1.0;
    if (rnd() < 0.2) {
        *far = 1;
        return s * 0.3;
    }
    int j = 20 + (int)(rnd() * 41.0);
    *far = j <= 30;
    return s * ldexp(1.0, -j);
}

static mpfr_t t1, t2, t3, en, G, s2;

/* x = sum a[i] b[i] (i < 3), exactly. */
static void dot_exact(mpfr_t x, const double *a, const double *b)
{
    mpfr_set_d(x, 0.0, MPFR_RNDN);
    for (int i = 0; i < 3; i++) {
        mpfr_set_d(t1, a[i], MPFR_RNDN);
        mpfr_mul_d(t1, t1, b[i], MPFR_RNDN);
        mpfr_add(x, x, t1, MPFR_RNDN);
    }
}

/* At p: G <= 0 or G^2 <= sa2 (nn - (e.n)^2), exactly. */
static int keep_exact(const vbx_ia *e, vbx_ia ca, vbx_ia sa2, const vbx_ia *n, vbx_ia h, vbx_ia nn)
{
    double ep[3] = {e[0].lo, e[1].lo, e[2].lo}, np[3] = {n[0].lo, n[1].lo, n[2].lo};
    dot_exact(en, ep, np);
    mpfr_mul_d(t1, en, ca.lo, MPFR_RNDN); /* ca e.n */
    mpfr_min(t2, t1, en, MPFR_RNDN);
    mpfr_sub_d(t2, t2, h.lo, MPFR_RNDN);  /* min - h */
    mpfr_max(t3, t1, en, MPFR_RNDN);
    mpfr_d_sub(t3, h.lo, t3, MPFR_RNDN);  /* h - max */
    mpfr_max(G, t2, t3, MPFR_RNDN);
    if (mpfr_sgn(G) <= 0)
        return 1;
    mpfr_sqr(t1, en, MPFR_RNDN);
    mpfr_d_sub(t1, nn.lo, t1, MPFR_RNDN);
    mpfr_mul_d(s2, t1, sa2.lo, MPFR_RNDN);
    mpfr_sqr(G, G, MPFR_RNDN);
    return mpfr_cmp(G, s2) <= 0;
}

/* At p: sin(r1 + r2) <= 0 or e1.e2 >= cos(r1 + r2), exactly. */
static int meet_exact(const vbx_ia *e1, vbx_ia c1, vbx_ia s1, const vbx_ia *e2, vbx_ia c2,
                      vbx_ia s2v)
{
    mpfr_set_d(t1, s1.lo, MPFR_RNDN);
    mpfr_mul_d(t1, t1, c2.lo, MPFR_RNDN);
    mpfr_set_d(t2, c1.lo, MPFR_RNDN);
    mpfr_mul_d(t2, t2, s2v.lo, MPFR_RNDN);
    mpfr_add(t3, t1, t2, MPFR_RNDN);
    if (mpfr_sgn(t3) <= 0)
        return 1;
    double a[3] = {e1[0].lo, e1[1].lo, e1[2].lo}, b[3] = {e2[0].lo, e2[1].lo, e2[2].lo};
    dot_exact(en, a, b);
    mpfr_set_d(t1, c1.lo, MPFR_RNDN);
    mpfr_mul_d(t1, t1, c2.lo, MPFR_RNDN);
    mpfr_set_d(t2, s1.lo, MPFR_RNDN);
    mpfr_mul_d(t2, t2, s2v.lo, MPFR_RNDN);
    mpfr_sub(t3, t1, t2, MPFR_RNDN); /* cos(r1 + r2) */
    return mpfr_cmp(en, t3) >= 0;
}

int main(void)
{
    mpfr_inits2(PREC, t1, t2, t3, en, G, s2, (mpfr_ptr)0);
    long keep = 0, keep_far = 0, keep_far_all = 0, meet = 0, meet_far = 0, meet_far_all = 0;
    long keep_test = 0, keep_wrong = 0, meet_test = 0, meet_wrong = 0;
    for (int it = 0; it < 100000; it++) {
        vbx_ia e[3], ca, sa, n[3];
        random_cap(e, &ca, &sa);
        vbx_ia sa2 = vbx_ia_sqr(ca.lo >= 0.0 ? sa : vbx_ia_point(1.0));
        for (int i = 0; i < 3; i++)
            n[i] = around((rnd() * 2.0 - 1.0) * 40.0);
        vbx_ia nn = vbm_dot3(n, n);
        /* h on the boundary of "all on the cap's side" (lo) or "none" (hi),
         * from doubles, moved off by a relative offset */
        double enm = e[0].lo * n[0].lo + e[1].lo * n[1].lo + e[2].lo * n[2].lo;
        double root = sqrt(fabs(sa2.lo * (nn.lo - enm * enm)));
        int far, lo_side = rnd() < 0.5;
        double h0 = lo_side ? fmin(ca.lo * enm, enm) - root : fmax(ca.lo * enm, enm) + root;
        double off = offset(&far);
        vbx_ia h = around(h0 + off * (fabs(h0) + root + 1e-300));
        int kf = vbm_cut_keep_fast(e, ca, sa2, n, h, nn), t = vbm_cut_test(e, ca, sa2, n, h, nn);
        if (kf) {
            keep++;
            keep_test += t != 0;
            keep_wrong += !keep_exact(e, ca, sa2, n, h, nn);
        }
        if (far && t == 0) {
            keep_far_all++;
            keep_far += kf;
        }
        /* a second cap at an angle r1 + r2 + offset from the first */
        vbx_ia e2[3], c2, s2c;
        random_cap(e2, &c2, &s2c);
        double r = acos(fmax(-1.0, fmin(1.0, ca.lo))) + acos(fmax(-1.0, fmin(1.0, c2.lo)));
        double ang = r * (1.0 + offset(&far));
        /* e2 = cos(ang) e + sin(ang) w, w a unit vector normal to e */
        double w[3] = {-e[1].lo, e[0].lo, 0.0};
        if (fabs(e[2].lo) > 0.9) {
            w[0] = 0.0;
            w[1] = -e[2].lo;
            w[2] = e[1].lo;
        }
        double wn = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        for (int i = 0; i < 3; i++)
            e2[i] = around(cos(ang) * e[i].lo + sin(ang) * w[i] / wn);
        int mf = vbm_caps_meet_fast(e, ca, sa, e2, c2, s2c), ap = vbm_caps_apart(e, ca, sa, e2, c2, s2c);
        if (mf) {
            meet++;
            meet_test += ap != 0;
            meet_wrong += !meet_exact(e, ca, sa, e2, c2, s2c);
        }
        if (far && !ap) {
            meet_far_all++;
            meet_far += mf;
        }
    }
    printf("keep: %ld decided (%ld against the test, %ld wrong at p), %ld of %ld off by >= 2^-30\n"
           "meet: %ld decided (%ld against the test, %ld wrong at p), %ld of %ld off by >= 2^-30\n",
           keep, keep_test, keep_wrong, keep_far, keep_far_all, meet, meet_test, meet_wrong,
           meet_far, meet_far_all);
    CHECK(keep_test == 0 && keep_wrong == 0);
    CHECK(meet_test == 0 && meet_wrong == 0);
    CHECK(keep > 10000 && meet > 10000);
    CHECK(keep_far >= 0.99 * (double)keep_far_all && keep_far_all > 5000);
    CHECK(meet_far >= 0.99 * (double)meet_far_all && meet_far_all > 5000);
    mpfr_clears(t1, t2, t3, en, G, s2, (mpfr_ptr)0);
    mpfr_free_cache();
    VB_TEST_END();
}
