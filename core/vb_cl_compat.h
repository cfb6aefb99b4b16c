/* The one C / OpenCL C compatibility preamble of the headers whose math both
 * the host and the kernels compile (core/cells/vb_geom_shared.h,
 * core/discrete/vb_grid.h, core/discrete/channel_math.h): fixed-width
 * integer types, the address-space qualifier of kernel buffers and the
 * storage class of shared functions, as OpenCL C spells them and as C11
 * does. The floating-point pragmas (fp64, contraction off) stay in the
 * headers and kernels that need them: they change what a file computes. */
#ifndef VB_CL_COMPAT_H
#define VB_CL_COMPAT_H

#ifdef __OPENCL_C_VERSION__
typedef uchar vb_u8;
typedef int vb_i32;
typedef uint vb_u32;
typedef long vb_i64;
typedef ulong vb_u64;
#define VB_GLOBAL __global
#define VB_I64_MAX LONG_MAX
#define VB_U64_MAX ULONG_MAX
#else
#include <stdint.h>
typedef uint8_t vb_u8;
typedef int32_t vb_i32;
typedef uint32_t vb_u32;
typedef int64_t vb_i64;
typedef uint64_t vb_u64;
#define VB_GLOBAL
#define VB_I64_MAX INT64_MAX
#define VB_U64_MAX UINT64_MAX
#endif

/* Functions shared by host and kernels: one copy per translation unit. */
#define VB_SHARED_FN static inline

#endif
