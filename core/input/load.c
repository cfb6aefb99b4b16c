/* The one call that reads and checks a sphere file as every command does. */
#include "vb_spheres.h"

#include "vb_stage_clock.h"

int vb_spheres_load(vb_ctx *ctx, const char *path, const vb_read_options *ro,
                    const char *radii_path, size_t min_count, vb_sphere_set **out)
{
    return vb_spheres_load_clocked(ctx, path, ro, radii_path, min_count, out, NULL);
}

int vb_spheres_load_clocked(vb_ctx *ctx, const char *path, const vb_read_options *ro,
                            const char *radii_path, size_t min_count, vb_sphere_set **out,
                            vb_stage_clock *clk)
{
    *out = NULL;
    vb_radii_table *radii = NULL;
    int rc = VB_OK;
    vb_read_options o = *ro;
    if (radii_path && (rc = vb_radii_load(ctx, radii_path, &radii)) == VB_OK)
        o.radii = radii;
    vb_sphere_set *set = NULL;
    if (rc == VB_OK)
        rc = vb_spheres_read_file(ctx, path, &o, &set);
    vb_stage_lap(clk, VB_STAGE_READ);
    if (rc == VB_OK)
        rc = vb_spheres_validate(ctx, set, min_count);
    vb_stage_lap(clk, VB_STAGE_VALIDATE);
    vb_radii_free(radii);
    if (rc != VB_OK) {
        vb_spheres_free(set);
        return rc;
    }
    *out = set;
    return VB_OK;
}
