/* The exact tiled nearest-seed engine (variants "exact" and "exact-boundary"):
 * the one copy of its decisions, compiled as C11 (core/discrete/jfa_tiles.c,
 * the plain-C twin) and as OpenCL C (gpu/jfa_tiles.cl).
 *
 * The grid is cut into tiles of S^d voxels (S = 8 in 3D, 16 in 2D; the
 * grid side when smaller). For a tile T with voxel-centre box [lo, hi]
 * (16.16 fixed point, vb_grid.h) the engine needs a list of seeds that
 * provably contains the owner of every voxel of T (nearest seed, ties to
 * the lowest index: the paper's Definition 2), and decides each voxel
 * against that list only.
 *
 * The distance bound. For a seed s let near(s) and far(s) be the smallest
 * and the largest distance from s to a point of the box, and
 * U = min over all seeds s' of far(s'). If s owns a voxel centre p of T,
 * then for every seed s', |p - s| <= |p - s'| (ties allowed) <= far(s'),
 * so |p - s| <= U, and near(s) <= |p - s| <= U. Hence every owner has
 * near(s) <= U; the minimum over any subset of the seeds is >= U, so an
 * upper bound of U found from some seeds only keeps the list complete
 * (a larger bound admits more seeds, never fewer). near^2 and far^2 are
 * exact 64-bit integers (vbj_xt_bounds), so the test near^2 <= U^2 rounds
 * nothing.
 *
 * The seed grid. Seeds sit in buckets of 2^bs pixels per axis (bs >= the
 * tile shift, so a tile lies in one bucket b0): bucket b holds the seeds
 * whose nearest pixel p has p >> bs = b, i.e. coordinates in
 * [(b 2^bs) px - 1/2, ((b + 1) 2^bs) px - 1/2). After the buckets of the
 * block [b0 - r, b0 + r]^d are visited, every other seed lies beyond a face
 * of the block, at least vbj_xt_gap = D(r) from the box (D grows with r).
 * So for any bound V >= U, every seed with near <= U, every seed that
 * could lower U, and the nearest seed to every voxel of the box (|p - s*|
 * <= U) lie in the block of the smallest r with D(r) > V (exactly: D^2 >
 * V^2, vbj_xt_done): a seed outside has far >= near >= D > V >= U.
 *
 * The search. ring0[b] is the Chebyshev distance in buckets from b to the
 * nearest bucket holding a seed (saturated at VBJ_XT_RING0_MAX: a smaller
 * value only searches more), so the block of radius r0 = ring0[b0] holds a
 * seed and every smaller block none. (A) The block of radius r0 (and, only
 * when saturation left it empty, the next rings until a seed is met)
 * gives a first bound V = the smallest far seen, and the centre owner
 * among those seeds. (B) The blocks grow at once to the smallest R1 with
 * D(R1) > V; the seeds added lower V to the true U (the minimiser of far
 * lies in that block, by the remark above) and give the true centre owner
 * (its distance to the centre is at most U). (C) R2 <= R1, the smallest
 * radius with D(R2) > U, bounds the block whose seeds are tested below:
 * it holds every seed with near <= U.
 *
 * Blocks are read by rows of buckets (vbj_xt_unit): the buckets of one row
 * are consecutive in the seed grid, so a row's seeds are one range of
 * records whatever the number of empty buckets in it; a block less a
 * smaller block is read as the rows outside the smaller one plus two
 * segments of each row through it. The cost of a tile is then the number
 * of rows of its blocks, (2R + 1)^(d - 1), plus the seeds read, not the
 * (2R + 1)^d buckets: far from the seeds (the empty corners of a protein's
 * box, where R is large) the buckets would dominate.
 *
 * The dominance test. Let c be the owner of the tile's centre voxel (found
 * exactly in the search above). A seed s is dropped when c beats it at every voxel centre of the
 * box: f(p) = |p - s|^2 - |p - c|^2 is a sum over the axes of functions
 * affine in p_a (the squares of p cancel), so its minimum over the box is
 * the sum over the axes of the smaller of the two end values, exact in
 * 64-bit integers (vbj_xt_dominated). f_min > 0, or f_min = 0 and c < s,
 * means c is nearer (or as near with a lower index) at every voxel of T,
 * so s owns none. What is left (the survivors) still holds every owner;
 * when only c is left, every voxel of T is c's and the tile is filled
 * without any per-voxel work (a "uniform" tile). This test is what keeps
 * lists short where the distance bound alone is weak: far from the seeds
 * (the corners of a protein's box, the inside of a shell of seeds) U - d
 * is the tile's whole diagonal and the bound admits a wide cap of seeds.
 *
 * The per-voxel decision. Survivors are kept relative to the tile's first
 * voxel centre lo (r = s - lo, 16.16 integers). When every |r_a| <= 2^24 -
 * (S - 1) 2^16 (survivors within ~248 px: all but the sparsest layouts),
 * r_a, the voxel offsets j 2^16 (j < S) and their differences are exact
 * floats (integers of magnitude <= 2^24), so only the squares and the two
 * adds of D~ = fl(fl(dx^2) + fl(fl(dy^2) + fl(dz^2))) round: D~ = D (1 + t),
 * |t| <= (1 + u)^3 - 1 < 3.0001 u = eps with u = 2^-24 (all terms >= 0;
 * D = 0 gives D~ = 0). Per voxel the engine keeps the float minimum d1, its
 * seed b (the first offered at d1) and d2, the float minimum over the other
 * survivors (vbj_xt_offer). The voxel is decided when d2 > h = fl(d1 (1 +
 * 2^-19)) (vbj_xt_decided): then for every other survivor c, Dc >= D~c /
 * (1 + eps) >= d2 / (1 + eps) > D~b (1 + 2^-19)(1 - u) / (1 + eps) >= Db (1 +
 * 2^-19)(1 - u)(1 - eps) / (1 + eps) > Db, since 2^-19 = 32 u exceeds
 * u + 2 eps and their products: b is strictly nearest, whatever the indices.
 * Any other voxel (near or exact ties, D~b = D~c = 0 included) is redone
 * with exact 64-bit integer distances and the tie rule (vbj_dist2,
 * vbj_better) over all survivors; so is every voxel of a tile with a
 * survivor too far for exact floats. Every label therefore equals the exact
 * one, and no decision depends on the order of the survivors.
 *
 * Both backends run the same search, the same tests and the same
 * float expressions in the same order (contraction off), so their labels
 * and their work counts agree exactly. */
