/* OpenCL runtime: device choice, program build and cache, error mapping. */
#include "vbg_runtime.h"
#include "vb_diag.h"

#include <dirent.h>
#include <errno.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define VBG_MAX_PROGRAMS 16

struct vb_device {
    cl_platform_id platform;
    cl_device_id device;
    cl_context context;
    cl_command_queue queue;
    int is_gpu;
    char name[256];
    struct {
        char key[256]; /* kernel file name + options */
        cl_program program;
    } programs[VBG_MAX_PROGRAMS];
    int nprograms;
};

static const char *cl_error_name(cl_int e)
{
    switch (e) {
#define N(x) case x: return #x
    N(CL_DEVICE_NOT_FOUND); N(CL_DEVICE_NOT_AVAILABLE); N(CL_COMPILER_NOT_AVAILABLE);
    N(CL_MEM_OBJECT_ALLOCATION_FAILURE); N(CL_OUT_OF_RESOURCES); N(CL_OUT_OF_HOST_MEMORY);
    N(CL_PROFILING_INFO_NOT_AVAILABLE); N(CL_BUILD_PROGRAM_FAILURE); N(CL_INVALID_VALUE);
    N(CL_INVALID_DEVICE_TYPE); N(CL_INVALID_PLATFORM); N(CL_INVALID_DEVICE);
    N(CL_INVALID_CONTEXT); N(CL_INVALID_QUEUE_PROPERTIES); N(CL_INVALID_COMMAND_QUEUE);
    N(CL_INVALID_MEM_OBJECT); N(CL_INVALID_BINARY); N(CL_INVALID_BUILD_OPTIONS);
    N(CL_INVALID_PROGRAM); N(CL_INVALID_PROGRAM_EXECUTABLE); N(CL_INVALID_KERNEL_NAME);
    N(CL_INVALID_KERNEL); N(CL_INVALID_ARG_INDEX); N(CL_INVALID_ARG_VALUE);
    N(CL_INVALID_ARG_SIZE); N(CL_INVALID_KERNEL_ARGS); N(CL_INVALID_WORK_DIMENSION);
    N(CL_INVALID_WORK_GROUP_SIZE); N(CL_INVALID_WORK_ITEM_SIZE); N(CL_INVALID_GLOBAL_OFFSET);
    N(CL_INVALID_EVENT_WAIT_LIST); N(CL_INVALID_EVENT); N(CL_INVALID_OPERATION);
    N(CL_INVALID_BUFFER_SIZE); N(CL_INVALID_GLOBAL_WORK_SIZE);
#undef N
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR (no OpenCL platform installed)";
    default: return "unknown OpenCL error";
    }
}

int vbg_check(vb_ctx *ctx, cl_int err, const char *what)
{
    if (err == CL_SUCCESS)
        return VB_OK;
    return vb_error(ctx, VB_EDEVICE, NULL, 0, "%s: %s (%d)", what, cl_error_name(err), (int)err);
}

static int device_has_fp64(cl_device_id d)
{
    cl_device_fp_config cfg = 0;
    if (clGetDeviceInfo(d, CL_DEVICE_DOUBLE_FP_CONFIG, sizeof cfg, &cfg, NULL) != CL_SUCCESS)
        return 0;
    return cfg != 0;
}

/* Finds device number `index` (modulo their count) among the devices of
 * `type` with fp64, counted over the platforms in their order. */
