/* The 2D pipeline stages of the channel analysis (the Facet-JFA paper's
 * Fig. 5): the planar cut of a molecule, its frame run, and the eight
 * panels rendered from the flag bytes and labels the pipeline returns. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vbc_frame.h"

#define GAP 4

static void put(uint8_t *px, uint32_t r, uint32_t g, uint32_t b)
{
    px[0] = (uint8_t)r;
    px[1] = (uint8_t)g;
    px[2] = (uint8_t)b;
}

/* A pleasant, stable colour per Voronoi region. */
static void label_colour(uint32_t l, uint8_t *px)
{
    uint32_t h = l * 2654435761u;
    put(px, 90 + (h >> 24) % 150, 90 + (h >> 16) % 150, 90 + (h >> 8) % 150);
}

int vbc_planar_cut(vb_ctx *ctx, const vb_sphere_set *s, int normal, vb_sphere_set **out)
{
    *out = NULL;
    int ax = normal == 0 ? 1 : 0, ay = normal == 2 ? 1 : 2;
    const double *c[3] = {s->x, s->y, s->z};
    double centre = 0.0;
    for (size_t i = 0; i < s->n; i++)
        centre += c[normal][i];
    centre /= (double)s->n;
    vb_sphere_set *cut;
    int rc = vb_spheres_new(ctx, "planar cut", s->n, 0, &cut);
    if (rc != VB_OK)
        return rc;
    cut->n = 0;
    for (size_t i = 0; i < s->n; i++) {
        double d = c[normal][i] - centre;
        if (fabs(d) >= s->r[i])
            continue;
        cut->x[cut->n] = c[ax][i];
        cut->y[cut->n] = c[ay][i];
        cut->r[cut->n] = sqrt(s->r[i] * s->r[i] - d * d);
        cut->n++;
    }
    if (cut->n == 0) {
        vb_spheres_free(cut);
        return vb_error(ctx, VB_EINPUT_EMPTY, NULL, 0, "the slice for --png meets no atom");
    }
    *out = cut;
    return VB_OK;
}

void vbc_image_free(vbc_image *img)
{
    free(img->rgb);
    memset(img, 0, sizeof *img);
}

int vbc_stages_render(vb_ctx *ctx, vbc_pipe *pipe, const vb_sphere_set *s, double probe, int n,
                      int normal, const vbc_options *opt, vbc_image *img)
{
    memset(img, 0, sizeof *img);
    vb_sphere_set *cut = NULL;
    vbc_frame F;
    memset(&F, 0, sizeof F);
    vbc_grid g;
    int rc = vbc_planar_cut(ctx, s, normal, &cut);
    if (rc == VB_OK)
        rc = vbc_grid_fit(ctx, cut, probe, n, 2, &g);
    vbc_options o2 = *opt;
    o2.keep_cavities = 1; /* in a cut, a pore is often closed: show it */
    o2.pore = NULL;       /* the pore sweep is a 3D stage */
    if (rc == VB_OK)
        rc = vbc_frame_run(ctx, pipe, &g, cut, probe, VBC_WANT_FLAGS | VBC_WANT_LABELS, &o2, &F);
    if (rc != VB_OK)
        goto done;

    uint32_t W = 4 * (uint32_t)n + 5 * GAP, H = 2 * (uint32_t)n + 3 * GAP;
    uint8_t *rgb = malloc((size_t)W * H * 3);
    if (!rgb) {
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "picture of %ux%u", W, H);
        goto done;
    }
    memset(rgb, 255, (size_t)W * H * 3);
    for (int panel = 0; panel < 8; panel++) {
        uint32_t ox = GAP + (uint32_t)(panel % 4) * ((uint32_t)n + GAP);
        uint32_t oy = GAP + (uint32_t)(panel / 4) * ((uint32_t)n + GAP);
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                size_t v = (size_t)i + (size_t)n * (size_t)j;
                unsigned f = F.out.flags[v];
                /* Row 0 of the image is the top: flip y. */
                uint8_t *px = rgb + 3 * ((size_t)(oy + (uint32_t)(n - 1 - j)) * W + ox + (uint32_t)i);
                int in_atom = 0, in_sas = 0;
                if (panel < 2) {
                    for (size_t a = 0; a < cut->n && !in_atom; a++) {
                        double dx = i + 0.5 - F.atoms4[4 * a], dy = j + 0.5 - F.atoms4[4 * a + 1];
                        double d = sqrt(dx * dx + dy * dy) * g.h;
                        in_atom |= d <= cut->r[a];
                        in_sas |= d <= cut->r[a] + probe;
                    }
                }
                switch (panel) {
                case 0: /* (a) input atoms */
                    if (in_atom) put(px, 120, 120, 120);
                    break;
                case 1: /* (b) solvent accessible disks */
                    if (in_atom) put(px, 120, 120, 120);
                    else if (in_sas) put(px, 170, 200, 240);
                    break;
                case 2: /* (c) Voronoi regions */
                    label_colour(F.out.labels[v], px);
                    break;
                case 3: /* (d) Voronoi edges */
                    if (f & VBC_F_EDGE) put(px, 0, 0, 0);
                    break;
                case 4: /* (e) atomic region */
                    if (f & VBC_F_ATOMIC) put(px, 240, 150, 60);
                    break;
                case 5: /* (f) molecular region */
                    if (f & VBC_F_MOLECULAR) put(px, 240, 210, 80);
                    break;
                case 6: /* (g) interior */
                    if (f & VBC_F_INTERIOR) put(px, 240, 210, 80);
                    else if (f & VBC_F_ATOMIC) put(px, 250, 225, 200);
                    break;
                default: /* (h) channels over the atomic region */
                    if (f & VBC_F_CHANNEL) put(px, 30, 90, 230);
                    else if (f & VBC_F_ATOMIC) put(px, 250, 200, 150);
                    break;
                }
            }
        if (panel == 7)
            for (size_t t = 0; t < F.result.nchannels; t++) {
                const vbc_channel *ch = &F.result.channels[t];
                for (size_t u = 0; u < ch->npoints; u++) {
                    const vbc_point *p = F.result.points + ch->first_point + u;
                    int i = (int)((p->x - g.origin[0]) / g.h), j = (int)((p->y - g.origin[1]) / g.h);
                    if (i >= 0 && j >= 0 && i < n && j < n)
                        put(rgb + 3 * ((size_t)(oy + (uint32_t)(n - 1 - j)) * W + ox + (uint32_t)i),
                            200, 0, 0);
                }
            }
    }
    img->w = W;
    img->h = H;
    img->rgb = rgb;
done:
    vbc_frame_free(&F);
    vb_spheres_free(cut);
    return rc;
}