#ifndef VBJ_TILES_H
#define VBJ_TILES_H

#include "vb_grid.h"

/* Voxels per work-item along x (at most; S when the tile is narrower). */
#define VBJ_XT_ROW 8u
/* Survivors staged in local memory at a time; a tile with more is decided
 * in chunks of this many (the ring block rescanned per chunk). */
#define VBJ_XT_CAP 512u
/* Most work-items per tile: S^d / VBJ_XT_ROW (64 in 3D, 32 in 2D). */
#define VBJ_XT_WG 64u
/* Relative coordinates up to this magnitude are exact floats with every
 * voxel offset of the tile (see above; 2^24 - 7 2^16 for S = 8 and 2^24 -
 * 15 2^16 for S = 16 are both above it). */
#define VBJ_XT_FLOAT_MAX (16777216 - 15 * VBJ_FIX_ONE)
/* 1 + 2^-19: the filter's margin (see above). */
#define VBJ_XT_UP (1.0f + 0x1p-19f)
/* The largest start ring stored per bucket (an 8-bit count). */
#define VBJ_XT_RING0_MAX 255u
/* Counters of a run (vbj_counts' exact-engine fields), in this order. */
enum {
    VBJ_XT_C_UNIFORM = 0, /* tiles with one survivor */
    VBJ_XT_C_CAND,        /* seeds passing near <= U, summed over tiles */
    VBJ_XT_C_SURV,        /* survivors of the dominance test, summed */
    VBJ_XT_C_EVALS,       /* voxel x survivor float evaluations */
    VBJ_XT_C_EXACT,       /* voxels decided with 64-bit integers */
    VBJ_XT_C_CHUNKED,     /* tiles with more than VBJ_XT_CAP survivors */
    VBJ_XT_C_VISITED,     /* seeds read by the searches (bounds, then survivors) */
    VBJ_XT_NC
};

