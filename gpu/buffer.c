/* Device buffers with a meter (vbg_buffer.h). */
#include "vbg_buffer.h"

int vbg_buf_ensure(vb_ctx *ctx, vbg_runtime *rt, vbg_meter *m, vbg_buf *b, size_t need,
                   cl_mem_flags flags)
{
    if (need == 0)
        need = 16;
    if (b->mem && b->size >= need)
        return VB_OK;
    vbg_buf_release(m, b);
    cl_int err = CL_SUCCESS;
    b->mem = clCreateBuffer(vbg_runtime_context(rt), flags, need, NULL, &err);
    if (err != CL_SUCCESS || !b->mem) {
        b->mem = NULL;
        return vbg_check(ctx, err != CL_SUCCESS ? err : CL_OUT_OF_RESOURCES, "clCreateBuffer");
    }
    b->size = need;
    m->live += need;
    if (m->live > m->peak)
        m->peak = m->live;
    return VB_OK;
}

void vbg_buf_release(vbg_meter *m, vbg_buf *b)
{
    if (b->mem) {
        clReleaseMemObject(b->mem);
        m->live -= b->size;
    }
    b->mem = NULL;
    b->size = 0;
}
