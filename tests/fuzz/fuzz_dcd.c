/* libFuzzer target: the DCD reader, every frame (headers that claim more
 * atoms than the file holds, fixed atoms, unit cells, 4D records, either
 * byte order, cut and padded files). */
#include "fuzz_common.h"
#include "vb_dcd.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    vb_ctx *ctx;
    const char *path = vb_fuzz_begin(data, size, &ctx);
    if (!path)
        return 0;
    vb_dcd *d = NULL;
    if (vb_dcd_open(ctx, path, &d) == VB_OK) {
        size_t na = vb_dcd_atoms(d);
        /* Frames are read only when their coordinates fit in the input. */
        double *xyz = na <= size ? malloc(3 * na * sizeof *xyz) : NULL;
        double cell[6];
        int got = 1;
        for (int f = 0; xyz && got && f < 64; f++)
            if (vb_dcd_next(ctx, d, xyz, xyz + na, xyz + 2 * na, (f & 1) ? cell : NULL, &got) !=
                VB_OK)
                break;
        free(xyz);
        vb_dcd_close(d);
    }
    vb_close(ctx);
    return 0;
}
