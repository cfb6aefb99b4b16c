/* Internals of arc closure (verify/arc_*.c): the trisector of a triple of
 * spheres as a conic, exact and filtered positions on it, the local arc
 * test at a vertex, candidate bounds along an arc and the first touching
 * sphere.
 *
 * The geometry (all of it in the frame of the smallest sphere a of the
 * triple T = {a < b < c}, in the unknowns u = (q, s), q = p - c_a,
 * s = t + R_a, as in tangent_solver.c). A tangent sphere (p, t) of a, b, c
 * solves |q|^2 = s^2 and the two linear rows m_b . u = W_b / 2,
 * m_c . u = W_c / 2 (m_x = (c_x - c_a, R_x - R_a), W_x = |c_x - c_a|^2 -
 * (R_x - R_a)^2). The rows leave a 2-plane; its intersection with the cone
 * Q(u) = |q|^2 - s^2 = 0 is a conic, and the trisector is its branch with
 * s > 0 (for spheres that do not contain one another, W_x > 0, so the plane
 * misses the apexes of the three cones and each branch keeps the signs of
 * s, s + R_b - R_a and s + R_c - R_a). On that plane every other sphere j
 * has the affine function
 *     L_j(u) = W_j - 2 m_j . u = |q - d_j|^2 - (s + r_j)^2   (on the cone),
 * and j cuts the tangent sphere at u exactly when L_j(u) < 0 (L_j < 0
 * forces t + R_j > 0 unless j lies inside a, which validation excludes).
 * So an arc of the trisector is a Voronoi edge exactly where every L_j is
 * >= 0, and its vertices are where some L_j vanishes: the roots of the
 * quadruple T + j.
 *
 * Positions along the branch. Two linear functionals G, S on u serve as
 * coordinates of the plane:
 *   - centres not collinear: G = n . q with n = d_b x d_c, S = s. The conic
 *     is G^2 = A' s^2 + B' s + C' up to a positive factor, with
 *     A' = |n|^2 - |r_b d_c - r_c d_b|^2 (A' >= 0: hyperbola or parabola,
 *     an open branch along which G grows monotonically from -inf to +inf;
 *     A' < 0: an ellipse);
 *   - collinear centres (n = 0): the trisector is a circle around the axis,
 *     S = e1 . q, G = e2 . q for integer e1, e2 across the axis.
 * On an open branch the position is G. On a closed curve it is (half, value)
 * counter-clockwise in the (S, G) plane from the point of largest S: half 0
 * (G = 0, S > S_c), 1 (G > 0, value -S), 2 (G = 0, S < S_c), 3 (G < 0,
 * value S), S_c the centre's S. "Forward" is the direction of increasing
 * position. Every comparison is decided on double intervals first (the
 * vertex's correctly rounded coordinates enclose the exact point within an
 * ulp) and in Z[sqrt(delta)] of the points' quadruples where they overlap. */
#ifndef VBX_ARC_H
#define VBX_ARC_H

#include "vbx_cert.h"

/* ---- Z[sqrt(d)] ---------------------------------------------------------- */

/* a + b sqrt(d); d is held by whoever owns the number. */
typedef struct vbx_zs {
    mpz_t a, b;
} vbx_zs;

void vbx_zs_init(vbx_zs *x);
void vbx_zs_clear(vbx_zs *x);
/* r = x * y in Z[sqrt(d)] (r must not alias x or y). */
void vbx_zs_mul(vbx_zs *r, const vbx_zs *x, const vbx_zs *y, const mpz_t d, mpz_t tmp);
/* r += z x (z an integer). */
void vbx_zs_addmul_z(vbx_zs *r, const vbx_zs *x, const mpz_t z);
void vbx_zs_submul_z(vbx_zs *r, const vbx_zs *x, const mpz_t z);
/* Sign of x. */
int vbx_zs_sign(const vbx_zs *x, const mpz_t d, mpz_t t1, mpz_t t2);

/* Sign of A + B sqrt(d1) + C sqrt(d2) (d1, d2 >= 0). t[0..3] scratch. */
int vbx_sign_two_sqrt(const mpz_t A, const mpz_t B, const mpz_t d1, const mpz_t C,
                      const mpz_t d2, mpz_t *t);

/* ---- a point on a trisector, exactly ------------------------------------- */

/* u = U / den with U in Z[sqrt(d)]^4 (a's frame, scaled units), den > 0,
 * and its coordinates G = Gn / den, S = Sn / den. */
typedef struct vbx_xpt {
    mpz_t d, den;
    vbx_zs U[4], Gn, Sn;
} vbx_xpt;

void vbx_xpt_init(vbx_xpt *x);
void vbx_xpt_clear(vbx_xpt *x);

/* ---- the frame of a triple ----------------------------------------------- */

enum {
    VBX_TRI_OPEN = 0,     /* hyperbola branch or parabola: position G */
    VBX_TRI_CLOSED = 1,   /* ellipse (centres not collinear) */
    VBX_TRI_CIRCLE = 2,   /* collinear centres: a circle around the axis */
    VBX_TRI_NONE = 3      /* rank-deficient rows, or an internally tangent pair with centres
                             not collinear (no curve, a few points): not traced */
};

