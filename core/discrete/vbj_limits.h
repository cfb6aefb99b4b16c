/* The discrete grids' fixed point and limits (16.16 seeds, the largest grid
 * side, the label of no seed, the interior mark): what a caller of the
 * nearest-seed engines (vbj_jfa.h) reads, and what the one copy of the
 * distance math (vb_grid.h, compiled as C11 and as OpenCL C) builds on.
 * Plain constants only. */
#ifndef VBJ_LIMITS_H
#define VBJ_LIMITS_H

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
/* Most z-slices of a 3D picture (vorball jfa --slice). */
#define VBJ_MAX_SLICES 16

#endif