static int find_device(cl_device_type type, unsigned index, cl_platform_id *plat,
                       cl_device_id *dev)
{
    cl_uint np = 0;
    if (clGetPlatformIDs(0, NULL, &np) != CL_SUCCESS || np == 0)
        return 0;
    cl_platform_id ps[16];
    if (np > 16)
        np = 16;
    if (clGetPlatformIDs(np, ps, NULL) != CL_SUCCESS)
        return 0;
    cl_platform_id fp[256];
    cl_device_id fd[256];
    unsigned n = 0;
    for (cl_uint p = 0; p < np; p++) {
        cl_device_id ds[16];
        cl_uint nd = 0;
        if (clGetDeviceIDs(ps[p], type, 16, ds, &nd) != CL_SUCCESS)
            continue;
        for (cl_uint i = 0; i < nd && i < 16; i++)
            if (device_has_fp64(ds[i])) {
                fp[n] = ps[p];
                fd[n++] = ds[i];
            }
    }
    if (n == 0)
        return 0;
    *plat = fp[index % n];
    *dev = fd[index % n];
    return 1;
}

/* VORBALL_DEVICE_INDEX: which of the devices of a kind to open (0 when
 * unset). The MPI ranks on one host set it to their rank on the host
 * (cli/world_mpi.c), so each takes its own GPU; more ranks than GPUs share
 * them round-robin (the index is taken modulo their count), and a
 * scheduler that shows each rank one GPU (CUDA_VISIBLE_DEVICES) gives
 * index mod 1 = that GPU. VB_OK, or VB_EMISUSE for a value that is not a
 * number from 0. */
static int device_index(vb_ctx *ctx, unsigned *out)
{
    const char *v = getenv("VORBALL_DEVICE_INDEX");
    *out = 0;
    if (!v || !*v)
        return VB_OK;
    char *end;
    unsigned long k = strtoul(v, &end, 10);
    if (*end != '\0' || v[0] == '-' || k > 65535)
        return vb_error(ctx, VB_EMISUSE, NULL, 0,
                        "VORBALL_DEVICE_INDEX='%s': a device number from 0 to 65535 is wanted", v);
    *out = (unsigned)k;
    return VB_OK;
}

int vbg_runtime_gpu_present(void)
{
    DIR *d = opendir("/dev");
    if (!d)
        return 0;
    int found = 0;
    for (struct dirent *e; !found && (e = readdir(d));) {
        const char *n = e->d_name;
        found = strcmp(n, "kfd") == 0 ||
                (strncmp(n, "nvidia", 6) == 0 && n[6] >= '0' && n[6] <= '9');
    }
    closedir(d);
    return found;
}

int vbg_runtime_open(vb_ctx *ctx, vb_device_kind kind, vbg_runtime **out)
{
    *out = NULL;
    if (kind == VB_DEVICE_REF)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "the reference backend has no OpenCL runtime");
    cl_platform_id plat = NULL;
    cl_device_id dev = NULL;
    int found = 0;
    unsigned index;
    if (device_index(ctx, &index) != VB_OK)
        return VB_EMISUSE;
    vbg_pocl_cache_check(ctx);
    if (kind == VB_DEVICE_AUTO || kind == VB_DEVICE_GPU)
        found = find_device(CL_DEVICE_TYPE_GPU, index, &plat, &dev);
    if (!found && (kind == VB_DEVICE_AUTO || kind == VB_DEVICE_CPU))
        found = find_device(CL_DEVICE_TYPE_CPU, index, &plat, &dev);
    if (!found)
        return vb_error(ctx, VB_EDEVICE, NULL, 0, "no OpenCL %sdevice with double precision found",
                        kind == VB_DEVICE_GPU ? "GPU " : kind == VB_DEVICE_CPU ? "CPU " : "");
    vbg_runtime *rt = calloc(1, sizeof *rt);
    if (!rt)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    rt->platform = plat;
    rt->device = dev;
    cl_device_type type = 0;
    clGetDeviceInfo(dev, CL_DEVICE_TYPE, sizeof type, &type, NULL);
    rt->is_gpu = (type & CL_DEVICE_TYPE_GPU) != 0;
    char dname[160] = "", pname[90] = "";
    clGetDeviceInfo(dev, CL_DEVICE_NAME, sizeof dname - 1, dname, NULL);
    clGetPlatformInfo(plat, CL_PLATFORM_NAME, sizeof pname - 1, pname, NULL);
    snprintf(rt->name, sizeof rt->name, "%s (%s)", dname, pname);
    cl_int err;
    cl_context_properties props[] = {CL_CONTEXT_PLATFORM, (cl_context_properties)plat, 0};
    rt->context = clCreateContext(props, 1, &dev, NULL, NULL, &err);
    int rc = vbg_check(ctx, err, "clCreateContext");
    if (rc == VB_OK) {
        rt->queue = clCreateCommandQueue(rt->context, dev, CL_QUEUE_PROFILING_ENABLE, &err);
        rc = vbg_check(ctx, err, "clCreateCommandQueue");
    }
    if (rc != VB_OK) {
        vbg_runtime_close(rt);
        return rc;
    }
    vb_info(ctx, "OpenCL device: %s", rt->name);
    *out = rt;
    return VB_OK;
}