typedef struct vbx_tframe {
    uint32_t t[3];
    int kind, parabola;
    /* filter, input units: rows of b, c and the functionals */
    vbx_ia mb[4], mc[4], Wb, Wc;
    vbx_ia gf[4], sf[4];
    vbx_ia minor[6];       /* 2x2 minors of (m_b, m_c): columns 01 02 03 12 13 23 */
    vbx_ia n[3];           /* d_b x d_c, for the plane's frame */
    int plane;             /* the filter frame below is set (vbx_tframe_plane) */
    /* filter frame of the plane, u = O + S ES + G EG (ok: usable) */
    int ok;
    vbx_ia O[4], ES[4], EG[4];
    vbx_ia Sc;             /* centre's S (closed: both; open: the asymptotes') */
    vbx_ia k, Smin;        /* open hyperbola: asymptotes S = Sc +- k G, branch's S at G = 0 */
    vbx_ia cp;             /* open: (S - Sc)^2 = k^2 G^2 + cp on the branch */
    vbx_ia mq;             /* open: Q(u) = mq (k^2 G^2 + cp - (S - Sc)^2) on the plane */
    vbx_ia ax, bx;         /* closed: semi-axes along S and G */
    /* exact, scaled (set up lazily by vbx_tframe_exact) */
    int exact;
    mpz_t gz[4], sz[4], ez[4]; /* G, S and (closed, centres not collinear) the plane's S direction */
    mpz_t mz[6];           /* exact 2x2 minors */
    mpz_t rb[5], rc[5];    /* exact rows (vbx_row) */
} vbx_tframe;

/* ---- the worker ---------------------------------------------------------- */

typedef struct vbx_arc_counters {
    uint64_t filter_calls, filter_failures, exact_evals;
    uint64_t candidates, root_checks, brute;
    uint64_t tail_pieces, tail_strips; /* vbx_arc_search: pieces of tails, tails ended by a strip */
} vbx_arc_counters;

typedef struct vbx_arcw {
    vb_ctx *ctx;
    vb_certifier *c;
    const vb_sphere_set *set;
    vbx_solver sv, sq;      /* exact solves: vertex points, candidate roots */
    mpz_t z[16];            /* scratch */
    vbx_zs zs[8];
    vbx_xpt yx[2];          /* scratch points (roots) */
    uint8_t *mark;          /* n: candidate dedupe */
    const uint32_t *own;    /* NULL, or three spheres the gather leaves out */
    uint32_t *cand;
    size_t ncand, cand_cap;
    vbx_arc_counters cnt;
} vbx_arcw;

int vbx_arcw_init(vbx_arcw *w, vb_ctx *ctx, vb_certifier *c);
void vbx_arcw_free(vbx_arcw *w);

/* The triple's frame: kind decided exactly, filter data in t. Returns
 * VB_OK or VB_ENOMEM; t must be released with vbx_tframe_clear. */
void vbx_tframe_init(vbx_tframe *f);
void vbx_tframe_clear(vbx_tframe *f);
/* Makes an initialised frame fresh for another triple: every field but the
 * exact integers zeroed, as vbx_tframe_init leaves them (those are written
 * before they are read: f->exact and the kind's set-up say when). */
void vbx_tframe_reset(vbx_tframe *f);
int vbx_tframe_setup(vbx_arcw *w, vbx_tframe *f, const uint32_t t[3]);
/* vbx_tframe_setup without the filter frame of the plane (ok, O, ES, EG
 * and the conic's data): enough for positions (vbx_key_of_box,
 * vbx_pos_cmp) and the local test; vbx_tframe_plane completes it before
 * any search (idempotent). */
int vbx_tframe_setup_local(vbx_arcw *w, vbx_tframe *f, const uint32_t t[3]);
void vbx_tframe_plane(vbx_tframe *f);
/* The exact functionals and minors (idempotent). */
void vbx_tframe_exact(vbx_arcw *w, vbx_tframe *f);

/* ---- positions ----------------------------------------------------------- */

/* The filter's position of a point: for an open branch G; for a closed curve
 * the half (-1 when the filter cannot tell) and the value. */
typedef struct vbx_key {
    vbx_ia G, S, val;
    int half;
} vbx_key;

/* Key of the point with enclosures box (x, y, z, t, input units). */
void vbx_key_of_box(const vbx_arcw *w, const vbx_tframe *f, const vbx_ia box[4], vbx_key *k);

/* Exact half of a point on a closed curve (0..3). */
int vbx_xpt_half(vbx_arcw *w, vbx_tframe *f, const vbx_xpt *x);

/* Position comparison: -1, 0 (same point), 1; filter first. xa, xb may be
 * NULL when the caller has no exact point yet: then 2 is returned where the
 * filter cannot decide (the caller supplies them and asks again). */
int vbx_pos_cmp(vbx_arcw *w, vbx_tframe *f, const vbx_key *ka, const vbx_xpt *xa,
                const vbx_key *kb, const vbx_xpt *xb);

