/* The pore verdict (vbc_pore.h, core/discrete/channel_verdict.c) on
 * synthetic walls whose gaps are known: a tube of touching atoms walls its
 * axis, a ring with every other atom gone with every other atom gone (gaps wider than the wall
 * probe's disc) does not, half a tube (a groove) does not; the buried length
 * of a tube is its walled span, and a tube shorter than VBC_PORE_MIN_BURIED
 * is no pore; a gap of one missing ring is bridged, of two is not.
 * #33: vbc_cells_any_within answers as vbc_cells_within with a true lower
 * bound of the distance when it finds nothing, and the flood that trusts
 * those bounds walls the same planes as the plain flood (a copy below, one
 * query per pixel) in a random cloud of atoms; the verdict is the same on
 * 1 and 5 threads, and with the bounds one plane's flood leaves for the
 * next. */
#include "synth.h"
#include "vb_test.h"
#include "vbc_pore.h"

/* A hand-made pore on the z axis from z0 to z1, one point every 0.25 A,
 * radius `r` (only the verdict reads it). */
static void pore_on_z(vbc_pore *p, double z0, double z1, double r)
{
    memset(p, 0, sizeof *p);
    size_t n = (size_t)((z1 - z0) / 0.25 + 0.5) + 1;
    p->pts = calloc(n, sizeof *p->pts);
    p->n = p->pts ? n : 0;
    p->axis.u[2] = 1.0;
    for (size_t k = 0; k < p->n; k++) {
        p->pts[k].s = p->pts[k].z = z0 + 0.25 * (double)k;
        p->pts[k].r = r;
    }
}

static int walled_at(vb_ctx *ctx, const vb_sphere_set *s, double z, double r)
{
    vbc_cells *c = NULL;
    CHECK_INT(vbc_cells_build(ctx, s, 3.0, &c), VB_OK);
    if (!c)
        return -2;
    void *scratch = NULL;
    size_t len = 0;
    double u[3] = {0, 0, 1}, p[3] = {0, 0, z};
    int w = vbc_plane_walled(c, u, p, r, &scratch, &len);
    free(scratch);
    vbc_cells_free(c);
    return w;
}

/* Keeps the atoms for which keep(x, y) holds. */
static vb_sphere_set *filtered(vb_sphere_set *s, int (*keep)(size_t i, double x, double y))
{
    size_t n = 0;
    for (size_t i = 0; i < s->n; i++)
        n += (size_t)keep(i, s->x[i], s->y[i]);
    vb_sphere_set *t = vb_test_spheres_alloc(n, 0);
    for (size_t i = 0, j = 0; i < s->n; i++)
        if (keep(i, s->x[i], s->y[i])) {
            t->x[j] = s->x[i];
            t->y[j] = s->y[i];
            t->z[j] = s->z[i];
            t->r[j++] = s->r[i];
        }
    vb_spheres_free(s);
    return t;
}

static int every_other(size_t i, double x, double y)
{
    (void)x;
    (void)y;
    return i % 2 == 0;
}

static int half(size_t i, double x, double y)
{
    (void)i;
    (void)y;
    return x > 0.0;
}

static void test_walls(vb_ctx *ctx)
{
    /* 16 atoms of 1.5 A on a 6 A circle: 2.36 A apart, overlapping. The
     * staggered rings put a plane between two rings; the probe disc of 1 A
     * still finds no way out (the atoms 1.3 A above and below come within
     * its reach). */
    vb_sphere_set *tube = synth_cylinder(16, 16, 6.0, 1.5, 2.6);
    CHECK_INT(walled_at(ctx, tube, 0.0, 4.5), 1);
    CHECK_INT(walled_at(ctx, tube, 1.3, 4.5), 1);
    /* Beyond the tube's ends the plane is open. */
    CHECK_INT(walled_at(ctx, tube, 30.0, 4.5), 0);
    vb_spheres_free(tube);
    /* 8 atoms of 1.0 A on the circle: 4.6 A apart, gaps of 2.6 A > 2 A. A
     * single ring: nothing above or below closes the gaps. */
    vb_sphere_set *sparse = filtered(synth_cylinder(1, 16, 6.0, 1.0, 2.6), every_other);
    CHECK_INT((int)sparse->n, 8);
    CHECK_INT(walled_at(ctx, sparse, 0.0, 5.0), 0);
    vb_spheres_free(sparse);
    /* A groove: half the tube. */
    vb_sphere_set *groove = filtered(synth_cylinder(16, 16, 6.0, 1.5, 2.6), half);
    CHECK_INT(walled_at(ctx, groove, 0.0, 4.5), 0);
    vb_spheres_free(groove);
}