void vbg_runtime_close(vbg_runtime *rt)
{
    if (!rt)
        return;
    for (int i = 0; i < rt->nprograms; i++)
        clReleaseProgram(rt->programs[i].program);
    if (rt->queue)
        clReleaseCommandQueue(rt->queue);
    if (rt->context)
        clReleaseContext(rt->context);
    free(rt);
}

/* Device memory one stage may hold at once. A CPU device (PoCL) allocates
 * host memory: it gets at most 1/8 of the memory free when asked and never
 * more than 256 MiB (a batch of 2^22 rays, PoCL's own batch size, needs
 * less than 64 MiB on proteins), so a run on PoCL needs little beyond what
 * the reference
 * backend needs (batches sized for a GPU, on all of host memory, took
 * 13.6 GB for the 26k-atom capsid against 6.4 GB on the reference). A GPU
 * gets a quarter of its memory, at most 8 GiB; both at most one allocation's
 * maximum and at least 16 MiB. VORBALL_DEVICE_MEMORY_MIB sets the budget
 * (tests, shared machines). */
#define VBG_BUDGET_CPU_CAP ((size_t)256 << 20)
#define VBG_BUDGET_GPU_CAP ((size_t)8 << 30)
#define VBG_BUDGET_FLOOR ((size_t)16 << 20)

size_t vbg_runtime_memory_budget(const vbg_runtime *rt)
{
    const char *env = getenv("VORBALL_DEVICE_MEMORY_MIB");
    if (env && *env) {
        char *end;
        unsigned long long mib = strtoull(env, &end, 10);
        if (*end == '\0' && mib > 0 && mib < ((unsigned long long)1 << 40))
            return (size_t)mib << 20;
    }
    cl_ulong max_alloc = 0, global = 0;
    clGetDeviceInfo(rt->device, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof max_alloc, &max_alloc, NULL);
    clGetDeviceInfo(rt->device, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof global, &global, NULL);
    size_t budget = rt->is_gpu ? VBG_BUDGET_GPU_CAP : VBG_BUDGET_CPU_CAP;
    if (global && global / 4 < budget)
        budget = (size_t)(global / 4);
    if (max_alloc && max_alloc < budget)
        budget = (size_t)max_alloc;
    if (!rt->is_gpu) {
        long pages = sysconf(_SC_AVPHYS_PAGES), page = sysconf(_SC_PAGESIZE);
        if (pages > 0 && page > 0 && (size_t)pages / 8 * (size_t)page < budget)
            budget = (size_t)pages / 8 * (size_t)page;
    }
    return budget < VBG_BUDGET_FLOOR ? VBG_BUDGET_FLOOR : budget;
}

cl_context vbg_runtime_context(const vbg_runtime *rt) { return rt->context; }
cl_command_queue vbg_runtime_queue(const vbg_runtime *rt) { return rt->queue; }
cl_device_id vbg_runtime_device(const vbg_runtime *rt) { return rt->device; }
const char *vbg_runtime_device_name(const vbg_runtime *rt) { return rt->name; }
int vbg_runtime_is_gpu(const vbg_runtime *rt) { return rt->is_gpu; }

