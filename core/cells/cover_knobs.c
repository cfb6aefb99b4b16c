/* The cover's knobs read from the environment (vb_cover.h): the device
 * batch, the pipeline's parts and the early take of a batch's finished
 * cells. Only speed depends on them. */
#include "vb_cover.h"

#include <stdlib.h>
#include <string.h>

size_t vb_cover_batch_cells(const vb_cover_options *opt)
{
    if (opt && opt->batch_cells)
        return opt->batch_cells;
    const char *e = getenv("VORBALL_COVER_BATCH");
    if (e && *e) {
        char *end;
        unsigned long long v = strtoull(e, &end, 10);
        if (*end == '\0' && v >= 1 && v <= (1ull << 30))
            return (size_t)v;
    }
    return 0;
}

unsigned vb_cover_pipeline_parts(void)
{
    const char *e = getenv("VORBALL_COVER_PARTS");
    if (e && *e) {
        char *end;
        unsigned long v = strtoul(e, &end, 10);
        if (*end == '\0' && v >= 1 && v <= 64)
            return (unsigned)v;
    }
    return 1u;
}

int vb_cover_early_on(const vb_cover_backend *be)
{
    const char *e = getenv("VORBALL_COVER_EARLY");
    if (e && strcmp(e, "0") == 0)
        return 0;
    if (e && strcmp(e, "1") == 0)
        return 1;
    return be && be->resume_spread;
}