/* Rings 7 (and 8 when `two`) of the 16 of a tube gone. */
static int ring7 = 0, ring8 = 0;
static int without_rings(size_t i, double x, double y)
{
    (void)x;
    (void)y;
    size_t ring = i / 16;
    return !((ring7 && ring == 7) || (ring8 && ring == 8));
}

static double buried_of(vb_ctx *ctx, const vb_sphere_set *s)
{
    vbc_cells *c = NULL;
    CHECK_INT(vbc_cells_build(ctx, s, 3.0, &c), VB_OK);
    vbc_pore p;
    pore_on_z(&p, -30.0, 30.0, 4.5);
    vbc_pore_verdict v = {0, -1.0, 0, 0, 0};
    CHECK_INT(vbc_pore_judge(c, &p, INFINITY, &v), 0);
    vbc_pore_free(&p);
    vbc_cells_free(c);
    return v.buried;
}

/* A missing ring opens a gap shorter than VBC_WALL_GAP: bridged, the whole
 * tube is buried; two missing rings open a longer one: the run splits. */
static void test_gaps(vb_ctx *ctx)
{
    ring7 = 1;
    vb_sphere_set *one = filtered(synth_cylinder(16, 16, 6.0, 1.5, 2.6), without_rings);
    CHECK_INT((int)one->n, 15 * 16);
    double b1 = buried_of(ctx, one);
    CHECK(b1 >= 42.0 && b1 <= 44.0);
    vb_spheres_free(one);
    ring8 = 1;
    vb_sphere_set *two = filtered(synth_cylinder(16, 16, 6.0, 1.5, 2.6), without_rings);
    double b2 = buried_of(ctx, two);
    CHECK(b2 > 15.0 && b2 < 25.0);
    vb_spheres_free(two);
    ring7 = ring8 = 0;
}

static void test_buried(vb_ctx *ctx)
{
    /* 16 rings 2.6 A apart: atoms from z = -19.5 - 1.5 to 19.5 + 1.5. */
    vb_sphere_set *tube = synth_cylinder(16, 16, 6.0, 1.5, 2.6);
    vbc_cells *c = NULL;
    CHECK_INT(vbc_cells_build(ctx, tube, 3.0, &c), VB_OK);
    vbc_pore p;
    pore_on_z(&p, -30.0, 30.0, 4.5);
    vbc_pore_verdict v;
    CHECK_INT(vbc_pore_judge(c, &p, INFINITY, &v), 0);
    CHECK(v.is_pore);
    /* Walled within the rings' span, not beyond the last atoms. */
    /* Walled within the atoms' span (|z| <= 21) and the probe's reach
     * beyond it (the disc is a ball of 1 A: an atom 1 A off the plane
     * still walls it), never further: 42 to 44 A. */
    CHECK(v.buried >= 42.0 && v.buried <= 44.0);
    CHECK(p.pts[v.run_lo].s >= -22.0 - 1e-9 && p.pts[v.run_hi].s <= 22.0 + 1e-9);
    vbc_pore_free(&p);
    vbc_cells_free(c);
    vb_spheres_free(tube);
    /* 4 rings: 7.8 A of centres, about 11 A walled: no pore. */
    vb_sphere_set *ring = synth_cylinder(4, 16, 6.0, 1.5, 2.6);
    CHECK_INT(vbc_cells_build(ctx, ring, 3.0, &c), VB_OK);
    pore_on_z(&p, -20.0, 20.0, 4.5);
    CHECK_INT(vbc_pore_judge(c, &p, INFINITY, &v), 0);
    CHECK(!v.is_pore);
    CHECK(v.buried > 5.0 && v.buried < VBC_PORE_MIN_BURIED);
    vbc_pore_free(&p);
    vbc_cells_free(c);
    vb_spheres_free(ring);
}

