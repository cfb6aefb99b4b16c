/* Exact numbers of verify/: the sphere set as scaled integers, signs in
 * Q(sqrt(D)), correctly rounded doubles, and the tangent-sphere solver.
 *
 * Every input decimal mant * 10^e becomes the integer mant * 10^(e + E) where
 * E is the largest number of decimal places in the set: one common scale, so
 * the whole solver runs on GMP integers (no gcd work) and the scale cancels
 * from every sign. Coordinates come back in input units only when rounded. */
#ifndef VBX_EXACT_H
#define VBX_EXACT_H

#include <gmp.h>
#include <mpfr.h>

#include "vb.h"
#include "vb_spheres.h"
#include "vbx_ia.h"

/* The exact sphere set. c[4*i + k]: X, Y, Z, R of sphere i times 10^E. */
typedef struct vbx_data {
    size_t n;
    mpz_t *c;
    mpz_t scale;  /* 10^E */
    vbx_ia *box;  /* 4n: enclosures of the exact decimals in input units */
    double *near; /* 4n: the exact decimals rounded to nearest (monotone in the value) */
    double rmax;  /* >= every exact radius */
} vbx_data;

/* Fills d from the decimals of set (never from its doubles). Returns VB_OK
 * (free with vbx_data_free), VB_ENOMEM or VB_EINPUT_MAGNITUDE (exponent
 * spread too large to scale); on failure d holds nothing. */
int vbx_data_init(vb_ctx *ctx, vbx_data *d, const vb_sphere_set *set);
void vbx_data_free(vbx_data *d);

/* Sign (-1, 0, +1) of a + b*sqrt(D) for integers a, b and D >= 0. t1, t2 are
 * scratch integers. */
int vbx_sign_qsqrt(const mpz_t a, const mpz_t b, const mpz_t D, mpz_t t1, mpz_t t2);

/* (num + b*sqrt(D)) / den (den != 0, D >= 0) rounded to the nearest double
 * (ties to even), with a 53-bit enclosure [*lo, *hi] of the exact value:
 * vbx_round_fast when it decides, else vbx_round_mpfr. *slow (may be NULL)
 * is incremented when MPFR had to decide. Returns VB_OK or VB_EPREC. */
int vbx_round(const mpz_t num, const mpz_t b, const mpz_t D, const mpz_t den, double *out,
              double *lo, double *hi, uint64_t *slow);

/* The MPFR path of vbx_round: the precision grows until the rounding is
 * decided; this terminates because an irrational value is never a rounding
 * midpoint and a rational one becomes exactly representable. Returns VB_OK
 * or VB_EPREC (precision cap hit). */
int vbx_round_mpfr(const mpz_t num, const mpz_t b, const mpz_t D, const mpz_t den, double *out,
                   double *lo, double *hi);

/* The fast path of vbx_round, without MPFR: a 64-bit (x87 extended) interval
 * evaluation of the exact value. Returns 1 with the same *out as
 * vbx_round_mpfr when the whole enclosure rounds to one double (and a
 * 53-bit enclosure in *lo, *hi), 0 when it cannot tell (a near tie,
 * overflow, or a platform without a 64-bit long double). Cancellation
 * between num and b*sqrt(D) is removed exactly (see vbx_round_with). */
int vbx_round_fast(const mpz_t num, const mpz_t b, const mpz_t D, const mpz_t den, double *out,
                   double *lo, double *hi);

/* The part of vbx_round_fast shared by every coordinate of one root:
 * enclosures of den and sqrt(D), D itself and two scratch integers. */
typedef struct vbx_round_common {
    int ok, root;              /* ok: usable; root: D != 0 */
    long double dl, dh, sl, sh;
    mpz_srcptr D;
    mpz_ptr t1, t2;
} vbx_round_common;

/* Prepares rc for values over den in Q(sqrt(D)); D, t1 and t2 must outlive
 * rc's use (t1, t2: scratch, clobbered by vbx_round_with). */
void vbx_round_prepare(vbx_round_common *rc, const mpz_t D, const mpz_t den, mpz_ptr t1,
                       mpz_ptr t2);

