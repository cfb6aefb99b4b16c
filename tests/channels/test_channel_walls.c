/* The pore verdict's rasters (core/discrete/vbc_walls.h, issue 33):
 * - every pixel the float filter calls blocked or free is what the host's
 *   double test (vbc_cells_within, reach VBC_WALL_PROBE) says, on hollowed
 *   clouds along tilted axes, near the origin and 3,000 A from it, and on
 *   pixels that lie exactly at an atom's reach (those must be unsure);
 * - the verdict from the twin's rasters (vbc_pore_judge_on) is
 *   vbc_pore_judge's, every field, judged to the end and stopped early;
 * - the kernel (gpu/channel_walls.cl, on the OpenCL device when one opens)
 *   gives the twin's words bit for bit. */
#include "synth.h"
#include "vb_test.h"
#include "vbc_channel_gpu.h"
#include "channel_walls_math.h"
#include "vbc_walls.h"

static void mark(int32_t atom, void *user)
{
    (void)atom;
    *(int *)user = 1;
}

/* A cloud of n atoms in a cube of side L at `off`, radii 1 to 2 A, with a
 * tube of radius `hole` A along z through its middle left empty. */
static vb_sphere_set *hollow_cloud(size_t n, double L, double off, uint64_t seed, double hole)
{
    vb_sphere_set *s = vb_test_spheres_alloc(n, 0);
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        double x = L * synth_uniform(&seed), y = L * synth_uniform(&seed);
        double z = L * synth_uniform(&seed), r = 1.0 + synth_uniform(&seed);
        if ((x - L / 2) * (x - L / 2) + (y - L / 2) * (y - L / 2) < hole * hole)
            continue;
        s->x[m] = x + off;
        s->y[m] = y + off;
        s->z[m] = z + off;
        s->r[m++] = r;
    }
    s->n = m;
    return s;
}

/* A pore along a tilted axis through the tube: n planes ds A apart. */
static void tilted_pore(vbc_pore *p, double L, double off, double tilt, size_t n, double ds)
{
    memset(p, 0, sizeof *p);
    p->pts = calloc(n, sizeof *p->pts);
    p->n = n;
    double u[3] = {tilt, 0.5 * tilt, 1.0}, nu = sqrt(1.0 + 1.25 * tilt * tilt);
    for (int a = 0; a < 3; a++)
        p->axis.u[a] = u[a] / nu;
    for (size_t k = 0; k < n; k++) {
        double t = -8.0 + ds * (double)k;
        p->pts[k].x = off + L / 2 + t * p->axis.u[0] + 0.3 * (double)(k % 5);
        p->pts[k].y = off + L / 2 + t * p->axis.u[1] - 0.2 * (double)(k % 3);
        p->pts[k].z = off + t * p->axis.u[2];
        p->pts[k].s = t;
        p->pts[k].r = 0.5 + 0.1 * (double)(k % 11);
    }
}

/* Checks every pixel of in's rasters against the host's test; counts. */
static void check_pixels(const vbc_cells *c, const vbc_pore *p, const vbc_walls_input *in,
                         const vbc_walls_raster *R, size_t count[3], size_t *wrong)
{
    double a[3], b[3];
    vbc_plane_basis(p->axis.u, a, b);
    for (size_t k = 0; k < p->n; k++) {
        int n = in->half[k];
        size_t side = (size_t)(2 * n + 1);
        const uint32_t *bl = R->blocked + in->word0[k], *un = R->unsure + in->word0[k];
        for (size_t v = 0; v < side * side; v++) {
            double x = VBC_WALL_PIXEL * (double)((int)(v / side) - n);
            double y = VBC_WALL_PIXEL * (double)((int)(v % side) - n);
            double q[3], at[3] = {p->pts[k].x, p->pts[k].y, p->pts[k].z};
            for (int d = 0; d < 3; d++)
                q[d] = at[d] + x * a[d] + y * b[d];
            int hit = 0;
            vbc_cells_within(c, q, VBC_WALL_PROBE, mark, &hit);
            uint32_t m = 1u << (v & 31);
            int state = (bl[v >> 5] & m) ? VBC_WALLS_BLOCKED
                        : (un[v >> 5] & m) ? VBC_WALLS_UNSURE : VBC_WALLS_FREE;
            count[state]++;
            *wrong += (state == VBC_WALLS_BLOCKED && !hit) || (state == VBC_WALLS_FREE && hit);
        }
    }
}