/* Slots of the OpenCL run counters: work-group w adds to slot
 * w % VBJ_XT_SLOTS of each (32-bit; the host sums the slots in 64 bits, so
 * a count overflows only past 2^32 per slot, 2^40 in all). */
#define VBJ_XT_SLOTS 256u

/* log2 of the tile side for a 2^logn grid in dim dimensions. */
VBJ_FN vbj_u32 vbj_xt_tile_shift(vbj_u32 dim, vbj_u32 logn)
{
    vbj_u32 t = dim == 3 ? 3u : 4u;
    return t < logn ? t : logn;
}

/* The voxel-centre box of a tile: lo and hi per axis in 16.16 (z 0..0 in
 * 2D). */
typedef struct vbj_xt_box {
    vbj_i32 lo[3], hi[3];
} vbj_xt_box;

/* The box of tile (tx, ty, tz) with side 2^ts. */
VBJ_FN vbj_xt_box vbj_xt_tile_box(vbj_u32 tx, vbj_u32 ty, vbj_u32 tz, vbj_u32 ts, vbj_u32 dim)
{
    vbj_xt_box b;
    vbj_i32 span = (vbj_i32)((1u << ts) - 1u) * VBJ_FIX_ONE;
    b.lo[0] = (vbj_i32)(tx << ts) * VBJ_FIX_ONE;
    b.lo[1] = (vbj_i32)(ty << ts) * VBJ_FIX_ONE;
    b.lo[2] = dim == 3 ? (vbj_i32)(tz << ts) * VBJ_FIX_ONE : 0;
    b.hi[0] = b.lo[0] + span;
    b.hi[1] = b.lo[1] + span;
    b.hi[2] = dim == 3 ? b.lo[2] + span : 0;
    return b;
}

/* near^2 and far^2 of seed (sx, sy, sz) to box b, exact (differences below
 * 2^30, so each square below 2^60 and the sums below 2^62). */
VBJ_FN void vbj_xt_bounds(vbj_xt_box b, vbj_i32 sx, vbj_i32 sy, vbj_i32 sz, vbj_u32 dim,
                          vbj_u64 *near2, vbj_u64 *far2)
{
    vbj_i32 c[3] = {sx, sy, sz};
    vbj_u64 n2 = 0, f2 = 0;
    for (vbj_u32 a = 0; a < dim; a++) {
        vbj_i64 below = (vbj_i64)b.lo[a] - c[a], above = (vbj_i64)c[a] - b.hi[a];
        vbj_i64 g = below > 0 ? below : above > 0 ? above : 0;
        vbj_i64 f = (vbj_i64)c[a] - b.lo[a] > (vbj_i64)b.hi[a] - c[a] ? (vbj_i64)c[a] - b.lo[a]
                                                                      : (vbj_i64)b.hi[a] - c[a];
        n2 += (vbj_u64)(g * g);
        f2 += (vbj_u64)(f * f);
    }
    *near2 = n2;
    *far2 = f2;
}

/* Lower bound D (16.16) on the distance from box b to every seed outside
 * the bucket block [c - r, c + r]^d (buckets of 2^bs px, g per axis; c the
 * bucket holding the box); VBJ_I64_MAX when the block covers the grid.
 * Above the block a seed has coordinate >= ((c + r + 1) 2^bs) px - 1/2,
 * below it < ((c - r) 2^bs) px - 1/2. */
