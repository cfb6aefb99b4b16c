/* Internal to the sampling pipeline (core/cells/sampler*.c, the matching
 * stage of vbs_match.h, topology.c): the spatial hash of centres, the
 * conservative culling of bisectors into direction tiles, the tangent test,
 * the entry of matching and the topology evidence. */
#ifndef VBS_INTERNAL_H
#define VBS_INTERNAL_H

#include "vb_parallel.h"
#include "vb_sampler.h"

/* Uniform grid of sphere centres (CSR: cell k holds idx[start[k]..start[k+1])). */
typedef struct vbs_hash {
    double lo[3], h;
    int dim[3];
    uint32_t *start, *idx;
    const vb_sphere_set *set;
    double rmax;
} vbs_hash;

int vbs_hash_build(vb_ctx *ctx, const vb_sphere_set *set, vbs_hash *g);
void vbs_hash_free(vbs_hash *g);

/* Appends to *out (growable, *cap) the ids of spheres whose centre lies within
 * `radius` of p, in grid order (callers that need ids sorted sort what they
 * keep). Returns VB_OK or VB_ENOMEM. */
int vbs_hash_query(const vbs_hash *g, const double p[3], double radius, uint32_t **out,
                   size_t *n, size_t *cap);

/* Whether the tangent sphere of candidate k (centre x, y, z, radius t) is
 * empty: no sphere other than q[0..3] (repeat one for fewer) and the
 * contained ones cuts it by more than tol. Walks the grid cells around it
 * and stops at the first intruder. Returns 1 when empty. */
int vbs_tangent_empty(const vbs_hash *h, const vbs_cand *k, const uint32_t q[4], double tol);

/* The trisector of spheres a, b, c: centres p of the spheres tangent to
 * all three from outside, |p - c_x| = r_x + t. p = c_a + w0 + t w1 + g n,
 * with w0, w1 in the plane of the centres, n its unit normal and
 * g^2 = A t^2 + B t + C. A >= 0: one open branch, t >= tmin, on which the
 * offset g from the plane is monotone: its parameter s = g. A < 0: a
 * closed curve, tmin <= t <= tmax, an ellipse in (t, g): its parameter is
 * the angle s = atan2(g, sqrt(-A) (t - tc)) in (-pi, pi], tc the middle,
 * with s = +-pi the point at tmin. (Not t itself: near the plane t moves
 * with g^2 and loses the order of close vertices to rounding.) Collinear
 * centres (`circle`): a circle of radius C around w0 at fixed t = tmin,
 * in the plane of the unit vectors w1, n; s is the angle from w1. */
typedef struct vbs_trisector {
    double ca[3], w0[3], w1[3], n[3];
    double A, B, C, tmin, tmax;
    int closed, circle;
} vbs_trisector;

/* Sets up the trisector of a, b, c. Returns 0 when there is none (three
 * equal spheres on a line; no valid branch). */
int vbs_trisector_init(const vb_sphere_set *s, uint32_t a, uint32_t b, uint32_t c,
                       vbs_trisector *tr);

/* Branch parameter s of a point p (with its t) on the trisector. */
double vbs_trisector_param(const vbs_trisector *tr, const double p[3], double t);

/* Point (and t) at branch parameter s. */
void vbs_trisector_point(const vbs_trisector *tr, double s, double p[3], double *t);

/* 1 when spheres t[0..2] have exactly equal radii. */
int vbs_trisector_equal_radii(const vb_sphere_set *s, const uint32_t t[3]);

/* For a triple of equal radii: whether the point of its trisector line
 * nearest p (taken exactly) is on the Voronoi edge of the triple, decided
 * in rationals against the spheres cand[0..ncand) (the others must be
 * farther than rounding). Returns 1 on the edge. */
int vbs_trisector_exact_on_edge(const vb_sphere_set *s, const uint32_t t[3], const double p[3],
                                const uint32_t *cand, size_t ncand);

/* Direction tiles: 6*T*T cones (centre direction, cos/sin of the half-angle
 * with a safety margin), the same for every base. */
typedef struct vbs_tiles {
    unsigned T;
    double *dir;   /* 3 per tile */
    double *cth, *sth;
} vbs_tiles;

int vbs_tiles_build(vb_ctx *ctx, unsigned T, vbs_tiles *t);
void vbs_tiles_free(vbs_tiles *t);

