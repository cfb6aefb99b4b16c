/* Test kernel for the runtime: y = a*x + y in double, loaded from disk. */
#include "probe_scale.h"
__kernel void probe_axpy(__global const double *x, __global double *y)
{
    size_t i = get_global_id(0);
    y[i] = PROBE_SCALE * x[i] + y[i];
}