/* Rasters of in by the twin (R allocated). */
static void twin(const vbc_walls_input *in, vbc_walls_raster *R)
{
    size_t words = in->word0[in->nplanes];
    R->blocked = malloc(words * sizeof *R->blocked);
    R->unsure = malloc(words * sizeof *R->unsure);
    CHECK_INT(vbc_walls_raster_ref(in, R), VB_OK);
}

/* check_pixels on the twin's rasters of p against c. */
static void check_twin(const vbc_cells *c, const vbc_pore *p, size_t count[3], size_t *wrong)
{
    vbc_walls_input in;
    CHECK_INT(vbc_walls_prep(c, p, &in), 0);
    vbc_walls_raster R;
    twin(&in, &R);
    check_pixels(c, p, &in, &R, count, wrong);
    free(R.blocked);
    free(R.unsure);
    vbc_walls_input_free(&in);
}

static void test_sound(vb_ctx *ctx)
{
    size_t count[3] = {0, 0, 0}, wrong = 0;
    const double offs[2] = {0.0, 3000.0};
    for (int o = 0; o < 2; o++)
        for (size_t atoms = 1500; atoms <= 3600; atoms += 700) {
            vb_sphere_set *s = hollow_cloud(atoms, 30.0, offs[o], 5 + atoms, 2.0);
            vbc_cells *c = NULL;
            CHECK_INT(vbc_cells_build(ctx, s, 3.0, &c), VB_OK);
            vbc_pore p;
            tilted_pore(&p, 30.0, offs[o], 0.05 * (double)(atoms % 7), 30, 1.0);
            check_twin(c, &p, count, &wrong);
            vbc_pore_free(&p);
            vbc_cells_free(c);
            vb_spheres_free(s);
        }
    CHECK_INT((int)wrong, 0);
    CHECK(count[VBC_WALLS_BLOCKED] > 10000 && count[VBC_WALLS_FREE] > 10000);
    /* The band is thin: about the bound over the pixel's share of atoms. */
    CHECK(count[VBC_WALLS_UNSURE] * 1000 < count[VBC_WALLS_BLOCKED]);
    if (vb_test_failed)
        fprintf(stderr, "blocked %zu free %zu unsure %zu wrong %zu\n", count[1], count[0], count[2],
                wrong);
}

/* Atoms of radius 1 A placed so that pixels of the plane z = 0 (axis z,
 * basis a = (0, 1, 0), b = (-1, 0, 0)) lie exactly 2 A (r + probe) from
 * them: the host says blocked (2 - 1 <= 1); the filter must not say free. */
static void test_ties(vb_ctx *ctx)
{
    vb_sphere_set *s = vb_test_spheres_alloc(4, 0);
    const double at[4][3] = {{2.0, 0.0, 0.0}, {0.0, 4.5, 0.0}, {-3.0, -3.0, 0.0}, {1.5, 2.0, 0.0}};
    for (int i = 0; i < 4; i++) {
        s->x[i] = at[i][0] + 10.0;
        s->y[i] = at[i][1] + 10.0;
        s->z[i] = at[i][2];
        s->r[i] = 1.0;
    }
    vbc_cells *c = NULL;
    CHECK_INT(vbc_cells_build(ctx, s, 3.0, &c), VB_OK);
    vbc_pore p;
    memset(&p, 0, sizeof p);
    p.pts = calloc(1, sizeof *p.pts);
    p.n = 1;
    p.axis.u[2] = 1.0;
    p.pts[0].x = p.pts[0].y = 10.0;
    size_t count[3] = {0, 0, 0}, wrong = 0;
    check_twin(c, &p, count, &wrong);
    CHECK_INT((int)wrong, 0);
    /* Each atom has pixels exactly 2 A away (e.g. (0, 0) for the first,
     * (0, 2.5) for the second): those are unsure. */
    CHECK(count[VBC_WALLS_UNSURE] >= 4);
    vbc_pore_free(&p);
    vbc_cells_free(c);
    vb_spheres_free(s);
}

static int same(const vbc_pore_verdict *x, const vbc_pore_verdict *y)
{
    return x->walled == y->walled && x->buried == y->buried && x->run_lo == y->run_lo &&
           x->run_hi == y->run_hi && x->is_pore == y->is_pore;
}

