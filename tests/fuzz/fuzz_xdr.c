/* libFuzzer target: the XTC and TRR readers (headers, the xtc3d decoder,
 * TRR's float/double blocks) over an in-memory stream, every frame read. */
#include <stdio.h>
#include <stdlib.h>

#include "fuzz_common.h"
#include "vb_xdr.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0)
        return 0;
    vb_ctx *ctx = NULL;
    vb_config cfg = {.verbosity = 0};
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 0;
    FILE *f = fmemopen((void *)data, size, "rb");
    vb_xdr_traj *t = NULL;
    if (f && vb_xdr_open_stream(ctx, "fuzz", f, &t) == VB_OK) {
        /* The caller's frame buffer is bounded as the topology bounds it in
         * vb_frame_source (an atom count no topology matches stops there). */
        size_t na = vb_xdr_atoms(t);
        double *xyz = na <= 100000 ? malloc(3 * na * sizeof *xyz) : NULL;
        int got = 1;
        for (int k = 0; xyz && got && k < 64; k++)
            if (vb_xdr_next(ctx, t, xyz, NULL, &got) != VB_OK)
                break;
        free(xyz);
        vb_xdr_close(t);
    }
    vb_close(ctx);
    return 0;
}
