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
    vb_fuzz_options(data, size, VB_FMT_AUTO, &opt);
    vb_sphere_set *set = NULL;
    vbi_read_psf(ctx, "fuzz", (const char *)data, size, &opt, &set);
    vb_spheres_free(set);
    vb_close(ctx);
    return 0;
}
