/* libFuzzer target: the vertex-file reader (tsv, json, Voronota), as
 * `verify` and `crosscheck` read a file. */
#include "fuzz_common.h"
#include "vb_vertex_io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    vb_ctx *ctx = NULL;
    vb_config cfg = {.verbosity = 0};
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 0;
    vb_vertex_list v;
    vb_vertex_list_init(&v);
    vb_vertex_format fmt;
    long *lines = NULL;
    if (vb_vertex_read_buffer(ctx, "fuzz", (const char *)data, size, &v, &fmt, &lines) == VB_OK)
        vb_vertex_list_sort(&v);
    free(lines);
    vb_vertex_list_free(&v);
    vb_close(ctx);
    return 0;
}