static void test_judge(vb_ctx *ctx)
{
    int differ = 0, walled = 0, pores = 0;
    const vbc_walls_engine *ref = vbc_walls_engine_ref();
    vb_sphere_set *tube = synth_cylinder(16, 16, 6.0, 1.5, 2.6);
    vbc_cells *c = NULL;
    CHECK_INT(vbc_cells_build(ctx, tube, 3.0, &c), VB_OK);
    vbc_pore p;
    tilted_pore(&p, 0.0, 0.0, 0.0, 200, 0.25);
    for (size_t k = 0; k < p.n; k++) {
        p.pts[k].x = p.pts[k].y = 0.0;
        p.pts[k].z = p.pts[k].s = -25.0 + 0.25 * (double)k;
        p.pts[k].r = 4.5;
    }
    const double enough[2] = {INFINITY, VBC_PORE_MIN_BURIED};
    for (int e = 0; e < 2; e++) {
        vbc_pore_verdict v0, v1;
        CHECK_INT(vbc_pore_judge(c, &p, enough[e], &v0), 0);
        CHECK_INT(vbc_pore_judge_on(ref, c, &p, enough[e], &v1), 0);
        differ += !same(&v0, &v1);
        pores += v0.is_pore;
    }
    vbc_pore_free(&p);
    vbc_cells_free(c);
    vb_spheres_free(tube);
    for (size_t atoms = 900; atoms <= 4000; atoms += 310) {
        vb_sphere_set *s = hollow_cloud(atoms, 36.0, 0.0, 11 + atoms, 5.0);
        CHECK_INT(vbc_cells_build(ctx, s, 3.0, &c), VB_OK);
        tilted_pore(&p, 36.0, 0.0, 0.05 * (double)(atoms % 7), 120, 0.25);
        for (int e = 0; e < 2; e++) {
            vbc_pore_verdict v0, v1;
            CHECK_INT(vbc_pore_judge(c, &p, enough[e], &v0), 0);
            CHECK_INT(vbc_pore_judge_on(ref, c, &p, enough[e], &v1), 0);
            differ += !same(&v0, &v1);
            walled += (int)v0.walled;
        }
        vbc_pore_free(&p);
        vbc_cells_free(c);
        vb_spheres_free(s);
    }
    CHECK_INT(differ, 0);
    CHECK(pores == 2 && walled > 100);
}

/* The kernel against the twin, word for word. */
static void test_kernel(vb_ctx *ctx)
{
    vbg_runtime *rt = NULL;
    if (vbg_runtime_open(ctx, VB_DEVICE_AUTO, &rt) != VB_OK) {
        fprintf(stderr, "no OpenCL device (%s): kernel not compared\n", vb_errmsg(ctx));
        vb_clear_error(ctx);
        return;
    }
    vbc_walls_gpu *W = NULL;
    int rc = vbc_walls_gpu_open(ctx, rt, &W);
    CHECK_INT(rc, VB_OK);
    if (rc != VB_OK)
        fprintf(stderr, "%s\n", vb_errmsg(ctx));
    const vbc_walls_engine *E = vbc_walls_gpu_engine(W);
    size_t words_total = 0, differ = 0;
    for (int o = 0; o < 2 && E; o++) {
        double off = o ? 3000.0 : 0.0;
        vb_sphere_set *s = hollow_cloud(2500, 30.0, off, 21 + (uint64_t)o, 2.0);
        vbc_cells *c = NULL;
        CHECK_INT(vbc_cells_build(ctx, s, 3.0, &c), VB_OK);
        vbc_pore p;
        tilted_pore(&p, 30.0, off, 0.1, 40, 0.75);
        vbc_walls_input in;
        CHECK_INT(vbc_walls_prep(c, &p, &in), 0);
        vbc_walls_raster R, G;
        twin(&in, &R);
        size_t words = in.word0[in.nplanes];
        G.blocked = calloc(words, sizeof *G.blocked);
        G.unsure = calloc(words, sizeof *G.unsure);
        CHECK_INT(E->raster(E->user, &in, &G), VB_OK);
        for (size_t w = 0; w < words; w++)
            differ += G.blocked[w] != R.blocked[w] || G.unsure[w] != R.unsure[w];
        words_total += words;
        vbc_pore_verdict v0, v1;
        CHECK_INT(vbc_pore_judge(c, &p, INFINITY, &v0), 0);
        CHECK_INT(vbc_pore_judge_on(E, c, &p, INFINITY, &v1), 0);
        CHECK(same(&v0, &v1));
        free(R.blocked);
        free(R.unsure);
        free(G.blocked);
        free(G.unsure);
        vbc_walls_input_free(&in);
        vbc_pore_free(&p);
        vbc_cells_free(c);
        vb_spheres_free(s);
    }
    CHECK(words_total > 1000);
    CHECK_INT((int)differ, 0);
    vbc_walls_gpu_close(W);
    vbg_runtime_close(rt);
}

int main(void)
{
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK)
        return 1;
    test_sound(ctx);
    test_ties(ctx);
    test_judge(ctx);
    test_kernel(ctx);
    vb_close(ctx);
    VB_TEST_END();
}
