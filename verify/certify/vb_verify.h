/* Exact certification of Voronoi vertices of spheres, and the brute-force
 * exact reference.
 *
 * A vertex of the additively weighted (Apollonius) diagram is a point p and a
 * tangent radius t with |p - c_a| - R_a = t for at least four spheres a and
 * >= t for every other sphere (t < 0 is legal for overlapping spheres). The
 * certifier re-derives everything from the exact decimals of the input: it
 * never trusts the candidate beyond choosing which of the (at most two) exact
 * solutions is meant. Signs are decided by a double filter with a proven error
 * bound, falling back to GMP; counts go to vb_ctx_stats(ctx). */
#ifndef VB_VERIFY_H
#define VB_VERIFY_H

#include "vb.h"
#include "vb_spheres.h"
#include "vb_vertex.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct vb_certifier vb_certifier;

/* Builds the certifier for a validated sphere set: exact rationals from the
 * decimals and a provably conservative spatial index for the emptiness test.
 * The set must outlive the certifier. Free with vb_certifier_close. Returns
 * VB_OK, VB_ENOMEM, VB_EINPUT_TOOLARGE (more than 2^32 - 1 spheres) or
 * VB_EINPUT_MAGNITUDE (decimal exponents spanning more than 800 orders).
 * One certifier serves one thread at a time (it keeps scratch state);
 * vb_certify_list spreads its own work over worker threads. */
int vb_certifier_open(vb_ctx *ctx, const vb_sphere_set *set, vb_certifier **out);

void vb_certifier_close(vb_certifier *c);

/* Frees the identities c has handed out (the keys of vb_cert_result) when a
 * caller keeps c open for other work, e.g. arc closure after judging a file
 * (their memory grows with the vertices judged). Keys handed out later
 * start again from 0, so they do not compare with earlier ones. NULL: no-op. */
void vb_certifier_forget_keys(vb_certifier *c);

enum vb_cert_verdict {
    VB_CERT_OK = 0,          /* certified vertex */
    VB_CERT_NO_SOLUTION = 1, /* the defining spheres have no common (outer) tangent sphere */
    VB_CERT_INTRUDER = 2,    /* the tangent sphere is not empty: `intruder` cuts it */
    VB_CERT_FAR = 3,         /* exact vertex exists but is farther than tol from the candidate */
    VB_CERT_UNDETERMINED = 4,/* the defining spheres do not determine a finite set of points */
    VB_CERT_BAD_IDS = 5      /* fewer than 4 distinct ids, or an id out of range */
};

typedef struct vb_cert_result {
    int verdict;             /* enum vb_cert_verdict */
    uint32_t intruder;       /* VB_CERT_INTRUDER: a sphere strictly inside the tangent sphere */
    double x, y, z, t;       /* exact solution nearest the candidate, rounded correctly */
    double dist;             /* distance candidate -> exact point */
    const uint32_t *members; /* VB_CERT_OK: sorted ids of ALL spheres the vertex touches */
    size_t nmembers;         /*   (owned by the certifier; valid until the next call) */
    size_t key;              /* VB_CERT_OK: identity of the exact point; equal keys <=> same exact vertex */
} vb_cert_result;

/* Certifies one candidate. ids: >= 4 sphere ids (any order, duplicates
 * ignored) whose tangent sphere defines the vertex; p: the candidate point,
 * used only to choose the nearest of the exact solutions (by the distance of
 * the rounded points) and to measure dist. tol <= 0 disables the distance
 * check. Verdicts are decided in this order: BAD_IDS; UNDETERMINED or
 * NO_SOLUTION (rank-deficient ids: NO_SOLUTION when inconsistent); among the
 * roots that solve the unsquared system for ALL ids, the nearest is judged:
 * INTRUDER (the deepest intruder is named), then FAR. x, y, z, t, dist are
 * set from INTRUDER on. Counts candidates, certified, rejected and the filter
 * statistics in the context. Returns VB_OK with the verdict in *res, or
 * VB_ENOMEM / VB_EPREC / VB_EINTERNAL (message in ctx). */