/* The exact point of root r of solver s (base a, rows b, c, j) into x. */
void vbx_xpt_of_root(vbx_arcw *w, vbx_tframe *f, const vbx_solver *s, const vbx_root *r,
                     vbx_xpt *x);

/* The exact point of vertex v (members m[0..nm), correctly rounded xyzt):
 * solves T + k for a member k and takes the root that rounds to xyzt.
 * Returns 1, or 0 when no root can be told to be v (then x is unset). */
int vbx_xpt_of_vertex(vbx_arcw *w, vbx_tframe *f, const uint32_t *m, size_t nm,
                      const double xyzt[4], vbx_xpt *x);

/* ---- the local test ------------------------------------------------------ */

/* The tangent direction tau (in u) of f's curve at the point with
 * enclosures box (x, y, z, t, input units): x . tau = det[x; m_b; m_c; l]
 * with l = (q, -s), so tau is orthogonal to m_b, m_c (it stays in the
 * plane) and to the cone's gradient at the point (it is tangent to the
 * conic there). Enclosures of the exact tau at every point of the box. */
void vbx_tau_of_box(const vbx_arcw *w, const vbx_tframe *f, const vbx_ia box[4], vbx_ia tau[4]);

/* Whether an edge of T leaves the vertex (members m, nm; box; exact point x,
 * built on demand into *x when the filter cannot decide: *have says whether
 * x is set) forward (*fwd) and backward (*bwd): 1 or 0. tau: vbx_tau_of_box
 * of box when the caller has it, else NULL (computed here). *extra (may be NULL)
 * gets a bit per member beyond T (in member order, up to 64) whose L_j is
 * identically zero on T's plane (spheres that share the edge). Returns VB_OK,
 * or VB_EDEGENERATE when the point cannot be handled (tangent of the conic
 * vanishes, vertex not identified). */
int vbx_local_arcs(vbx_arcw *w, vbx_tframe *f, const uint32_t *m, size_t nm,
                   const double xyzt[4], const vbx_ia box[4], const vbx_ia *tau, vbx_xpt *x,
                   int *have, int *fwd, int *bwd, uint64_t *extra);

/* ---- the first touching sphere along an arc ------------------------------- */

/* An end of an arc: a vertex on the curve (its key, exact point on demand,
 * members) or an end at infinity. A vertex end must be a certified vertex
 * (no sphere cuts its tangent ball): the search of a bounded arc relies on
 * it (arc_region.c). */
typedef struct vbx_arc_end {
    int inf;                 /* 1: the open branch's end (then nothing else is set) */
    vbx_key key;
    vbx_xpt *x;              /* exact point (NULL until needed) */
    int *have;               /* *have: x is set */
    const uint32_t *m;       /* members */
    size_t nm;
    const double *xyzt;
    /* Or NULL: the enclosures of the vertex's rounded point (x, y, z, t)
     * and of the curve's tangent direction there (vbx_tau_of_box); with
     * both at both ends a bounded arc of an open branch is searched at the
     * apex of its tangents found in u (arc_region.c, vbx_apex_point), with
     * no plane frame. */
    const vbx_ia *box, *tau;
} vbx_arc_end;

/* A touching point found inside an arc: sphere j (T + j, root sigma of the
 * solve with base a and rows b, c, j) and its position. */
typedef struct vbx_touch {
    int found;
    uint32_t j;
    int r;                   /* root index in the exact solve of sorted T + j */
    int seg;                 /* closed curves: 0 after the arc's start, 1 after the wrap */
    vbx_key key;
    int have;                /* x is set */
    vbx_xpt x;
} vbx_touch;

/* Searches the open arc from e0 to e1 (forward along the curve; e1->inf for
 * the open branch's forward end; e0->inf with dir = -1 for its backward end,
 * e1 then the first vertex; e0 == e1 on a closed curve: all the way round)
 * for points where a sphere beyond T touches: the first after e0 into
 * *first and the last before e1 into *last (either may be NULL). Returns
 * VB_OK, VB_ENOMEM or VB_EDEGENERATE (a position could not be decided).
 * Completes f's plane frame (vbx_tframe_plane) unless the arc's region is
 * an apex found in u (vbx_apex_point). */
int vbx_arc_search(vbx_arcw *w, vbx_tframe *f, vbx_arc_end *e0, vbx_arc_end *e1,
                   vbx_touch *first, vbx_touch *last);

/* Certifies the touching point tp (the tangent sphere of T + j there): the
 * exact vertex rounded into xyzt and all its members into c->members
 * (c->nmembers). Returns 1 when it is a vertex (empty), 0 when a sphere
 * cuts it, -1 on an error (message in ctx). */
int vbx_touch_certify(vbx_arcw *w, vbx_tframe *f, const vbx_touch *tp, double xyzt[4]);

/* Enclosures of a vertex's correctly rounded coordinates. */
void vbx_box_of_rounded(const double xyzt[4], vbx_ia box[4]);

#endif
