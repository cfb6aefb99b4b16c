/* LD_PRELOAD fault injection for the OpenCL API (a test helper, in the
 * spirit of SQLite's *fault.test): the N-th call of a chosen entry point
 * (or the N-th OpenCL call of any kind) fails with a real error code, as a
 * driver reports a failed allocation, exhausted resources or a lost queue.
 * Calls go on to the real loader (dlsym RTLD_NEXT) otherwise.
 *
 * Environment:
 *   VB_CLFAULT_FUNC    entry point to fail (e.g. clCreateBuffer), or "any"
 *   VB_CLFAULT_AT      which call of it fails, from 1 (unset: none fails)
 *   VB_CLFAULT_STICKY  non-empty: that call and every later one of the kind
 *                      fail (a device that is gone)
 *   VB_CLFAULT_ERR     the error: a number or a CL_ name (default: per entry
 *                      point, CL_MEM_OBJECT_ALLOCATION_FAILURE for buffers,
 *                      CL_INVALID_COMMAND_QUEUE for clFinish,
 *                      CL_OUT_OF_RESOURCES otherwise)
 *   VB_CLFAULT_SLOW    name:ms, every call of that entry point sleeps ms
 *                      first (fails or not as above)
 *   VB_CLFAULT_COUNTS  file to which "name count" lines of every call made
 *                      are appended at exit (the counting pass), then
 *                      "# max_buffer_bytes N", the largest clCreateBuffer
 * A failing call does what the specification says of an error: no object,
 * no event, *errcode_ret set; it is named on stderr ("clfault: ..."). */
#define _GNU_SOURCE
#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>
#include <dlfcn.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define VBF_ENTRY_POINTS(X)                                                     \
    X(clGetPlatformIDs) X(clGetPlatformInfo) X(clGetDeviceIDs) X(clGetDeviceInfo) \
    X(clCreateContext) X(clCreateCommandQueue) X(clCreateProgramWithSource)      \
    X(clCreateProgramWithBinary) X(clBuildProgram) X(clGetProgramInfo)           \
    X(clGetProgramBuildInfo) X(clCreateKernel) X(clSetKernelArg)                 \
    X(clGetKernelWorkGroupInfo) X(clCreateBuffer) X(clEnqueueWriteBuffer)        \
    X(clEnqueueReadBuffer) X(clEnqueueFillBuffer) X(clEnqueueNDRangeKernel)      \
    X(clFinish) X(clGetEventProfilingInfo)

enum {
#define VBF_ENUM(f) VBF_##f,
    VBF_ENTRY_POINTS(VBF_ENUM) VBF_COUNT
#undef VBF_ENUM
};

static const char *const vbf_names[VBF_COUNT] = {
#define VBF_NAME(f) #f,
    VBF_ENTRY_POINTS(VBF_NAME)
#undef VBF_NAME
};

static atomic_ulong vbf_calls[VBF_COUNT];
static atomic_ulong vbf_any;
static atomic_ulong vbf_max_buffer;

static const struct {
    const char *name;
    cl_int code;
} vbf_errors[] = {{"CL_MEM_OBJECT_ALLOCATION_FAILURE", CL_MEM_OBJECT_ALLOCATION_FAILURE},
                  {"CL_OUT_OF_RESOURCES", CL_OUT_OF_RESOURCES},
                  {"CL_OUT_OF_HOST_MEMORY", CL_OUT_OF_HOST_MEMORY},
                  {"CL_INVALID_COMMAND_QUEUE", CL_INVALID_COMMAND_QUEUE},
                  {"CL_DEVICE_NOT_AVAILABLE", CL_DEVICE_NOT_AVAILABLE},
                  {"CL_BUILD_PROGRAM_FAILURE", CL_BUILD_PROGRAM_FAILURE},
                  {"CL_INVALID_BINARY", CL_INVALID_BINARY},
                  {"CL_INVALID_VALUE", CL_INVALID_VALUE}};

static cl_int default_error(int which)
{
    switch (which) {
    case VBF_clCreateBuffer: return CL_MEM_OBJECT_ALLOCATION_FAILURE;
    case VBF_clFinish: return CL_INVALID_COMMAND_QUEUE;
    case VBF_clGetPlatformIDs: return -1001; /* CL_PLATFORM_NOT_FOUND_KHR */
    case VBF_clGetDeviceIDs: return CL_DEVICE_NOT_FOUND;
    case VBF_clBuildProgram: return CL_BUILD_PROGRAM_FAILURE;
    case VBF_clCreateProgramWithBinary: return CL_INVALID_BINARY;
    default: return CL_OUT_OF_RESOURCES;
    }
}

