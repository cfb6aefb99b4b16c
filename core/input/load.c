/* The one call that reads and checks a sphere file as every command does. */
#include "vb_spheres.h"

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "vb_stage_clock.h"
#include "vbi_input.h"

/* XYZR spends one line per sphere: the longest whole line of the file's
 * head (at least 8 bytes, "0 0 0 1\n"), or 0 when the head is not XYZR. */
static size_t xyzr_line_bytes(const char *head, size_t got)
{
    size_t whole = got;
    while (whole > 0 && head[whole - 1] != '\n')
        whole--;
    if (whole == 0)
        return 0;
    vbi_detector d;
    vbi_detector_init(&d);
    vbi_detector_feed(&d, head, whole);
    vb_format f;
    if (vbi_detector_result(&d, &f) != VB_OK || f != VB_FMT_XYZR)
        return 0;
    size_t longest = 8;
    vbi_lines it;
    vbi_lines_init(&it, head, whole, 1);
    const char *line;
    size_t n;
    while (vbi_lines_next(&it, &line, &n))
        if (n + 1 > longest)
            longest = n + 1;
    return longest;
}

size_t vb_spheres_count_hint(const char *path)
{
    if (!path || strcmp(path, "-") == 0)
        return 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    char head[4096];
    size_t got = fread(head, 1, sizeof head, f);
    struct stat st;
    int ok = fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode);
    fclose(f);
    const unsigned char *h = (const unsigned char *)head;
    int gzip = got >= 2 && h[0] == 0x1f && h[1] == 0x8b;
    int bzip2 = got >= 3 && memcmp(head, "BZh", 3) == 0;
    if (!ok || gzip || bzip2)
        return 0;
    size_t line = xyzr_line_bytes(head, got);
    return (size_t)st.st_size / (line ? line : VB_BYTES_PER_SPHERE_MAX);
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
