/* Internals shared by the certifier and the exact reference. */
#ifndef VBX_CERT_H
#define VBX_CERT_H

#include <stdint.h>

#include "vb_array.h"
#include "vb_hash.h"
#include "vb_verify.h"
#include "vbx_exact.h"
#include "vbx_sindex.h"
#include "vbx_quad.h"

/* One canonical vertex identity: its sorted member set and the root of its
 * canonical quadruple (see vbx_cert_key_of); the key is its index. */
typedef struct vbx_key_entry {
    uint64_t hash;
    size_t off, n; /* members in pool[off .. off + n) */
    int sigma;
} vbx_key_entry;

struct vb_certifier {
    const vb_sphere_set *set;
    vbx_data d;
    vbx_sindex t;          /* centres for the emptiness scans */
    vbx_qdata qd;          /* the scaled input in 64-bit integers (vb_certify_quads) */
    int64_t *qz;           /* qd.z, owned unless borrowed */
    int borrowed;          /* worker of vb_certify_list: d and t belong to the parent */
    unsigned threads;      /* vb_certify_list threads; 0 = VORBALL_THREADS or online CPUs */
    uint64_t slow_rounds;  /* MPFR roundings of finished worker runs (vb_certifier_counts) */
    vbx_solver sol, canon;
    uint32_t *ids;         /* sorted distinct ids of the current candidate */
    uint32_t *members;     /* result of the last judged root */
    size_t nmembers, cap;  /* capacity of ids and members */
    uint8_t *is_def;       /* n flags: defining ids of the current root */
    vbx_key_entry *keys;   /* the identities, by key */
    size_t nkeys, keys_cap;
    vb_hash keytab;        /* the keys by identity */
    uint32_t *pool;
    size_t npool, pool_cap;
};

/* Rounds root r of c->sol to doubles xyzt (x, y, z, t in input units) and
 * their enclosures box (vbx_root_coords). Returns VB_OK, or the rounding's
 * error, recorded in ctx ("cannot round an exact vertex to double"). */
int vbx_cert_round(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, double xyzt[4],
                   vbx_ia box[4]);

/* Is root r of c->sol a solution of the unsquared system for all of
 * def[0..ndef) (which contain c->sol's base and rows)? Checks outer tangency
 * t + R_i >= 0 of every defining sphere and exact tangency of those beyond
 * the solved four. box: enclosure of (x, y, z, t) of r in input units.
 * Returns 1 (yes) or 0. */
int vbx_cert_defining(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, const uint32_t *def,
                      size_t ndef, const vbx_ia box[4]);

/* The empty tangent sphere: scans the hierarchy around root r and sets *verdict
 * to VB_CERT_OK (all touching spheres, def included, sorted in c->members)
 * or VB_CERT_INTRUDER (*intruder: the deepest sphere inside). */
void vbx_cert_scan(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, const uint32_t *def,
                   size_t ndef, const vbx_ia box[4], int *verdict, uint32_t *intruder);

/* vbx_cert_scan for callers that need no intruder's name: stops at the
 * first sphere proven inside (*verdict = VB_CERT_INTRUDER, c->nmembers = 0). */
void vbx_cert_scan_empty(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, const uint32_t *def,
                         size_t ndef, const vbx_ia box[4], int *verdict);

/* Outer tangency (t + R_j >= 0) of sphere j at root r of c->sol: filter on
 * box, exact fallback. Returns the sign. */
int vbx_cert_tangent_sign(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, uint32_t j,
                          const vbx_ia box[4]);

/* Identity of the exact vertex at root r of c->sol whose members are
 * c->members, beyond the members: the root (*sigma) of the canonical
 * quadruple it is. Returns VB_OK or VB_EINTERNAL. */
int vbx_cert_identity(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, int *sigma);

/* Key of the exact vertex with sorted members m[0..n) and canonical root
 * sigma in c's table: equal exact points get equal keys, new ones the next
 * number. Returns VB_OK or VB_ENOMEM. */
int vbx_cert_key_of(vb_ctx *ctx, vb_certifier *c, const uint32_t *m, size_t n, int sigma,
                    size_t *key);

/* Makes room for entry `key` in a key -> slot table (where, *nwhere) that
 * grows with the keys vbx_cert_key_of hands out: the entries it adds hold
 * SIZE_MAX (no slot yet). Returns VB_OK, or VB_ENOMEM with the table as it
 * was. */
static inline int vbx_where_fit(size_t **where, size_t *nwhere, size_t key)
{
    if (key < *nwhere)
        return VB_OK;
    size_t old = *nwhere;
    if (VB_ARRAY_FIT(*where, *nwhere, key + 1, 64) != VB_OK)
        return VB_ENOMEM;
    for (size_t i = old; i < *nwhere; i++)
        (*where)[i] = SIZE_MAX;
    return VB_OK;
}

/* vb_certify_candidate without the key: everything else of *res, and the
 * canonical root in *sigma when the verdict is VB_CERT_OK. Same returns. */
int vbx_certify_one(vb_ctx *ctx, vb_certifier *c, const uint32_t *ids, size_t nids,
                    const double p[3], double tol, vb_cert_result *res, int *sigma);

/* A worker for another thread: own scratch and solvers, c's exact data and
 * grid (read-only while the worker lives). Close with vb_certifier_close.
 * NULL when out of memory. */
vb_certifier *vbx_certifier_worker(const vb_certifier *c);

/* The canonical quadruple of the member set c->members: the
 * lexicographically first sorted 4-subset (base = its smallest id) whose
 * system is VBX_SOLVED with a root; every exact point with these members is
 * one of its roots. Returns 0 when there is none (rank < 3), else 1 with
 * c->canon solved for it (unless *ours) and *ours = 1 when it is c->sol's
 * quadruple. */
int vbx_cert_canonical(vb_certifier *c, int *ours);

#endif
