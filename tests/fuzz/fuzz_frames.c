/* libFuzzer target: the frame reader (multi-model PDB and PQR streamed
 * block by block, mmCIF model by model, XYZR), every frame validated. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    vb_ctx *ctx;
    const char *path = vb_fuzz_begin(data, size, &ctx);
    if (!path)
        return 0;
    vb_read_options opt;
    memset(&opt, 0, sizeof opt);
    vb_fuzz_options(data, size, &opt);
    vb_frame_reader *rd = NULL;
    if (vb_frame_reader_open(ctx, path, &opt, &rd) == VB_OK) {
        for (int f = 0; f < 64; f++) {
            vb_sphere_set *s = NULL;
            int model;
            if (vb_frame_reader_next(ctx, rd, &s, &model) != VB_OK || !s)
                break;
            vb_spheres_validate(ctx, s, 1);
            vb_spheres_free(s);
        }
        vb_frame_reader_close(rd);
    }
    vb_close(ctx);
    return 0;
}
