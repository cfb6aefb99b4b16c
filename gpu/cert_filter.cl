/* The certification filter on OpenCL: one work-item judges the two roots of
 * one proposed quadruple with vbd_judge (core/cells/vbd_cert_shared.h, the
 * same code as the host twin core/cells/cert_filter.c), writing one byte of
 * two verdicts. Built without fast-math or mad, contraction off: the error
 * bound of the header assumes correctly rounded double operations. */
#pragma OPENCL FP_CONTRACT OFF

#include "vbd_cert_shared.h"

__kernel void vbd_judge_kernel(__global const long *z, __global const uint *cell_start,
                               __global const uint *cell_ids, __global const long *cell_z,
                               const double ox, const double oy,
                               const double oz, const double inv, const uint nx, const uint ny,
                               const uint nz, const long rmax, __global const uint *quads,
                               const uint n, __global uchar *verdict)
{
    size_t k = get_global_id(0);
    if (k >= n)
        return;
    vbd_grid g;
    g.ox = ox;
    g.oy = oy;
    g.oz = oz;
    g.inv = inv;
    g.nx = nx;
    g.ny = ny;
    g.nz = nz;
    g.rmax = rmax;
    __global const uint *q = quads + 4 * k;
    verdict[k] = (uchar)vbd_judge(z, cell_start, cell_ids, cell_z, &g, q[0], q[1], q[2], q[3]);
}
