/* Unit tests of the OpenCL runtime on the default CPU device (PoCL in CI):
 * device choice, disk kernels with includes, build-log reporting, errors. */
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vbg_runtime.h"

static void test_kind_parse(vb_ctx *ctx)
{
    vb_device_kind k;
    CHECK_INT(vb_device_kind_parse(ctx, "ref", &k), VB_OK);
    CHECK_INT(k, VB_DEVICE_REF);
    CHECK_INT(vb_device_kind_parse(ctx, "gpu", &k), VB_OK);
    CHECK_INT(k, VB_DEVICE_GPU);
    CHECK_INT(vb_device_kind_parse(ctx, "tpu", &k), VB_EMISUSE);
    CHECK(strstr(vb_errmsg(ctx), "tpu") != NULL);
}

static void test_axpy(vb_ctx *ctx, vbg_runtime *rt)
{
    cl_program prog;
    CHECK_INT(vbg_program_get(ctx, rt, "probe_add.cl", NULL, &prog), VB_OK);
    cl_program again;
    CHECK_INT(vbg_program_get(ctx, rt, "probe_add.cl", NULL, &again), VB_OK);
    CHECK(prog == again); /* cached */
    cl_int err;
    cl_kernel k = clCreateKernel(prog, "probe_axpy", &err);
    CHECK_INT(err, CL_SUCCESS);
    double x[4] = {1, 2, 3, 4}, y[4] = {10, 20, 30, 40};
    cl_mem bx = clCreateBuffer(vbg_runtime_context(rt), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                               sizeof x, x, &err);
    cl_mem by = clCreateBuffer(vbg_runtime_context(rt), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                               sizeof y, y, &err);
    clSetKernelArg(k, 0, sizeof bx, &bx);
    clSetKernelArg(k, 1, sizeof by, &by);
    size_t n = 4;
    CHECK_INT(clEnqueueNDRangeKernel(vbg_runtime_queue(rt), k, 1, NULL, &n, NULL, 0, NULL, NULL),
              CL_SUCCESS);
    CHECK_INT(clEnqueueReadBuffer(vbg_runtime_queue(rt), by, CL_TRUE, 0, sizeof y, y, 0, NULL, NULL),
              CL_SUCCESS);
    CHECK(y[0] == 12.5 && y[3] == 50.0);
    clReleaseMemObject(bx);
    clReleaseMemObject(by);
    clReleaseKernel(k);
}

static void test_errors(vb_ctx *ctx, vbg_runtime *rt)
{
    cl_program prog;
    CHECK_INT(vbg_program_get(ctx, rt, "probe_broken.cl", NULL, &prog), VB_EDEVICE);
    CHECK(strstr(vb_errmsg(ctx), "undefined_symbol_for_test") != NULL);
    CHECK_INT(vbg_program_get(ctx, rt, "no_such_kernel.cl", NULL, &prog), VB_EINTERNAL);
    CHECK_INT(vbg_check(ctx, CL_OUT_OF_RESOURCES, "clFoo"), VB_EDEVICE);
    CHECK_STR(vb_errmsg(ctx), "clFoo: CL_OUT_OF_RESOURCES (-5)");
}

/* VORBALL_DEVICE_INDEX (one device per MPI rank): taken modulo the
 * devices of the kind, so index 7 on a host with one CPU device opens that
 * device; a value that is not a number is refused, never read as 0. */
static void test_device_index(vb_ctx *ctx)
{
    vbg_runtime *a = NULL, *b = NULL;
    unsetenv("VORBALL_DEVICE_INDEX");
    if (vbg_runtime_open(ctx, VB_DEVICE_CPU, &a) != VB_OK)
        return;
    setenv("VORBALL_DEVICE_INDEX", "7", 1);
    CHECK_INT(vbg_runtime_open(ctx, VB_DEVICE_CPU, &b), VB_OK);
    if (b)
        CHECK_STR(vbg_runtime_device_name(b), vbg_runtime_device_name(a));
    vbg_runtime_close(b);
    const char *bad[] = {"x", "-1", "1x", "70000"};
    for (int k = 0; k < 4; k++) {
        b = NULL;
        setenv("VORBALL_DEVICE_INDEX", bad[k], 1);
        CHECK_INT(vbg_runtime_open(ctx, VB_DEVICE_CPU, &b), VB_EMISUSE);
        CHECK(b == NULL);
        CHECK(strstr(vb_errmsg(ctx), "VORBALL_DEVICE_INDEX") != NULL);
    }
    unsetenv("VORBALL_DEVICE_INDEX");
    vbg_runtime_close(a);
}

int main(void)
{
    vb_ctx *ctx;
    vb_open(&ctx, NULL);
    test_kind_parse(ctx);
    const char *src = getenv("VORBALL_SOURCE_DIR");
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/tests/gpu/kernels", src ? src : ".");
    setenv("VORBALL_KERNEL_DIR", dir, 1);
    vbg_runtime *rt;
    int rc = vbg_runtime_open(ctx, VB_DEVICE_CPU, &rt);
    CHECK_INT(rc, VB_OK);
    if (rc == VB_OK) {
        CHECK(!vbg_runtime_is_gpu(rt));
        CHECK(strlen(vbg_runtime_device_name(rt)) > 0);
        test_axpy(ctx, rt);
        test_errors(ctx, rt);
        vbg_runtime_close(rt);
    }
    test_device_index(ctx);
    vbg_runtime *none;
    CHECK_INT(vbg_runtime_open(ctx, VB_DEVICE_REF, &none), VB_EMISUSE);
    CHECK(none == NULL);
    vb_close(ctx);
    VB_TEST_END();
}
