/* libFuzzer target: the PSF topology reader (!NATOM section, elements from
 * masses). */
#include "fuzz_common.h"
#include "vbi_input.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    vb_ctx *ctx = NULL;
    vb_config cfg = {.verbosity = 0};
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 0;
    vb_read_options opt;
    memset(&opt, 0, sizeof opt);
    opt.format = VB_FMT_AUTO;
    vb_fuzz_options(data, size, &opt);
    vb_sphere_set *set = NULL;
    vbi_read_psf(ctx, "fuzz", (const char *)data, size, &opt, &set);
    vb_spheres_free(set);
    vb_close(ctx);
    return 0;
}
