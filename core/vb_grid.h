/* Discrete grids for JFA / Facet-JFA: the one copy of the distance math,
 * compiled both as C11 (reference backend, checks) and as OpenCL C (kernels).
 *
 * Seeds live in grid coordinates where pixel p has its centre at p, stored as
 * 16.16 fixed point (VBJ_FIX_ONE = one pixel). A cell of f pixels per axis at
 * coarse position P has its centre at P*f + (f-1)/2, also exact in 16.16.
 * Squared distances are then exact 64-bit integers (|d| < 2^30 for n <= 2^14,
 * so three squares stay below 2^62): "nearest seed, ties to the lowest index"
 * (the paper's Definition 2) is decided without rounding, identically on every
 * device, and the exact reference is exact for the seeds as stored. */
#ifndef VB_GRID_H
#define VB_GRID_H

#ifdef __OPENCL_C_VERSION__
typedef int vbj_i32;
typedef uint vbj_u32;
typedef long vbj_i64;
typedef ulong vbj_u64;
#define VBJ_FN static inline
#else
#include <stdint.h>
typedef int32_t vbj_i32;
typedef uint32_t vbj_u32;
typedef int64_t vbj_i64;
typedef uint64_t vbj_u64;
#define VBJ_FN static inline
#endif

#define VBJ_FIX_BITS 16
#define VBJ_FIX_ONE 65536
#define VBJ_FIX_HALF 32768
/* Largest grid side: keeps |coordinate difference| < 2^30 in 16.16. */
#define VBJ_MAX_N 16384u
/* Label of a pixel that has not received any seed yet. */
#define VBJ_NONE 0xffffffffu
/* Facet-JFA keeps its "interior" mark in the top bit of a stored label, so
 * seed indices stay below 2^31 - 1. */
#define VBJ_MARK 0x80000000u
#define VBJ_LABEL_MASK 0x7fffffffu
#define VBJ_MAX_SEEDS 0x7ffffffeu

/* Fixed-point centre of the cell at coarse position p when a cell spans f
 * fine pixels (f a power of two; f = 1 is the pixel itself). */
VBJ_FN vbj_i32 vbj_cell_centre(vbj_u32 p, vbj_u32 f)
{
    return (vbj_i32)(p * f) * VBJ_FIX_ONE + (vbj_i32)(f - 1u) * VBJ_FIX_HALF;
}

/* Exact squared distance between two fixed-point points (units 2^-32 px^2).
 * Coordinates lie in [-2^15, 2^30), so each difference fits in 32 bits and
 * each square is one widening 32x32 -> 64 multiply. */
VBJ_FN vbj_u64 vbj_dist2(vbj_i32 ax, vbj_i32 ay, vbj_i32 az, vbj_i32 bx, vbj_i32 by,
                         vbj_i32 bz)
{
    vbj_i32 dx = ax - bx, dy = ay - by, dz = az - bz;
    return (vbj_u64)((vbj_i64)dx * dx) + (vbj_u64)((vbj_i64)dy * dy) +
           (vbj_u64)((vbj_i64)dz * dz);
}

/* True when candidate (d, l) beats the current (bd, bl): nearer, or as near
 * with a lower seed index (Definition 2's tie rule). */
VBJ_FN int vbj_better(vbj_u64 d, vbj_u32 l, vbj_u64 bd, vbj_u32 bl)
{
    return d < bd || (d == bd && l < bl);
}

/* Fine pixel nearest to a fixed-point coordinate (halves round up); callers
 * guarantee -0.5 <= c < n - 0.5 so the result lies in [0, n). */
VBJ_FN vbj_u32 vbj_pixel_of(vbj_i32 c)
{
    return (vbj_u32)((c + VBJ_FIX_HALF) >> VBJ_FIX_BITS);
}

#endif
