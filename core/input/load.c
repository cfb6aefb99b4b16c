/* The one call that reads and checks a sphere file as every command does. */
#include "vb_spheres.h"

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "vb_stage_clock.h"

size_t vb_spheres_count_hint(const char *path)
{
    if (!path || strcmp(path, "-") == 0)
        return 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    unsigned char head[3] = {0, 0, 0};
    size_t got = fread(head, 1, sizeof head, f);
    struct stat st;
    int ok = fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode);
    fclose(f);
    int gzip = got >= 2 && head[0] == 0x1f && head[1] == 0x8b;
    int bzip2 = got == 3 && memcmp(head, "BZh", 3) == 0;
    if (!ok || gzip || bzip2)
        return 0;
    return (size_t)st.st_size / VB_BYTES_PER_SPHERE_MAX;
}

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