/* VB_CLFAULT_SLOW=name:ms: every call of that entry point first sleeps ms
 * (a device whose set-up outlasts the work done meanwhile). */
static void vbf_slow(int which)
{
    const char *e = getenv("VB_CLFAULT_SLOW"), *colon = e ? strchr(e, ':') : NULL;
    size_t len = strlen(vbf_names[which]);
    if (!colon || (size_t)(colon - e) != len || strncmp(e, vbf_names[which], len) != 0)
        return;
    long ms = strtol(colon + 1, NULL, 10);
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    if (ms > 0)
        nanosleep(&ts, NULL);
}

/* 0 to go on to the real call, else the error this call returns. */
static cl_int vbf_fault(int which)
{
    vbf_slow(which);
    unsigned long k = atomic_fetch_add(&vbf_calls[which], 1) + 1;
    unsigned long any = atomic_fetch_add(&vbf_any, 1) + 1;
    const char *func = getenv("VB_CLFAULT_FUNC"), *at = getenv("VB_CLFAULT_AT");
    if (!func || !at || !*at)
        return CL_SUCCESS;
    int all = strcmp(func, "any") == 0;
    if (!all && strcmp(func, vbf_names[which]) != 0)
        return CL_SUCCESS;
    unsigned long n = strtoul(at, NULL, 10), me = all ? any : k;
    const char *sticky = getenv("VB_CLFAULT_STICKY");
    if (!(me == n || (sticky && *sticky && me > n)))
        return CL_SUCCESS;
    cl_int err = default_error(which);
    const char *e = getenv("VB_CLFAULT_ERR");
    if (e && *e) {
        char *end;
        long v = strtol(e, &end, 10);
        if (*end == '\0')
            err = (cl_int)v;
        for (size_t i = 0; i < sizeof vbf_errors / sizeof vbf_errors[0]; i++)
            if (strcmp(e, vbf_errors[i].name) == 0)
                err = vbf_errors[i].code;
    }
    fprintf(stderr, "clfault: %s call %lu fails with %d\n", vbf_names[which], k, (int)err);
    return err;
}

static void *vbf_real(const char *name)
{
    void *p = dlsym(RTLD_NEXT, name);
    if (!p) {
        fprintf(stderr, "clfault: no real %s\n", name);
        abort();
    }
    return p;
}

__attribute__((destructor)) static void vbf_report(void)
{
    const char *path = getenv("VB_CLFAULT_COUNTS");
    if (!path || !*path)
        return;
    FILE *f = fopen(path, "a");
    if (!f)
        return;
    for (int i = 0; i < VBF_COUNT; i++) {
        unsigned long c = atomic_load(&vbf_calls[i]);
        if (c)
            fprintf(f, "%s %lu\n", vbf_names[i], c);
    }
    fprintf(f, "# max_buffer_bytes %lu\n", atomic_load(&vbf_max_buffer));
    fclose(f);
}