int vb_certify_candidate(vb_ctx *ctx, vb_certifier *c, const uint32_t *ids, size_t nids,
                         const double p[3], double tol, vb_cert_result *res);

/* Certifies every candidate of `cand` and writes the canonical certified set
 * to `out` (sorted, one entry per exact vertex with all its members; dist is
 * the largest candidate distance merged into it; status CERTIFIED). Refused
 * candidates go to `rejected` (may be NULL) with status REJECTED. Counts in
 * the context's stats: candidates (all), rejected (refused candidates) and
 * certified (distinct canonical vertices added to out). Runs on the threads
 * of vb_certifier_set_threads; the result does not depend on their number. */
int vb_certify_list(vb_ctx *ctx, vb_certifier *c, const vb_vertex_list *cand, double tol,
                    vb_vertex_list *out, vb_vertex_list *rejected);

/* What vb_certify_quads did, for benchmarks and tests (every counter is the
 * same for any thread count). A root is one of the at most two exact
 * solutions of a quadruple's tangent system. */
typedef struct vb_cert_quad_stats {
    uint64_t quads;             /* quadruples judged */
    uint64_t no_root;           /* filter: no real root (delta < 0 proven) */
    uint64_t flat;              /* filter: rows of rank < 3 proven in integers (coplanar
                                   centres of equal radii): no vertex, no GMP */
    uint64_t delta_exact;       /* delta's sign computed in GMP integers where double-double
                                   could not tell (counted in exact_evals too) */
    uint64_t one_root;          /* ... of which delta = 0: one root, filtered as the others */
    uint64_t refused_tangent;   /* filter: roots with t + R < 0 proven for a member */
    uint64_t refused_intruder;  /* filter: roots with a sphere proven inside */
    uint64_t rejected_fast;     /* quadruples without a vertex, decided with no GMP */
    uint64_t roots_fast;        /* roots certified with no GMP (filter and long double rounding) */
    uint64_t roots_round_exact; /* roots the filter certified whose rounding needed GMP */
    uint64_t roots_exact;       /* roots judged on the exact path (filter undecided) */
    uint64_t roots_tied;        /* open roots proven a vertex of degree > 4 already solved
                                   (certify_ties.c): no exact path */
    uint64_t quads_exact;       /* quadruples the filter could not set up: every root exact */
    uint64_t exact_solves;      /* GMP solves of a quadruple */
    uint64_t mpfr_rounds;       /* coordinates that MPFR rounded */
    uint64_t vertices;          /* distinct vertices appended to out */
    uint64_t duplicates;        /* certified roots of degree > 4 already written by another quadruple */
    uint64_t power_signs;       /* scan signs the double box left open, decided by the power
                                   (double intervals, then double-double) */
    uint64_t power_signs_dd;    /* ... of which the double intervals left open */
    uint64_t judged_vertex;     /* roots the certification filter proved vertices (verdicts) */
    uint64_t judged_not;        /* roots it proved not vertices */
    uint64_t judged_open;       /* roots it left to this certifier's filter and exact stage */
} vb_cert_quad_stats;

/* Certifies every exact root of every quadruple: quads[k] holds 4 sphere ids
 * in increasing order, and the quadruples are in strictly increasing
 * lexicographic order (vb_cover_run's output is). Each root whose tangent
 * sphere touches every member from outside (t + R_i >= 0) and has no sphere
 * inside is a vertex; it is appended to `out` once, in canonical form: all
 * member ids sorted, x, y, z, t the exact vertex rounded correctly, status
 * CERTIFIED, dist 0 -- as vb_certify_list writes certified vertices. A
 * vertex of degree > 4 comes from several quadruples and is written once
 * per call (the certifier's keys identify it). out need not be empty; it is
 * left sorted (vb_vertex_list_sort's order). Counts in the context's stats:
 * candidates (quadruples), rejected (quadruples without a vertex),
 * certified (vertices appended), and the filter counters; *stats (may be
 * NULL) gets the details. Runs on the threads of vb_certifier_set_threads;
 * output and counters do not depend on their number. Returns VB_OK,
 * VB_EMISUSE (quadruples not as above; out unchanged), VB_ENOMEM, VB_EPREC
 * or VB_EINTERNAL (message in ctx). */