double vbg_event_seconds(cl_event e)
{
    cl_ulong a = 0, b = 0;
    if (clGetEventProfilingInfo(e, CL_PROFILING_COMMAND_START, sizeof a, &a, NULL) == CL_SUCCESS &&
        clGetEventProfilingInfo(e, CL_PROFILING_COMMAND_END, sizeof b, &b, NULL) == CL_SUCCESS &&
        b > a)
        return (double)(b - a) * 1e-9;
    return 0.0;
}

void vbg_runtime_versions(const vbg_runtime *rt, char *buf, size_t len)
{
    char pv[256] = "?", dv[256] = "?", drv[256] = "?";
    clGetPlatformInfo(rt->platform, CL_PLATFORM_VERSION, sizeof pv - 1, pv, NULL);
    clGetDeviceInfo(rt->device, CL_DEVICE_VERSION, sizeof dv - 1, dv, NULL);
    clGetDeviceInfo(rt->device, CL_DRIVER_VERSION, sizeof drv - 1, drv, NULL);
    pv[sizeof pv - 1] = dv[sizeof dv - 1] = drv[sizeof drv - 1] = '\0';
    snprintf(buf, len, "platform %s; device %s, driver %s", pv, dv, drv);
}

/* Reads a kernel file from VORBALL_KERNEL_DIR (development: edit kernels
 * without rebuilding). Returns malloc'd text or NULL. */
static char *read_kernel_file(const char *dir, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = NULL;
    if (fseek(f, 0, SEEK_END) == 0) {
        long n = ftell(f);
        if (n >= 0 && fseek(f, 0, SEEK_SET) == 0 && (buf = malloc((size_t)n + 1))) {
            if (fread(buf, 1, (size_t)n, f) != (size_t)n) {
                free(buf);
                buf = NULL;
            } else {
                buf[n] = '\0';
            }
        }
    }
    fclose(f);
    return buf;
}

static int build_failed(vb_ctx *ctx, vbg_runtime *rt, cl_program prog, const char *name, cl_int err)
{
    size_t len = 0;
    clGetProgramBuildInfo(prog, rt->device, CL_PROGRAM_BUILD_LOG, 0, NULL, &len);
    char *log = malloc(len + 1);
    if (log) {
        clGetProgramBuildInfo(prog, rt->device, CL_PROGRAM_BUILD_LOG, len, log, NULL);
        log[len] = '\0';
        /* The context message is bounded; the full log goes to stderr. */
        fprintf(stderr, "vorball: OpenCL build log of %s:\n%s\n", name, log);
    }
    vb_error(ctx, VB_EDEVICE, name, 0, "OpenCL program build failed: %s (%d): %.600s",
             cl_error_name(err), (int)err, log ? log : "");
    free(log);
    clReleaseProgram(prog);
    return VB_EDEVICE;
}

/* Program binary cache: building the kernels from source costs a few
 * hundred milliseconds on some drivers, more than the whole pipeline on a
 * small protein. Binaries live in $XDG_CACHE_HOME/vorball (else
 * $HOME/.cache/vorball), named by a 64-bit FNV-1a hash of the platform,
 * device and driver identity, the build options and the complete source, so
 * a changed kernel or driver never meets a stale binary. The cache is only
 * an accelerator: a file that is missing is built silently; one that cannot
 * be used is rebuilt after warning W750; a failure to write it is ignored.
 * VORBALL_NO_PROGRAM_CACHE (non-empty) turns it off.
 *
 * A driver handed a damaged binary may crash rather than fail (PoCL aborts
 * on a file one byte short and segfaults on half of one), so nothing reaches
 * clCreateProgramWithBinary unchecked: a file is
 *   magic (VBG_CACHE_MAGIC), then 4 little-endian-as-written u64: the key
 *   hash, the key length, the binary length, the FNV-1a sum of the binary;
 *   the key ("name\noptions\n"); the binary,
 * and it is used only when its length is exactly that, the hash and the key
 * are the ones asked for (a binary of the same kernel built with other
 * options under the expected name is refused) and the sum matches. */