/* Bisectors and tile lists of one base, in the layout of vb_sampler_batch
 * (bisectors sorted by id; tile_idx entries index `bis` of this base). */
typedef struct vbs_base_data {
    vbs_bisector *bis;
    double *norm;            /* |e| of each bisector */
    double *gb;              /* scratch: cone bounds of a tile's candidates */
    size_t nbis, bis_cap;
    uint32_t *tile_off;      /* 6*T*T + 1 */
    uint32_t *tile_idx;
    size_t nidx, idx_cap;
    /* scratch */
    uint32_t *near;
    size_t nnear, near_cap;
    uint8_t *keep;
    uint32_t *remap;         /* old bisector position -> kept position */
    uint64_t *sortkey;       /* (id, old position) of the kept bisectors */
    vbs_bisector *tmp;       /* the bisectors before compaction */
    size_t remap_cap;
    uint32_t *lvl_off[2], *lvl_idx[2]; /* coarser levels of the tile hierarchy */
    size_t lvl_n[2], lvl_cap[2];
    /* Second look (a widened query): per tile of every level, the largest
     * first-look envelope bound T_P of its finest descendants (levels one
     * after another, coarsest first), and per bisector the least distance
     * at which any ray can hit it. */
    double *lim, *smin;
    size_t smin_cap;
    /* Lists of the coarse tiles (T = VBS_COARSE_T or the finest if coarser),
     * kept for the targeted search: 6 T^2 + 1 offsets, indices into bis. */
    uint32_t *co_off, *co_idx;
    size_t nco, co_cap;
} vbs_base_data;

/* Every base's kept bisectors and coarse tile lists, in base order (the
 * targeted search reuses them instead of culling again). */
#define VBS_COARSE_T 2u
typedef struct vbs_bis_store {
    size_t *off;             /* n + 1: bisectors of base i are bis[off[i] .. off[i+1]) */
    vbs_bisector *bis;
    size_t nbis, cap;
    unsigned T;              /* tiles per face side of the coarse lists */
    uint32_t *co_off;        /* n * 6 T^2 + 1 offsets into co_idx */
    uint32_t *co_idx;        /* indices relative to the base's first bisector */
    size_t nco, co_cap;
} vbs_bis_store;

typedef struct vbs_culler {
    const vb_sphere_set *set;
    const vbs_hash *hash;
    const vbs_tiles *levels; /* T = 1, 2, 4, ..., the finest last */
    int nlevels;
    double clip;             /* world units */
    int all_pairs;
    vbs_bis_store *store;
} vbs_culler;

void vbs_base_data_free(vbs_base_data *bd);

/* Builds base i's bisectors and, per tile, the provably sufficient subset
 * (see sampler_cull.c for the bound). Contained bases get no bisectors.
 * Returns VB_OK or VB_ENOMEM. */
int vbs_cull_base(vb_ctx *ctx, const vbs_culler *cu, uint32_t i, vbs_base_data *bd);

/* The clip distance derived from the input (world units). */
double vbs_clip_distance(const vb_sphere_set *set);

/* Matching (Sec. 5.4), targeted search (5.5), the tangent-sphere test and
 * our completions on the sorted raw candidates (matching.c runs the phases
 * of vbs_match.h), on nthreads threads (the result does not depend on it);
 * fills res->candidates and the counters. */
int vbs_match(vb_ctx *ctx, const vb_sphere_set *set, const vbs_culler *cu,
              const vbs_params *params, unsigned target_depth, int nthreads,
              vb_cand_vec *raw, vb_proposal *res);

/* Topology evidence of the bases of a batch. */
typedef struct vbs_topo_acc {
    uint32_t *faces;   /* pairs */
    size_t nfaces, faces_cap;
    uint32_t *triples; /* triples */
    size_t ntriples, triples_cap;
} vbs_topo_acc;

/* Recomputes the batch base k's rays on the host, keeping only colours that
 * no rounding could change, and records its faces and two-colour triples. */
int vbs_topo_collect(vbs_topo_acc *acc, const vb_sampler_batch *bt, size_t k);
/* Sorts and deduplicates into the result; frees acc. */
int vbs_topo_finish(vbs_topo_acc *acc, vb_topology_evidence *ev);

#endif