/* A reproducible cloud: n atoms in a box of side L, radii 1 to 2 A. */
static vb_sphere_set *cloud(size_t n, double L, uint64_t seed)
{
    vb_sphere_set *s = vb_test_spheres_alloc(n, 0);
    for (size_t i = 0; i < n; i++) {
        s->x[i] = L * synth_uniform(&seed);
        s->y[i] = L * synth_uniform(&seed);
        s->z[i] = L * synth_uniform(&seed);
        s->r[i] = 1.0 + synth_uniform(&seed);
    }
    return s;
}

static void mark(int32_t atom, void *user)
{
    (void)atom;
    *(int *)user = 1;
}

static void test_any_within(vb_ctx *ctx)
{
    vb_sphere_set *s = cloud(300, 20.0, 7);
    vbc_cells *c = NULL;
    CHECK_INT(vbc_cells_build(ctx, s, 3.0, &c), VB_OK);
    const double reach[3] = {0.3, 1.0, 2.5};
    uint64_t seed = 99;
    int hits = 0, misses = 0, bad = 0;
    int32_t hint = -1;
    for (int k = 0; k < 3000; k++) {
        double p[3];
        for (int a = 0; a < 3; a++)
            p[a] = -6.0 + 32.0 * synth_uniform(&seed);
        double R = reach[k % 3], low = 0.0;
        int hit = 0;
        vbc_cells_within(c, p, R, mark, &hit);
        int any = vbc_cells_any_within(c, p, R, k % 2 ? &hint : NULL, &low);
        bad += any != hit;
        if (any) {
            hits++;
            continue;
        }
        misses++;
        double best = INFINITY;
        for (size_t i = 0; i < s->n; i++) {
            double dx = p[0] - s->x[i], dy = p[1] - s->y[i], dz = p[2] - s->z[i];
            best = fmin(best, sqrt(dx * dx + dy * dy + dz * dz) - s->r[i]);
        }
        bad += !(low > R && low <= best);
    }
    CHECK_INT(bad, 0);
    CHECK(hits > 300 && misses > 300);
    vbc_cells_free(c);
    vb_spheres_free(s);
}

/* The flood of vbc_plane_walled as it was before #33: one vbc_cells_within
 * per pixel outside the pore's sphere. */