#define VBG_CACHE_MAGIC "vorball program cache 1\n"
#define VBG_CACHE_MAGIC_LEN 24
#define VBG_CACHE_HEADER (VBG_CACHE_MAGIC_LEN + 4 * 8)

static uint64_t fnv1a(uint64_t h, const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++)
        h = (h ^ (unsigned char)s[i]) * 1099511628211ull;
    return (h ^ 0xff) * 1099511628211ull; /* field separator */
}

int vbg_cache_dir(char *dir, size_t cap, int make_dir)
{
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    int n;
    if (xdg && *xdg)
        n = snprintf(dir, cap, "%s/vorball", xdg);
    else if (home && *home)
        n = snprintf(dir, cap, "%s/.cache/vorball", home);
    else
        return 0;
    if (n <= 0 || (size_t)n >= cap)
        return 0;
    if (make_dir) {
        /* Parent first: $HOME/.cache may not exist yet. */
        char *slash = strrchr(dir, '/');
        if (slash && slash != dir) {
            *slash = '\0';
            int bad = mkdir(dir, 0755) != 0 && errno != EEXIST;
            *slash = '/';
            if (bad)
                return 0;
        }
        if (mkdir(dir, 0755) != 0 && errno != EEXIST)
            return 0;
    }
    return 1;
}

/* Path of the cached binary of (name, opts, src) and its key hash. */
static int cache_path(const vbg_runtime *rt, const char *name, const char *opts, const char *src,
                      char *path, size_t cap, int make_dir, uint64_t *hash)
{
    const char *off = getenv("VORBALL_NO_PROGRAM_CACHE"), *force = getenv("VORBALL_PROGRAM_CACHE");
    if (off && *off)
        return 0;
    /* PoCL caches what it builds itself (POCL_KERNEL_CACHE, on by default,
     * keyed by source and options), and asking it for a program binary
     * compiles every kernel once more for a dynamic work-group size: 22 s
     * for jfa_tiles.cl on a 2-core host against 0.8 s for the build, half of
     * a cold test_jfa. There vorball leaves caching to the driver unless
     * VORBALL_PROGRAM_CACHE=1 asks for its own, except for cover.cl (one
     * kernel, built by every `vertices` run): from its binary PoCL skips
     * preprocessing the source, which its own cache needs to find the
     * build. 2-core machine, 1crn --device cpu --threads 1, PoCL on one
     * thread, 10 processes: 0.172 -> 0.136 CPU s a process; once per cache,
     * the first run 2.5 -> 4.0 CPU s. */
    char plat[128] = "";
    if (!(force && *force) && strcmp(name, "cover.cl") != 0 &&
        clGetPlatformInfo(rt->platform, CL_PLATFORM_NAME, sizeof plat - 1, plat, NULL) == CL_SUCCESS &&
        strstr(plat, "Portable Computing Language"))
        return 0;
    char dir[900];
    if (!vbg_cache_dir(dir, sizeof dir, make_dir))
        return 0;
    uint64_t h = 1469598103934665603ull;
    char info[512];
    const cl_platform_info pq[] = {CL_PLATFORM_NAME, CL_PLATFORM_VERSION};
    const cl_device_info dq[] = {CL_DEVICE_NAME, CL_DEVICE_VERSION, CL_DRIVER_VERSION,
                                 CL_DEVICE_VENDOR};
    for (int k = 0; k < 2; k++) {
        info[0] = '\0';
        if (clGetPlatformInfo(rt->platform, pq[k], sizeof info - 1, info, NULL) != CL_SUCCESS)
            return 0;
        info[sizeof info - 1] = '\0';
        h = fnv1a(h, info, strlen(info));
    }
    for (int k = 0; k < 4; k++) {
        info[0] = '\0';
        if (clGetDeviceInfo(rt->device, dq[k], sizeof info - 1, info, NULL) != CL_SUCCESS)
            return 0;
        info[sizeof info - 1] = '\0';
        h = fnv1a(h, info, strlen(info));
    }
    h = fnv1a(h, opts, strlen(opts));
    h = fnv1a(h, src, strlen(src));
    *hash = h;
    int n = snprintf(path, cap, "%s/%s-%016llx.bin", dir, name, (unsigned long long)h);
    return n > 0 && (size_t)n < cap;
}