int vb_certify_quads(vb_ctx *ctx, vb_certifier *c, const uint32_t (*quads)[4], size_t n,
                     vb_vertex_list *out, vb_cert_quad_stats *stats);

/* vb_certify_quads with the verdicts of the certification filter
 * (core/cells/vbd_cert_shared.h; verdict may be NULL: none): a root judged
 * VBD_VERTEX is certified without its emptiness scan (its coordinates are
 * still rounded here, exactly where double-double cannot), a root judged
 * VBD_NOT is not looked at, a quadruple with both roots VBD_NOT not even
 * set up; open roots are judged as vb_certify_quads judges them. The same
 * output as vb_certify_quads for verdicts that are true, which the filter
 * proves. A verdict this certifier's own proven filter contradicts (two
 * roots judged where it proves none) is VB_EINTERNAL. Counts the verdicts
 * (judged_*) in *stats. Same returns. */
int vb_certify_quads_judged(vb_ctx *ctx, vb_certifier *c, const uint32_t (*quads)[4],
                            const uint8_t *verdict, size_t n, vb_vertex_list *out,
                            vb_cert_quad_stats *stats);

/* Threads for vb_certify_list and vb_certify_quads: 0 (the default) takes
 * the environment variable VORBALL_THREADS when it is a positive integer,
 * else the online CPUs. The output does not depend on it: results are
 * placed by candidate (quadruple) index and merged in that order, so every
 * thread count writes the same lists, keys and stats as one thread. */
void vb_certifier_set_threads(vb_certifier *c, unsigned threads);

/* Counters of the certifier beyond vb_stats, for benchmarks: roundings of
 * exact coordinates that the fast enclosure could not decide and MPFR did
 * (all calls since open, every thread). */
uint64_t vb_certifier_slow_rounds(const vb_certifier *c);

/* Spheres above which `vorball reference` refuses an input unless --force
 * (E130), and vb_reference warns (W720): the enumeration grows as about
 * n^2.7 in practice (n^4 at worst): 800 spheres took 140 s, 1000 equal
 * spheres 3.4 min of CPU. */
#define VB_REFERENCE_MAX_SPHERES 500

/* Exact reference: every vertex of the diagram from all quadruples (with
 * filters and conservative culling), canonical and sorted, dist = 0; appended
 * to out (which it sorts). Stats: candidates = quadruples examined, rejected
 * = those the filter refuted, certified = vertices found. Cost grows as n^4
 * (W720 above VB_REFERENCE_MAX_SPHERES). Not enumerated: vertices whose members' tangency
 * system has rank < 3 yet an isolated solution (needs nested spheres that
 * touch; see verify/judge/reference.c). Returns VB_OK, VB_ENOMEM, VB_EPREC. */
int vb_reference(vb_ctx *ctx, const vb_sphere_set *set, vb_vertex_list *out);

/* vb_reference as `vorball reference` and Python's vorball.reference run it:
 * above VB_REFERENCE_MAX_SPHERES spheres it refuses (VB_EINPUT_REFERENCE_SIZE,
 * E130, naming `name`) unless force. Same returns as vb_reference. */
int vb_reference_run(vb_ctx *ctx, const vb_sphere_set *set, int force, const char *name,
                     vb_vertex_list *out);

/* The exact certifier behind the certifier table of the vertex pipeline
 * (vb_vertices.h): vb_certifier_open / vb_certify_list (no distance limit)
 * / vb_certify_candidate. */
struct vb_certifier_ops;
extern const struct vb_certifier_ops vb_exact_certifier;

/* The MPFR version the verifier runs with (mpfr_get_version). */
const char *vb_verify_mpfr_version(void);

#ifdef __cplusplus
}
#endif
#endif