static int walled_plain(const vbc_cells *c, const double a[3], const double b[3],
                        const double p[3], double r)
{
    double rr = r > 0.0 ? r : 0.0;
    int n = (int)ceil(fmin(2.0 * rr + VBC_WALL_REACH, VBC_WALL_MAX_REACH) / VBC_WALL_PIXEL);
    size_t side = (size_t)(2 * n + 1);
    int32_t *queue = malloc(side * side * sizeof *queue);
    uint8_t *seen = calloc(side * side, 1);
    size_t head = 0, tail = 0;
    int walled = 1;
    queue[tail++] = (int32_t)((size_t)n * side + (size_t)n);
    seen[queue[0]] = 1;
    while (head < tail && walled) {
        int32_t v = queue[head++];
        int i = (int)(v / (int32_t)side) - n, j = (int)(v % (int32_t)side) - n;
        if ((double)i * i + (double)j * j >= (double)(n - 1) * (n - 1)) {
            walled = 0;
            break;
        }
        static const int step[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
        for (int k = 0; k < 4; k++) {
            int ii = i + step[k][0], jj = j + step[k][1];
            int32_t w = (int32_t)((size_t)(ii + n) * side + (size_t)(jj + n));
            if (seen[w])
                continue;
            seen[w] = 1;
            double x = ii * VBC_WALL_PIXEL, y = jj * VBC_WALL_PIXEL;
            if (x * x + y * y > rr * rr) {
                double q[3];
                for (int d = 0; d < 3; d++)
                    q[d] = p[d] + x * a[d] + y * b[d];
                int hit = 0;
                vbc_cells_within(c, q, VBC_WALL_PROBE, mark, &hit);
                if (hit)
                    continue;
            }
            queue[tail++] = w;
        }
    }
    free(queue);
    free(seen);
    return walled;
}

/* A cloud of `atoms` in a 36 A cube less those within sqrt(r2) of the
 * line x = y = 18 (a tube along z through the middle). */
static vb_sphere_set *hollowed(size_t atoms, uint64_t seed, double r2)
{
    vb_sphere_set *s = cloud(atoms, 36.0, seed);
    size_t m = 0;
    for (size_t i = 0; i < s->n; i++) {
        double dx = s->x[i] - 18.0, dy = s->y[i] - 18.0;
        if (dx * dx + dy * dy < r2)
            continue;
        s->x[m] = s->x[i];
        s->y[m] = s->y[i];
        s->z[m] = s->z[i];
        s->r[m++] = s->r[i];
    }
    s->n = m;
    return s;
}

/* Planes through a dense cloud with a hollow core: the flood with the
 * distance bounds and the plain flood wall the same ones. */
static void same_walls(vb_ctx *ctx, size_t atoms, int *walled, int *open, int *differ)
{
    /* Hollowed: a tube of radius 5 A along z through the middle. */
    vb_sphere_set *s = hollowed(atoms, 11 + atoms, 25.0);
    vbc_cells *c = NULL;
    CHECK_INT(vbc_cells_build(ctx, s, 3.0, &c), VB_OK);
    void *scratch = NULL;
    size_t len = 0;
    for (int k = 0; k < 120; k++) {
        /* Tilted axes through the tube, planes from below the cloud to above it. */
        double t = 0.05 * (k % 7), u[3] = {t, 0.5 * t, 1.0};
        double nu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        for (int a = 0; a < 3; a++)
            u[a] /= nu;
        double p[3] = {18.0 + 0.3 * (k % 5), 18.0 - 0.2 * (k % 3), -8.0 + 0.45 * k};
        double r = 0.5 + 0.1 * (k % 11);
        double a[3], b[3];
        vbc_plane_basis(u, a, b);
        int w = vbc_plane_walled(c, u, p, r, &scratch, &len);
        *differ += w != walled_plain(c, a, b, p, r);
        *walled += w == 1;
        *open += w == 0;
    }
    free(scratch);
    vbc_cells_free(c);
    vb_spheres_free(s);
}

/* Clouds from sparse (gaps about the wall probe's disc: the verdict turns
 * on single pixels) to dense. */
static void test_same_walls(vb_ctx *ctx)
{
    int walled = 0, open = 0, differ = 0;
    for (size_t atoms = 900; atoms <= 4000; atoms += 310)
        same_walls(ctx, atoms, &walled, &open, &differ);
    CHECK_INT(differ, 0);
    CHECK(walled > 100 && open > 100);
    if (vb_test_failed)
        fprintf(stderr, "planes walled %d, open %d, differ %d\n", walled, open, differ);
}

/* Consecutive planes of one axis, a step of 0.25 A apart with their centres
 * wandering by up to 0.1 A and their spheres' radii changing, through
 * hollowed clouds (one scratch: each flood starts from the bounds the last
 * one left, channel_verdict.c's flood_memory): every plane walled or not
 * as by the plain flood; then the same planes in another order (bounds
 * carried over other distances). */
static void test_carried(vb_ctx *ctx)
{
    int walled = 0, open = 0, differ = 0;
    for (size_t atoms = 1200; atoms <= 4000; atoms += 700) {
        vb_sphere_set *s = hollowed(atoms, 5 + atoms, 20.0);
        vbc_cells *c = NULL;
        CHECK_INT(vbc_cells_build(ctx, s, 3.0, &c), VB_OK);
        double u[3] = {0.1, -0.05, 1.0}, a[3], b[3];
        double nu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        for (int k = 0; k < 3; k++)
            u[k] /= nu;
        vbc_plane_basis(u, a, b);
        for (int order = 0; order < 2; order++) {
            void *scratch = NULL;
            size_t len = 0;
            for (int t = 0; t < 160; t++) {
                int k = order ? (t * 37) % 160 : t;
                double z = -4.0 + 0.25 * k, wob = 0.1 * sin(0.7 * k);
                double p[3] = {18.0 + z * u[0] + wob * a[0], 18.0 + z * u[1] + wob * a[1],
                               z * u[2] + wob * a[2]};
                double r = 1.2 + 0.8 * sin(0.13 * k);
                int w = vbc_plane_walled(c, u, p, r, &scratch, &len);
                differ += w != walled_plain(c, a, b, p, r);
                walled += w == 1;
                open += w == 0;
            }
            free(scratch);
        }
        vbc_cells_free(c);
        vb_spheres_free(s);
    }
    CHECK_INT(differ, 0);
    CHECK(walled > 100 && open > 100);
    if (vb_test_failed)
        fprintf(stderr, "carried: planes walled %d, open %d, differ %d\n", walled, open, differ);
}

/* The verdict is the same on 1 and 5 threads (planes flooded in blocks,
 * scanned in order): a tube judged to the end and stopped at
 * VBC_PORE_MIN_BURIED, and a line through a random cloud (walled and open
 * planes mixed), every field of the verdict. */
static void same_verdict(const vbc_cells *c, const vbc_pore *p, double enough, int *differ)
{
    vbc_pore_verdict v[2];
    const char *th[2] = {"1", "5"};
    for (int k = 0; k < 2; k++) {
        setenv("VORBALL_THREADS", th[k], 1);
        CHECK_INT(vbc_pore_judge(c, p, enough, &v[k]), 0);
    }
    unsetenv("VORBALL_THREADS");
    *differ += v[0].walled != v[1].walled || v[0].buried != v[1].buried ||
               v[0].run_lo != v[1].run_lo || v[0].run_hi != v[1].run_hi ||
               v[0].is_pore != v[1].is_pore;
}

static void test_threads(vb_ctx *ctx)
{
    int differ = 0;
    vb_sphere_set *tube = synth_cylinder(16, 16, 6.0, 1.5, 2.6);
    vbc_cells *c = NULL;
    CHECK_INT(vbc_cells_build(ctx, tube, 3.0, &c), VB_OK);
    vbc_pore p;
    pore_on_z(&p, -30.0, 30.0, 4.5);
    CHECK(p.n > 5 * 32); /* enough planes for 5 threads */
    same_verdict(c, &p, INFINITY, &differ);
    same_verdict(c, &p, VBC_PORE_MIN_BURIED, &differ);
    vbc_pore_free(&p);
    vbc_cells_free(c);
    vb_spheres_free(tube);
    vb_sphere_set *s = cloud(3000, 40.0, 77);
    CHECK_INT(vbc_cells_build(ctx, s, 3.0, &c), VB_OK);
    pore_on_z(&p, -5.0, 45.0, 0.5);
    for (size_t k = 0; k < p.n; k++)
        p.pts[k].x = p.pts[k].y = 20.0;
    vbc_pore_verdict v;
    CHECK_INT(vbc_pore_judge(c, &p, INFINITY, &v), 0);
    CHECK(v.walled > 10 && v.walled + 10 < p.n); /* both kinds of plane */
    same_verdict(c, &p, INFINITY, &differ);
    same_verdict(c, &p, 2.0, &differ);
    vbc_pore_free(&p);
    vbc_cells_free(c);
    vb_spheres_free(s);
    CHECK_INT(differ, 0);
}

int main(void)
{
    vb_ctx *ctx;
    vb_config cfg = {0, NULL};
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 1;
    test_walls(ctx);
    test_buried(ctx);
    test_gaps(ctx);
    test_any_within(ctx);
    test_same_walls(ctx);
    test_carried(ctx);
    test_threads(ctx);
    vb_close(ctx);
    VB_TEST_END();
}