/* The key stored inside a cache file: kernel file name and options. */
static int cache_key(char *key, size_t cap, const char *name, const char *opts)
{
    int n = snprintf(key, cap, "%s\n%s\n", name, opts);
    return n > 0 && (size_t)n < cap ? n : -1;
}

/* Reads and checks the cache file at path. Returns the binary (malloc'd,
 * *len bytes), or NULL with *why saying what is wrong ("" when there is no
 * file: nothing to warn about). */
static unsigned char *cache_read(const char *path, uint64_t hash, const char *key, size_t key_len,
                                 size_t *len, const char **why)
{
    *why = "";
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    unsigned char *bin = NULL;
    unsigned char hdr[VBG_CACHE_HEADER];
    uint64_t v[4];
    long size = -1;
    if (fseek(f, 0, SEEK_END) != 0 || (size = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0)
        *why = "cannot read it";
    else if ((size_t)size < VBG_CACHE_HEADER || fread(hdr, 1, sizeof hdr, f) != sizeof hdr ||
             memcmp(hdr, VBG_CACHE_MAGIC, VBG_CACHE_MAGIC_LEN) != 0)
        *why = "not a vorball program cache file";
    else {
        memcpy(v, hdr + VBG_CACHE_MAGIC_LEN, sizeof v);
        if (v[0] != hash || v[1] != key_len)
            *why = "built for another kernel, options or device";
        else if (v[2] == 0 || v[2] != (uint64_t)size - VBG_CACHE_HEADER - key_len)
            *why = "its length does not match its header (truncated or padded)";
        else if (!(bin = malloc(key_len + (size_t)v[2])) ||
                 fread(bin, 1, key_len + (size_t)v[2], f) != key_len + (size_t)v[2])
            *why = bin ? "cannot read it" : "out of memory";
        else if (memcmp(bin, key, key_len) != 0)
            *why = "built for another kernel or other options";
        else if (fnv1a(1469598103934665603ull, (const char *)bin + key_len, (size_t)v[2]) != v[3])
            *why = "its checksum does not match (damaged)";
    }
    fclose(f);
    if (**why) {
        free(bin);
        return NULL;
    }
    memmove(bin, bin + key_len, (size_t)v[2]);
    *len = (size_t)v[2];
    return bin;
}

/* The cached binary built with opts, or NULL: silently when there is none,
 * after warning W750 when the file cannot be used (it is rebuilt and
 * rewritten by the caller). */
static cl_program cache_load(vb_ctx *ctx, const vbg_runtime *rt, const char *path, uint64_t hash,
                             const char *name, const char *opts)
{
    char key[2400];
    int key_len = cache_key(key, sizeof key, name, opts);
    if (key_len < 0)
        return NULL;
    size_t len = 0;
    const char *why;
    unsigned char *bin = cache_read(path, hash, key, (size_t)key_len, &len, &why);
    cl_program prog = NULL;
    if (bin) {
        const unsigned char *bp = bin;
        cl_int status = CL_SUCCESS, err;
        prog = clCreateProgramWithBinary(rt->context, 1, &rt->device, &len, &bp, &status, &err);
        if (!prog || err != CL_SUCCESS || status != CL_SUCCESS ||
            clBuildProgram(prog, 1, &rt->device, opts, NULL, NULL) != CL_SUCCESS) {
            if (prog)
                clReleaseProgram(prog);
            prog = NULL;
            why = "the OpenCL driver refused the binary";
        }
        free(bin);
    }
    if (!prog && *why)
        vb_warn(ctx, VB_W_PROGRAM_CACHE_BAD, path, 0, "cached program of %s cannot be used (%s): rebuilt from source",
                name, why);
    return prog;
}

/* Writes the device binary of prog to path with its header and key, through
 * a temporary file and a rename, so a concurrent reader never sees half a
 * file. */
static void cache_store(const vbg_runtime *rt, cl_program prog, const char *path, uint64_t hash,
                        const char *name, const char *opts)
{
    char key[2400];
    int key_len = cache_key(key, sizeof key, name, opts);
    size_t len = 0;
    if (key_len < 0 ||
        clGetProgramInfo(prog, CL_PROGRAM_BINARY_SIZES, sizeof len, &len, NULL) != CL_SUCCESS ||
        len == 0)
        return;
    unsigned char *bin = malloc(len);
    if (!bin)
        return;
    static atomic_uint serial;
    char tmp[1300];
    snprintf(tmp, sizeof tmp, "%s.%ld.%u.tmp", path, (long)getpid(),
             atomic_fetch_add(&serial, 1u));
    FILE *f = NULL;
    if (clGetProgramInfo(prog, CL_PROGRAM_BINARIES, sizeof bin, &bin, NULL) == CL_SUCCESS &&
        (f = fopen(tmp, "wb")) != NULL) {
        unsigned char hdr[VBG_CACHE_HEADER];
        uint64_t v[4] = {hash, (uint64_t)key_len, (uint64_t)len,
                         fnv1a(1469598103934665603ull, (const char *)bin, len)};
        memcpy(hdr, VBG_CACHE_MAGIC, VBG_CACHE_MAGIC_LEN);
        memcpy(hdr + VBG_CACHE_MAGIC_LEN, v, sizeof v);
        int ok = fwrite(hdr, 1, sizeof hdr, f) == sizeof hdr &&
                 fwrite(key, 1, (size_t)key_len, f) == (size_t)key_len &&
                 fwrite(bin, 1, len, f) == len;
        ok = fclose(f) == 0 && ok;
        if (!ok || rename(tmp, path) != 0)
            remove(tmp);
    }
    free(bin);
    (void)rt;
}

int vbg_program_get(vb_ctx *ctx, vbg_runtime *rt, const char *name, const char *options,
                    cl_program *out)
{
    char key[256];
    snprintf(key, sizeof key, "%s|%s", name, options ? options : "");
    for (int i = 0; i < rt->nprograms; i++)
        if (strcmp(rt->programs[i].key, key) == 0) {
            *out = rt->programs[i].program;
            return VB_OK;
        }
    if (rt->nprograms == VBG_MAX_PROGRAMS)
        return vb_error(ctx, VB_EINTERNAL, NULL, 0, "program cache full");

    const char *dir = getenv("VORBALL_KERNEL_DIR");
    char *disk = dir && *dir ? read_kernel_file(dir, name) : NULL;
    const char *src = disk ? disk : vbg_kernel_source(name);
    if (!src)
        return vb_error(ctx, VB_EINTERNAL, NULL, 0, "no kernel source named %s", name);
    /* No fast-math or mad flags: kernels compute candidates whose quality the
     * exact certifier judges, and PoCL and the GPU must round alike. Headers
     * of kernels loaded from disk are found beside them and in the core
     * wings they share with the host (../core, ../core/cells,
     * ../core/discrete). */
    char opts[2048];
    if (disk)
        snprintf(opts, sizeof opts,
                 "-cl-std=CL1.2 -I %s -I %s/../core -I %s/../core/cells -I %s/../core/discrete %s",
                 dir, dir, dir, dir, options ? options : "");
    else
        snprintf(opts, sizeof opts, "-cl-std=CL1.2 %s", options ? options : "");
    /* Kernels read from disk may include edited headers the hash cannot see. */
    char path[1200];
    uint64_t hash = 0;
    int cached = !disk && cache_path(rt, name, opts, src, path, sizeof path, 0, &hash);
    cl_program prog = cached ? cache_load(ctx, rt, path, hash, name, opts) : NULL;
    if (!prog) {
        cl_int err;
        prog = clCreateProgramWithSource(rt->context, 1, &src, NULL, &err);
        free(disk);
        disk = NULL;
        if (vbg_check(ctx, err, "clCreateProgramWithSource"))
            return VB_EDEVICE;
        err = clBuildProgram(prog, 1, &rt->device, opts, NULL, NULL);
        if (err != CL_SUCCESS)
            return build_failed(ctx, rt, prog, name, err);
        if (cached && cache_path(rt, name, opts, src, path, sizeof path, 1, &hash))
            cache_store(rt, prog, path, hash, name, opts);
    }
    free(disk);
    snprintf(rt->programs[rt->nprograms].key, sizeof rt->programs[0].key, "%s", key);
    rt->programs[rt->nprograms].program = prog;
    rt->nprograms++;
    *out = prog;
    return VB_OK;
}

static const char *type_name(cl_device_type t)
{
    if (t & CL_DEVICE_TYPE_GPU)
        return "GPU";
    if (t & CL_DEVICE_TYPE_CPU)
        return "CPU";
    if (t & CL_DEVICE_TYPE_ACCELERATOR)
        return "accelerator";
    return "other";
}

int vbg_list_devices(vb_ctx *ctx, FILE *out)
{
    cl_uint np = 0;
    vbg_pocl_cache_check(ctx);
    cl_int err = clGetPlatformIDs(0, NULL, &np);
    if (err != CL_SUCCESS || np == 0) {
        fprintf(out, "no OpenCL platform found (the reference backend, --device ref, still works)\n");
        return err == CL_SUCCESS || err == -1001 ? VB_OK : vbg_check(ctx, err, "clGetPlatformIDs");
    }
    cl_platform_id ps[16];
    if (np > 16)
        np = 16;
    if (vbg_check(ctx, clGetPlatformIDs(np, ps, NULL), "clGetPlatformIDs"))
        return VB_EDEVICE;
    fprintf(out, "#platform\tdevice\ttype\tversion\tfp64\tcompute_units\tglobal_mem_MiB\n");
    for (cl_uint p = 0; p < np; p++) {
        char pname[128] = "";
        clGetPlatformInfo(ps[p], CL_PLATFORM_NAME, sizeof pname - 1, pname, NULL);
        cl_device_id ds[16];
        cl_uint nd = 0;
        if (clGetDeviceIDs(ps[p], CL_DEVICE_TYPE_ALL, 16, ds, &nd) != CL_SUCCESS)
            continue;
        for (cl_uint i = 0; i < nd && i < 16; i++) {
            char dname[128] = "", ver[128] = "";
            cl_device_type t = 0;
            cl_uint cu = 0;
            cl_ulong mem = 0;
            clGetDeviceInfo(ds[i], CL_DEVICE_NAME, sizeof dname - 1, dname, NULL);
            clGetDeviceInfo(ds[i], CL_DEVICE_VERSION, sizeof ver - 1, ver, NULL);
            clGetDeviceInfo(ds[i], CL_DEVICE_TYPE, sizeof t, &t, NULL);
            clGetDeviceInfo(ds[i], CL_DEVICE_MAX_COMPUTE_UNITS, sizeof cu, &cu, NULL);
            clGetDeviceInfo(ds[i], CL_DEVICE_GLOBAL_MEM_SIZE, sizeof mem, &mem, NULL);
            fprintf(out, "%s\t%s\t%s\t%s\t%s\t%u\t%llu\n", pname, dname, type_name(t), ver,
                    device_has_fp64(ds[i]) ? "yes" : "no", cu,
                    (unsigned long long)(mem >> 20));
        }
    }
    return VB_OK;
}