/* An entry point that returns cl_int. */
#define VBF_STATUS(name, params, args)                                  \
    CL_API_ENTRY cl_int CL_API_CALL name params                         \
    {                                                                   \
        static cl_int(CL_API_CALL * real) params;                       \
        cl_int err = vbf_fault(VBF_##name);                             \
        if (err != CL_SUCCESS)                                          \
            return err;                                                 \
        if (!real)                                                      \
            *(void **)&real = vbf_real(#name);                          \
        return real args;                                               \
    }

/* An entry point that returns an object and reports through errcode_ret. */
#define VBF_OBJECT(type, name, params, args)                            \
    CL_API_ENTRY type CL_API_CALL name params                           \
    {                                                                   \
        static type(CL_API_CALL * real) params;                         \
        cl_int err = vbf_fault(VBF_##name);                             \
        if (err != CL_SUCCESS) {                                        \
            if (errcode_ret)                                            \
                *errcode_ret = err;                                     \
            return NULL;                                                \
        }                                                               \
        if (!real)                                                      \
            *(void **)&real = vbf_real(#name);                          \
        return real args;                                               \
    }

VBF_STATUS(clGetPlatformIDs, (cl_uint n, cl_platform_id *p, cl_uint *np), (n, p, np))
VBF_STATUS(clGetPlatformInfo,
           (cl_platform_id p, cl_platform_info w, size_t n, void *v, size_t *r), (p, w, n, v, r))
VBF_STATUS(clGetDeviceIDs, (cl_platform_id p, cl_device_type t, cl_uint n, cl_device_id *d,
                            cl_uint *nd),
           (p, t, n, d, nd))
VBF_STATUS(clGetDeviceInfo, (cl_device_id d, cl_device_info w, size_t n, void *v, size_t *r),
           (d, w, n, v, r))
VBF_OBJECT(cl_context, clCreateContext,
           (const cl_context_properties *pr, cl_uint n, const cl_device_id *d,
            void(CL_CALLBACK *cb)(const char *, const void *, size_t, void *), void *u,
            cl_int *errcode_ret),
           (pr, n, d, cb, u, errcode_ret))
VBF_OBJECT(cl_command_queue, clCreateCommandQueue,
           (cl_context c, cl_device_id d, cl_command_queue_properties p, cl_int *errcode_ret),
           (c, d, p, errcode_ret))
VBF_OBJECT(cl_program, clCreateProgramWithSource,
           (cl_context c, cl_uint n, const char **s, const size_t *l, cl_int *errcode_ret),
           (c, n, s, l, errcode_ret))
VBF_OBJECT(cl_program, clCreateProgramWithBinary,
           (cl_context c, cl_uint n, const cl_device_id *d, const size_t *l,
            const unsigned char **b, cl_int *st, cl_int *errcode_ret),
           (c, n, d, l, b, st, errcode_ret))
VBF_STATUS(clBuildProgram,
           (cl_program p, cl_uint n, const cl_device_id *d, const char *o,
            void(CL_CALLBACK *cb)(cl_program, void *), void *u),
           (p, n, d, o, cb, u))
VBF_STATUS(clGetProgramInfo, (cl_program p, cl_program_info w, size_t n, void *v, size_t *r),
           (p, w, n, v, r))
VBF_STATUS(clGetProgramBuildInfo,
           (cl_program p, cl_device_id d, cl_program_build_info w, size_t n, void *v, size_t *r),
           (p, d, w, n, v, r))
VBF_OBJECT(cl_kernel, clCreateKernel, (cl_program p, const char *k, cl_int *errcode_ret),
           (p, k, errcode_ret))
VBF_STATUS(clSetKernelArg, (cl_kernel k, cl_uint i, size_t n, const void *v), (k, i, n, v))
VBF_STATUS(clGetKernelWorkGroupInfo,
           (cl_kernel k, cl_device_id d, cl_kernel_work_group_info w, size_t n, void *v,
            size_t *r),
           (k, d, w, n, v, r))
/* clCreateBuffer also keeps the largest size asked for. */
static cl_mem(CL_API_CALL *vbf_real_create_buffer)(cl_context, cl_mem_flags, size_t, void *,
                                                   cl_int *);

CL_API_ENTRY cl_mem CL_API_CALL clCreateBuffer(cl_context c, cl_mem_flags f, size_t n, void *h,
                                               cl_int *errcode_ret)
{
    unsigned long seen = atomic_load(&vbf_max_buffer);
    while (n > seen && !atomic_compare_exchange_weak(&vbf_max_buffer, &seen, n))
        ;
    cl_int err = vbf_fault(VBF_clCreateBuffer);
    if (err != CL_SUCCESS) {
        if (errcode_ret)
            *errcode_ret = err;
        return NULL;
    }
    if (!vbf_real_create_buffer)
        *(void **)&vbf_real_create_buffer = vbf_real("clCreateBuffer");
    return vbf_real_create_buffer(c, f, n, h, errcode_ret);
}
VBF_STATUS(clEnqueueWriteBuffer,
           (cl_command_queue q, cl_mem m, cl_bool b, size_t o, size_t n, const void *p,
            cl_uint ne, const cl_event *w, cl_event *e),
           (q, m, b, o, n, p, ne, w, e))
VBF_STATUS(clEnqueueReadBuffer,
           (cl_command_queue q, cl_mem m, cl_bool b, size_t o, size_t n, void *p, cl_uint ne,
            const cl_event *w, cl_event *e),
           (q, m, b, o, n, p, ne, w, e))
VBF_STATUS(clEnqueueFillBuffer,
           (cl_command_queue q, cl_mem m, const void *pat, size_t ps, size_t o, size_t n,
            cl_uint ne, const cl_event *w, cl_event *e),
           (q, m, pat, ps, o, n, ne, w, e))
VBF_STATUS(clEnqueueNDRangeKernel,
           (cl_command_queue q, cl_kernel k, cl_uint d, const size_t *off, const size_t *g,
            const size_t *l, cl_uint ne, const cl_event *w, cl_event *e),
           (q, k, d, off, g, l, ne, w, e))
VBF_STATUS(clFinish, (cl_command_queue q), (q))
VBF_STATUS(clGetEventProfilingInfo,
           (cl_event e, cl_profiling_info w, size_t n, void *v, size_t *r), (e, w, n, v, r))
