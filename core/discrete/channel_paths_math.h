/* The arithmetic of the channel graph's sweeps, written once for the host
 * (the Dijkstra sweep vbc_sweep, channel_graph.c; the relaxation twin,
 * channel_paths.c) and the OpenCL kernels (gpu/channel_paths.cl). Both
 * sides evaluate the same double expressions in the same order with
 * contraction off, so a step costs the same bits everywhere. */
#ifndef VBC_CHANNEL_PATHS_MATH_H
#define VBC_CHANNEL_PATHS_MATH_H

#include "vb_cl_compat.h"

#ifndef __OPENCL_C_VERSION__
#include <math.h>
#endif

/* Smallest clearance used in the path cost, so a voxel touching an atom still
 * has a finite (if huge) cost. */
#define VBC_PATH_MIN_CLEAR 0.05

/* The cost of one step of the 26-connected voxel graph between voxels of
 * clearances cu and cq (Å): its length len in {1 face, 2 edge, 3 corner}
 * codes (voxels); weighted, that length / r^2 with r the smaller clearance
 * (at least VBC_PATH_MIN_CLEAR), so the cheapest path keeps to the widest
 * way through. Symmetric in cu, cq. Always > 0. */
/* The step lengths of the codes 1, 2, 3 (face, edge, corner), in voxels. */
#define VBC_PATH_LEN_EDGE 1.4142135623730951
#define VBC_PATH_LEN_CORNER 1.7320508075688772

/* vbc_path_step's weighting of a step of length `step` (voxels). */
VB_SHARED_FN double vbc_path_weigh(double step, double cu, double cq)
{
    /* fmax(fmin(cu, cq), VBC_PATH_MIN_CLEAR) written as comparisons:
     * the same r for every input, NaN included (fmin takes the other
     * operand, fmax the floor; of two equal zeros the sign is lost in
     * the floor), but without the libm calls that C compilers must
     * emit for fmin/fmax when NaN and signed zeros are honoured (perf:
     * most of a sweep's own time on the host). */
    double lo = cu < cq || cq != cq ? cu : cq;
    double r = lo > VBC_PATH_MIN_CLEAR ? lo : VBC_PATH_MIN_CLEAR;
    return step / (r * r);
}

VB_SHARED_FN double vbc_path_step(int len, double cu, double cq, int weighted)
{
    double step = len == 1 ? 1.0 : len == 2 ? VBC_PATH_LEN_EDGE : VBC_PATH_LEN_CORNER;
    return weighted ? vbc_path_weigh(step, cu, cq) : step;
}

/* The predecessor rule of the sweeps: of two neighbours (du, u) and
 * (db, b) that both reach a voxel at its distance, the one Dijkstra
 * settles first, the smaller (distance, position). */
VB_SHARED_FN int vbc_path_pred_before(double du, vb_u32 u, double db, vb_u32 b)
{
    return du < db || (du == db && u < b);
}

#endif
