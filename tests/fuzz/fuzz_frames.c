/* libFuzzer target: the frame reader (multi-model PDB and PQR streamed
 * block by block, mmCIF model by model, XYZR), every frame validated. */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = vb_fuzz_file(data, size);
    vb_ctx *ctx = NULL;
    vb_config cfg = {.verbosity = 0};
    if (!path || vb_open(&ctx, &cfg) != VB_OK)
        return 0;
    vb_read_options opt;
    memset(&opt, 0, sizeof opt);
    opt.max_spheres = 4096;
    if (size > 0) {
        opt.model = data[0] & 3;
        opt.keep_water = (data[0] >> 2) & 1;
        opt.drop_hydrogens = (data[0] >> 3) & 1;
    }
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
