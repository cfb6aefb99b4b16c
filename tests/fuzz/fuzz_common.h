/* Shared body of the libFuzzer targets: read a buffer as one format (or by
 * detection), validate what was read, free everything. Any crash, leak,
 * sanitizer report or hang is a finding; errors are expected answers. */
#ifndef VB_FUZZ_COMMON_H
#define VB_FUZZ_COMMON_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "vb_spheres.h"

/* Small limits keep each run fast (the limit path is exercised too); the
 * first byte picks the reading options, so they are fuzzed along. The caller
 * zeroes *opt and sets its format. */
static inline void vb_fuzz_options(const uint8_t *data, size_t size, vb_read_options *opt)
{
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
    memset(&opt, 0, sizeof opt);
    opt.format = format;
    vb_fuzz_options(data, size, &opt);
    return vb_fuzz_read_with(data, size, &opt);
}

/* For readers that take a path: writes the input to this process's own
 * temporary file and returns its name (static), or NULL. */
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static char vb_fuzz_path[256];

static inline void vb_fuzz_remove(void)
{
    remove(vb_fuzz_path);
}

static inline const char *vb_fuzz_file(const uint8_t *data, size_t size)
{
    char *path = vb_fuzz_path;
    if (!path[0]) {
        const char *dir = getenv("TMPDIR");
        snprintf(path, sizeof vb_fuzz_path, "%s/vb_fuzz_input.%ld", dir && *dir ? dir : "/tmp",
                 (long)getpid());
        atexit(vb_fuzz_remove);
    }
    FILE *f = fopen(path, "wb");
    if (!f)
        return NULL;
    int ok = fwrite(data, 1, size, f) == size;
    ok = fclose(f) == 0 && ok;
    return ok ? path : NULL;
}

/* The start of a target that reads a path: the input in a file (its name
 * returned) and a quiet context in *ctx; NULL (nothing to free) when either
 * fails. */
static inline const char *vb_fuzz_begin(const uint8_t *data, size_t size, vb_ctx **ctx)
{
    const char *path = vb_fuzz_file(data, size);
    vb_config cfg = {.verbosity = 0};
    *ctx = NULL;
    if (!path || vb_open(ctx, &cfg) != VB_OK)
        return NULL;
    return path;
}

#endif