VBJ_FN vbj_i64 vbj_xt_gap(vbj_xt_box b, vbj_i32 cx, vbj_i32 cy, vbj_i32 cz, vbj_i32 r, vbj_u32 bs,
                          vbj_i32 g, vbj_u32 dim)
{
    vbj_i32 c[3] = {cx, cy, cz};
    vbj_i64 D = VBJ_I64_MAX;
    for (vbj_u32 a = 0; a < dim; a++) {
        if (c[a] - r - 1 >= 0) {
            vbj_i64 edge = ((vbj_i64)(c[a] - r) << bs) * VBJ_FIX_ONE - VBJ_FIX_HALF;
            D = b.lo[a] - edge < D ? b.lo[a] - edge : D;
        }
        if (c[a] + r + 1 < g) {
            vbj_i64 edge = ((vbj_i64)(c[a] + r + 1) << bs) * VBJ_FIX_ONE - VBJ_FIX_HALF;
            D = edge - b.hi[a] < D ? edge - b.hi[a] : D;
        }
    }
    return D;
}

/* Row units of the block of radius R around a bucket less the block of
 * radius Rin (Rin < R; Rin < 0: the whole block): one unit per row of the
 * block ((2R + 1)^(d - 1) rows along x) for the whole block, else two per
 * row (the row whole or its two ends). */
VBJ_FN vbj_u32 vbj_xt_units(vbj_i32 R, vbj_i32 Rin, vbj_u32 dim)
{
    vbj_u32 s = 2u * (vbj_u32)R + 1u, rows = dim == 3 ? s * s : s;
    return Rin < 0 ? rows : 2u * rows;
}

/* Unit u of vbj_xt_units(R, Rin, dim) around bucket (bx, by, bz) of a grid
 * of g buckets per axis: 1 and its buckets *first .. *last (one row, so
 * their seeds are records start[*first] .. start[*last + 1]), or 0 when it
 * holds no bucket of the grid. Every bucket of the block less the inner
 * block lies in exactly one unit. */
VBJ_FN int vbj_xt_unit(vbj_i32 bx, vbj_i32 by, vbj_i32 bz, vbj_i32 R, vbj_i32 Rin, vbj_u32 u,
                       vbj_i32 g, vbj_u32 dim, vbj_i32 *first, vbj_i32 *last)
{
    vbj_u32 s = 2u * (vbj_u32)R + 1u, row = Rin < 0 ? u : u >> 1, end = Rin < 0 ? 0u : u & 1u;
    vbj_i32 dy = (vbj_i32)(row % s) - R, dz = dim == 3 ? (vbj_i32)(row / s) - R : 0;
    vbj_i32 y = by + dy, z = bz + dz;
    if (y < 0 || y >= g || z < 0 || z >= (dim == 3 ? g : 1))
        return 0;
    vbj_i32 ay = dy < 0 ? -dy : dy, az = dz < 0 ? -dz : dz;
    vbj_i32 xa = -R, xb = R;
    if ((ay > az ? ay : az) > Rin) {
        if (end)
            return 0; /* the row lies outside the inner block: whole in unit 0 */
    } else if (end == 0) {
        xb = -Rin - 1;
    } else {
        xa = Rin + 1;
    }
    xa += bx;
    xb += bx;
    xa = xa < 0 ? 0 : xa;
    xb = xb >= g ? g - 1 : xb;
    if (xa > xb)
        return 0;
    vbj_i32 base = (z * g + y) * g;
    *first = base + xa;
    *last = base + xb;
    return 1;
}

/* True when a block with gap D leaves out no seed within sqrt(u2) of the box. */
VBJ_FN int vbj_xt_done(vbj_i64 D, vbj_u64 u2)
{
    return D == VBJ_I64_MAX || (D > 0 && (vbj_u64)D * (vbj_u64)D > u2);
}

/* The smallest radius r >= r0 whose block leaves every unvisited seed
 * beyond sqrt(v2) of box b (vbj_xt_done). */
VBJ_FN vbj_i32 vbj_xt_radius(vbj_xt_box b, vbj_i32 bx, vbj_i32 by, vbj_i32 bz, vbj_i32 r0,
                             vbj_u32 bs, vbj_i32 g, vbj_u32 dim, vbj_u64 v2)
{
    vbj_i32 r = r0;
    while (!vbj_xt_done(vbj_xt_gap(b, bx, by, bz, r, bs, g, dim), v2))
        r++;
    return r;
}