/* vbx_round_fast for (num + b*sqrt(D)) / den with D and den prepared in rc. */
int vbx_round_with(const vbx_round_common *rc, const mpz_t num, const mpz_t b, double *out,
                   double *lo, double *hi);

/* One exact solution of the tangent system: u = (a + b*sqrt(delta)) / den
 * with u = (q, s), q = p - c_base, s = t + R_base, in scaled units; den > 0. */
typedef struct vbx_root {
    int sigma; /* sign in front of sqrt(delta) in the line parameter; 0: single root */
    mpz_t a[4], b[4], den;
} vbx_root;

enum vbx_solve_status {
    VBX_SOLVED = 0,       /* nroots in 0..2 (0: no real point on the cone) */
    VBX_SINGULAR = 1,     /* linear part has rank < 3 for these rows */
    VBX_UNDETERMINED = 2  /* the whole solution line lies on the cone */
};

/* Workspace and result of one solve: base sphere and three rows. */
typedef struct vbx_solver {
    const vbx_data *d;
    uint32_t base, rows[3];
    int status, nroots, k; /* k: the free unknown (column whose minor is non-zero) */
    mpz_t m[3][5];         /* rows: dx, dy, dz, r, W (equation m . u = W / 2) */
    mpz_t delta, A, B, C, Dk, U[4], v[4];
    vbx_root root[2];
    mpz_t row[5]; /* scratch row of a tested sphere */
    mpz_t t[6];   /* scratch */
    mpz_t minor[10]; /* 2x2 minors of rows 1, 2 of m (columns a < b) */
    uint64_t slow_rounds; /* vbx_root_coords coordinates that needed MPFR */
} vbx_solver;

void vbx_solver_init(vbx_solver *s, const vbx_data *d);
void vbx_solver_free(vbx_solver *s);

/* Row of sphere j relative to base: out[0..2] = C_j - C_base,
 * out[3] = R_j - R_base, out[4] = |out[0..2]|^2 - out[3]^2. */
void vbx_row(const vbx_data *d, uint32_t base, uint32_t j, mpz_t out[5], mpz_t tmp);

/* Chooses, among cand[0..n) (in that order, none equal to base), the first
 * three whose rows relative to base are linearly independent (greedy), and
 * writes them to rows. ncols = 4 uses the coefficient columns (dx, dy, dz, r);
 * ncols = 5 adds W (the augmented system, for a consistency test). Returns
 * the rank found, at most 3 (3 = success). Clobbers s->m. */
int vbx_pick_rows(vbx_solver *s, uint32_t base, const uint32_t *cand, size_t n, int ncols,
                  uint32_t rows[3]);

/* Solves |p - c_i| = t + R_i squared, for base and rows. Returns the status
 * (also in s->status); roots in s->root[0 .. s->nroots). Roots are those of
 * the squared system: outer tangency is checked by the caller. */
int vbx_solve(vbx_solver *s, uint32_t base, const uint32_t rows[3]);

/* Sign of t + R_j at root r (outer tangency of j needs >= 0). */
int vbx_sign_tangent(vbx_solver *s, const vbx_root *r, uint32_t j);

/* Sign of |p - c_j|^2 - (t + R_j)^2 at root r. */
int vbx_sign_power(vbx_solver *s, const vbx_root *r, uint32_t j);

/* Sign of |p - c_j| - R_j - t at root r, exactly (the emptiness predicate). */
int vbx_sign_distance(vbx_solver *s, const vbx_root *r, uint32_t j);

/* The root of `canon` (same exact point as root r of `ours`) in canon's own
 * parametrisation: +1/-1 for canon's two roots, 0 when canon has one root. */
int vbx_sigma_in(vbx_solver *canon, vbx_solver *ours, const vbx_root *r);

/* Root r rounded to nearest doubles in input units: out = x, y, z, t, with
 * 53-bit enclosures box[0..3]. Returns VB_OK or VB_EPREC. */
int vbx_root_coords(vbx_solver *s, const vbx_root *r, double out[4], vbx_ia box[4]);

#endif
