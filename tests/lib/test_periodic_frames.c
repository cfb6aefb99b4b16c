/* Periodic vertices frame by frame (lib/vb_periodic_frames.h) on the NGL
 * MD trajectory (corpus/data/ngl_md_10frames.xtc over its PDB, 183 atoms
 * in a cubic box that changes every frame): every frame runs in its own
 * box, and a frame's result equals the one-set call on that frame's atoms
 * with that box, byte for byte; the frames' coordinates are the shortest
 * decimals of their floats. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vorball.h"

typedef struct seen {
    int frames;
    double edge[10];
    size_t vertices[10];
    char *first;       /* frame 0's periodic file */
    size_t first_len;
    vb_sphere_set *copy; /* frame 0's atoms (decimals), for the one-set call */
} seen;

static char *write_bytes(vb_ctx *ctx, const vb_periodic_vertices *v, size_t *len)
{
    char *buf = NULL;
    FILE *f = open_memstream(&buf, len);
    CHECK_INT(vb_periodic_write(ctx, f, v, 0, NULL), VB_OK);
    fclose(f);
    return buf;
}

static vb_ctx *g_ctx;

static int on_frame(void *arg, long frame, int model, const vb_sphere_set *set, const vb_box *box,
                    const vb_periodic_result *res)
{
    seen *s = arg;
    CHECK_INT(model, (int)frame + 1);
    if (frame < 10) {
        s->edge[frame] = box->v[0];
        s->vertices[frame] = res->v.n;
    }
    CHECK(box->v[0] == box->v[4] && box->v[4] == box->v[8] && box->v[1] == 0.0);
    CHECK(set->ex != NULL); /* decimals of the frame's floats */
    /* An XTC coordinate is a float in nm: its decimal is the shortest that
     * reads back to the float (at most 9 digits), in Angstrom, and the
     * set's double is that decimal's (not the 17 digits of the float). */
    for (size_t i = 0; i < set->n; i++) {
        CHECK(set->ex[i].mant < 1000000000 && set->ex[i].mant > -1000000000);
        CHECK(set->x[i] == vb_decimal_double(set->ex[i]));
    }
    if (frame == 0) {
        s->first = write_bytes(g_ctx, &res->v, &s->first_len);
        vb_read_options ro = {0};
        char *xyzr = malloc(set->n * 200 + 1);
        size_t w = 0;
        for (size_t i = 0; i < set->n; i++) {
            char c[4][48];
            vb_decimal_format(set->ex[i], c[0], sizeof c[0]);
            vb_decimal_format(set->ey[i], c[1], sizeof c[1]);
            vb_decimal_format(set->ez[i], c[2], sizeof c[2]);
            vb_decimal_format(set->er[i], c[3], sizeof c[3]);
            w += (size_t)sprintf(xyzr + w, "%s %s %s %s\n", c[0], c[1], c[2], c[3]);
        }
        CHECK_INT(vb_spheres_read_buffer(g_ctx, "frame0.xyzr", xyzr, w, &ro, &s->copy), VB_OK);
        free(xyzr);
    }
    s->frames++;
    return VB_OK;
}

int main(void)
{
    vb_config cfg0 = {0, NULL};
    if (vb_open(&g_ctx, &cfg0) != VB_OK)
        return 1;
    const char *src = getenv("VORBALL_SOURCE_DIR");
    char topo[4096], traj[4096];
    snprintf(topo, sizeof topo, "%s/corpus/data/ngl_md_ascii_trj.pdb", src ? src : ".");
    snprintf(traj, sizeof traj, "%s/corpus/data/ngl_md_10frames.xtc", src ? src : ".");
    vb_read_options ro = {0};
    ro.keep_water = 1;
    vb_frame_range all = {0, -1, 1};
    vb_vertices_config cfg = {0};
    cfg.device = VB_DEVICE_REF;
    seen s;
    memset(&s, 0, sizeof s);
    long selected = 0;
    int rc = vb_periodic_run_frames(g_ctx, topo, traj, &ro, &all, NULL, &cfg, on_frame, &s,
                                    &selected);
    CHECK_INT(rc, VB_OK);
    CHECK_INT(selected, 10);
    CHECK_INT(s.frames, 10);
    /* MDAnalysis' boxes (corpus/golden/trajectories/ngl_md_10frames.xtc.expect). */
    CHECK(s.edge[0] == 56.064 && s.edge[1] == 56.035 && s.edge[2] == 56.068);
    for (int k = 0; k < 10; k++)
        CHECK(s.vertices[k] > 183);
    /* Frame 0 alone, in its box, through the one-set call: the same bytes. */
    if (s.copy) {
        CHECK_INT(vb_spheres_validate(g_ctx, s.copy, 4), VB_OK);
        const char *edge[3] = {"56.064", "56.064", "56.064"};
        vb_box b;
        CHECK_INT(vb_box_parse_args(g_ctx, edge, 3, &b), VB_OK);
        vb_periodic_result res;
        vb_periodic_result_init(&res);
        CHECK_INT(vb_periodic_vertices_run(g_ctx, s.copy, &b, &cfg, vb_default_backends(), &res),
                  VB_OK);
        size_t len = 0;
        char *one = write_bytes(g_ctx, &res.v, &len);
        CHECK(len > 0 && len == s.first_len && memcmp(one, s.first, len) == 0);
        free(one);
        vb_periodic_result_free(&res);
        vb_spheres_free(s.copy);
    }
    free(s.first);
    /* One box for every frame instead of each frame's. */
    memset(&s, 0, sizeof s);
    const char *big[3] = {"60", "60", "60"};
    vb_box fixed;
    CHECK_INT(vb_box_parse_args(g_ctx, big, 3, &fixed), VB_OK);
    vb_frame_range two = {0, 2, 1};
    CHECK_INT(vb_periodic_run_frames(g_ctx, topo, traj, &ro, &two, &fixed, &cfg, on_frame, &s,
                                     &selected),
              VB_OK);
    CHECK_INT(selected, 2);
    CHECK(s.edge[0] == 60.0 && s.edge[1] == 60.0);
    free(s.first);
    vb_spheres_free(s.copy);
    vb_close(g_ctx);
    VB_TEST_END();
}
