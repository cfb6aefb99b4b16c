/* Benchmark helpers (tests/verify/bench_*.c): one input read and
 * validated, and quadruples read from a file. */
#ifndef VT_BENCH_H
#define VT_BENCH_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vb_cover.h"
#include "vb_spheres.h"

/* Opens *ctx and reads input into *set (validated). 0, or 1 after printing
 * "tool: message" (*ctx may then be open, *set NULL). */
static inline int vt_bench_open(const char *tool, const char *input, vb_ctx **ctx,
                                vb_sphere_set **set)
{
    *set = NULL;
    if (vb_open(ctx, NULL) != VB_OK)
        return 1;
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    int rc = vb_spheres_read_file(*ctx, input, &ro, set);
    if (rc == VB_OK)
        rc = vb_spheres_validate(*ctx, *set, 4);
    if (rc != VB_OK) {
        fprintf(stderr, "%s: %s\n", tool, vb_errmsg(*ctx));
        return 1;
    }
    return 0;
}

/* Appends to q the quadruples of path ("a b c d" per line, sorted). 0, or
 * -1 when the file cannot be read or memory runs out. */
static inline int vt_read_quads(const char *path, vb_quad_list *q)
{
    FILE *f = fopen(path, "r");
    unsigned v[4];
    if (!f)
        return -1;
    while (fscanf(f, "%u %u %u %u", &v[0], &v[1], &v[2], &v[3]) == 4) {
        uint32_t t[4] = {v[0], v[1], v[2], v[3]};
        if (vb_quad_list_append(q, t, 1) != VB_OK) {
            fclose(f);
            return -1;
        }
    }
    fclose(f);
    return 0;
}

#endif
