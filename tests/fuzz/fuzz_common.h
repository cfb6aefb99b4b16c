/* Shared body of the libFuzzer targets: read a buffer as one format (or by
 * detection), validate what was read, free everything. Any crash, leak,
 * sanitizer report or hang is a finding; errors are expected answers. */
#ifndef VB_FUZZ_COMMON_H
#define VB_FUZZ_COMMON_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "vb_spheres.h"

/* Options of a run: small limits keep each run fast (the limit path is
 * exercised too); the first byte picks the others, so they are fuzzed along. */
static inline void vb_fuzz_options(const uint8_t *data, size_t size, vb_format format,
                            vb_read_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->format = format;
    opt->max_spheres = 4096;
    if (size > 0) {
        opt->model = data[0] & 3;
        opt->keep_water = (data[0] >> 2) & 1;
        opt->drop_hydrogens = (data[0] >> 3) & 1;
        opt->strict_elements = (data[0] >> 4) & 1;
    }
}

/* Reads the buffer with opt, validates what was read, frees everything. */
static inline int vb_fuzz_read_with(const uint8_t *data, size_t size, const vb_read_options *opt)
{
    vb_ctx *ctx = NULL;
    vb_config cfg = {.verbosity = 0};
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 0;
    vb_sphere_set *set = NULL;
    if (vb_spheres_read_buffer(ctx, "fuzz", (const char *)data, size, opt, &set) == VB_OK)
        vb_spheres_validate(ctx, set, 1);
    vb_spheres_free(set);
    vb_close(ctx);
    return 0;
}

static inline int vb_fuzz_read(const uint8_t *data, size_t size, vb_format format)
{
    vb_read_options opt;
    vb_fuzz_options(data, size, format, &opt);
    return vb_fuzz_read_with(data, size, &opt);
}

#endif