/* The radius the search reads next after the block of radius R with bound
 * u2 (steps A and B above): R + 1 while no seed was met (u2 infinite), the
 * block growing until one is, unless it covers the grid; then the smallest
 * radius >= R that leaves out no seed within sqrt(u2). R itself means the
 * search is over: after step B u2 only fell, so R still qualifies. */
VBJ_FN vbj_i32 vbj_xt_next(vbj_xt_box b, vbj_i32 bx, vbj_i32 by, vbj_i32 bz, vbj_i32 R,
                           vbj_u32 bs, vbj_i32 g, vbj_u32 dim, vbj_u64 u2)
{
    if (u2 == VBJ_U64_MAX)
        return vbj_xt_gap(b, bx, by, bz, R, bs, g, dim) == VBJ_I64_MAX ? R : R + 1;
    return vbj_xt_radius(b, bx, by, bz, R, bs, g, dim, u2);
}

/* True when seed s (index si) owns no voxel centre of box b because seed t
 * (index ti) is nearer at every one, or as near with the lower index (the
 * minimum of |p - s|^2 - |p - t|^2 over the box, exact: see above). */
VBJ_FN int vbj_xt_dominated(vbj_xt_box b, vbj_i32 tx, vbj_i32 ty, vbj_i32 tz, vbj_u32 ti,
                            vbj_i32 sx, vbj_i32 sy, vbj_i32 sz, vbj_u32 si, vbj_u32 dim)
{
    vbj_i32 t[3] = {tx, ty, tz}, s[3] = {sx, sy, sz};
    vbj_i64 f = 0;
    for (vbj_u32 a = 0; a < dim; a++) {
        vbj_i64 ls = (vbj_i64)b.lo[a] - s[a], lt = (vbj_i64)b.lo[a] - t[a];
        vbj_i64 hs = (vbj_i64)b.hi[a] - s[a], ht = (vbj_i64)b.hi[a] - t[a];
        vbj_i64 el = ls * ls - lt * lt, eh = hs * hs - ht * ht;
        f += el < eh ? el : eh;
    }
    return f > 0 || (f == 0 && ti < si);
}

/* True when a survivor's relative coordinates are exact floats with every
 * voxel offset (see VBJ_XT_FLOAT_MAX). */
VBJ_FN int vbj_xt_float_ok(vbj_i32 rx, vbj_i32 ry, vbj_i32 rz)
{
    return rx <= VBJ_XT_FLOAT_MAX && rx >= -VBJ_XT_FLOAT_MAX && ry <= VBJ_XT_FLOAT_MAX &&
           ry >= -VBJ_XT_FLOAT_MAX && rz <= VBJ_XT_FLOAT_MAX && rz >= -VBJ_XT_FLOAT_MAX;
}

/* The float distance of the filter from exact float differences, in the
 * one order both backends use: the y-z part first (shared by a row). */
VBJ_FN float vbj_xt_yz(float dy, float dz) { return dy * dy + dz * dz; }
VBJ_FN float vbj_xt_dist(float dx, float yz) { return dx * dx + yz; }

/* Offers survivor v at float distance d to a voxel's state (d1, b, d2):
 * the first offer at the smallest d keeps b; d2 is the smallest distance
 * of the others. */
VBJ_FN void vbj_xt_offer(float d, vbj_u32 v, float *d1, float *d2, vbj_u32 *b)
{
    float hi = d < *d1 ? *d1 : d;
    *d2 = hi < *d2 ? hi : *d2;
    *b = d < *d1 ? v : *b;
    *d1 = d < *d1 ? d : *d1;
}

/* True when the filter proved b strictly nearest (see above). */
VBJ_FN int vbj_xt_decided(float d1, float d2) { return d2 > d1 * VBJ_XT_UP; }

#endif
