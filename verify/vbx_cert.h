/* Internals shared by the certifier and the exact reference. */
#ifndef VBX_CERT_H
#define VBX_CERT_H

#include "vb_verify.h"
#include "vbx_exact.h"
#include "vbx_grid.h"

/* One canonical vertex identity: its sorted member set and the root of its
 * canonical quadruple (see vbx_cert_key). */
typedef struct vbx_key_entry {
    uint64_t hash;
    size_t off, n; /* members in pool[off .. off + n) */
    int sigma;
    size_t key;
} vbx_key_entry;

struct vb_certifier {
    const vb_sphere_set *set;
    vbx_data d;
    vbx_grid g;
    vbx_solver sol, canon;
    uint32_t *ids;         /* sorted distinct ids of the current candidate */
    uint32_t *members;     /* result of the last judged root */
    size_t nmembers, cap;  /* capacity of ids and members */
    uint8_t *is_def;       /* n flags: defining ids of the current root */
    vbx_key_entry *slots;  /* open-addressing table of keys */
    size_t nslots, nkeys;
    uint32_t *pool;
    size_t npool, pool_cap;
};

/* Is root r of c->sol a solution of the unsquared system for all of
 * def[0..ndef) (which contain c->sol's base and rows)? Checks outer tangency
 * t + R_i >= 0 of every defining sphere and exact tangency of those beyond
 * the solved four. box: enclosure of (x, y, z, t) of r in input units.
 * Returns 1 (yes) or 0. */
int vbx_cert_defining(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, const uint32_t *def,
                      size_t ndef, const vbx_ia box[4]);

/* The empty tangent sphere: scans the grid around root r and sets *verdict
 * to VB_CERT_OK (all touching spheres, def included, sorted in c->members)
 * or VB_CERT_INTRUDER (*intruder: the deepest sphere inside). */
void vbx_cert_scan(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, const uint32_t *def,
                   size_t ndef, const vbx_ia box[4], int *verdict, uint32_t *intruder);

/* Outer tangency (t + R_j >= 0) of sphere j at root r of c->sol: filter on
 * box, exact fallback. Returns the sign. */
int vbx_cert_tangent_sign(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, uint32_t j,
                          const vbx_ia box[4]);

/* Key of the exact vertex at root r of c->sol whose members are c->members:
 * equal exact points get equal keys. Returns VB_OK, VB_ENOMEM or
 * VB_EINTERNAL. */
int vbx_cert_key(vb_ctx *ctx, vb_certifier *c, const vbx_root *r, size_t *key);

/* The canonical quadruple of the member set c->members: the
 * lexicographically first sorted 4-subset (base = its smallest id) whose
 * system is VBX_SOLVED with a root; every exact point with these members is
 * one of its roots. Returns 0 when there is none (rank < 3), else 1 with
 * c->canon solved for it (unless *ours) and *ours = 1 when it is c->sol's
 * quadruple. */
int vbx_cert_canonical(vb_certifier *c, int *ours);

#endif
