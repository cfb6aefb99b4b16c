/* libFuzzer target: --radii tables, then a small PDB whose elements the
 * table may name (lookups, duplicates by value with the built-in radii). */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static const char pdb[] =
    "ATOM      1  O   SER A   1       0.000   0.000   0.000  1.00  0.00           O\n"
    "ATOM      2  C   ALA A   2       3.000   0.000   0.000  1.00  0.00           C\n"
    "ATOM      3  N   ALA A   3       0.000   3.000   0.000  1.00  0.00           N\n"
    "ATOM      4  FE  HEM A   4       0.000   0.000   3.000  1.00  0.00          FE\n"
    "ATOM      5  Q   UNK A   5       0.000   0.000   0.000  1.00  0.00           Q\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    vb_ctx *ctx;
    const char *path = vb_fuzz_begin(data, size, &ctx);
    if (!path)
        return 0;
    vb_radii_table *radii = NULL;
    if (vb_radii_load(ctx, path, &radii) == VB_OK) {
        vb_read_options opt;
        memset(&opt, 0, sizeof opt);
        opt.radii = radii;
        opt.strict_elements = size > 0 && (data[0] & 1);
        vb_sphere_set *s = NULL;
        if (vb_spheres_read_buffer(ctx, "fuzz.pdb", pdb, sizeof pdb - 1, &opt, &s) == VB_OK)
            vb_spheres_validate(ctx, s, 1);
        vb_spheres_free(s);
        vb_radii_free(radii);
    }
    vb_close(ctx);
    return 0;
}
