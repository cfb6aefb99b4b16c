/* The HOLE-style pore sweep (core/discrete/channel_pore.c) on synthetic pores
 * whose radius is known in closed form: a ring with a 1.0 A hole (narrower
 * than the 1.4 A probe) inside a wide tube, a funnel of rings, a closed gate,
 * a trimer whose pore runs through one subunit (vbc_pore_find, the axis
 * from the chains); and HOLE's Ohmic conductance on a hand-made profile. Every radius is
 * asserted to 1e-6 A (the sweep's radii are exact in double, vbc_pore.h),
 * every position to the plane. */
#include "synth.h"
#include "vb_test.h"
#include "vbc_pore_frame.h"

#define PI 3.14159265358979323846

/* A copy of s with `per` atoms of radius r added on a ring of radius rc
 * around the z axis in the plane z. */
static vb_sphere_set *with_ring(vb_sphere_set *s, int per, double rc, double r, double z)
{
    vb_sphere_set *t = vb_test_spheres_alloc(s->n + (size_t)per, 0);
    for (size_t i = 0; i < s->n; i++) {
        t->x[i] = s->x[i];
        t->y[i] = s->y[i];
        t->z[i] = s->z[i];
        t->r[i] = s->r[i];
    }
    for (int a = 0; a < per; a++) {
        size_t i = s->n + (size_t)a;
        t->x[i] = rc * cos(2.0 * PI * a / per);
        t->y[i] = rc * sin(2.0 * PI * a / per);
        t->z[i] = z;
        t->r[i] = r;
    }
    vb_spheres_free(s);
    return t;
}

/* Sweeps s along z from (0, 0, z0), step ds, max_half A each way. */
static int sweep_z(vb_ctx *ctx, const vb_sphere_set *s, double z0, double ds, double half,
                   vbc_pore *p)
{
    vbc_cells *cells = NULL;
    int rc = vbc_cells_build(ctx, s, 3.0, &cells);
    if (rc != VB_OK)
        return rc;
    vbc_axis ax = {{0.0, 0.0, 1.0}, {0.0, 0.0, z0}, VBC_AXIS_GIVEN, 0, ""};
    vbc_pore_options opt = {ds, 0.0, half};
    rc = vbc_pore_sweep(ctx, cells, s, &ax, &opt, NULL, NULL, p);
    vbc_cells_free(cells);
    return rc;
}

/* The point of the sweep in the plane z (-1 when none). */
static long at_s(const vbc_pore *p, double z)
{
    for (size_t k = 0; k < p->n; k++)
        if (fabs(p->pts[k].s - z) < 1e-9)
            return (long)k;
    return -1;
}

/* A tube of 10 rings of 16 atoms (radius 1.5 A at 6 A from the axis: 4.5 A
 * clear) with a ring of 6 atoms of 1.5 A at 2.5 A in the plane z = 0: the
 * hole there is exactly 1.0 A, below the probe radius, and nowhere else is
 * the pore as narrow. The sweep starts off the constriction (z = 5) and
 * reaches it by its own steps. */
static void test_ring_hole(vb_ctx *ctx)
{
    vb_sphere_set *s = with_ring(synth_cylinder(10, 16, 6.0, 1.5, 2.6), 6, 2.5, 1.5, 0.0);
    vbc_pore p;
    CHECK_INT(sweep_z(ctx, s, 5.0, 0.25, 9.0, &p), VB_OK);
    CHECK_INT(p.n, 2 * 36 + 1);
    const vbc_pore_point *m = &p.pts[p.min_at];
    CHECK_NEAR(m->r, 1.0, 1e-6);
    CHECK_NEAR(m->s, 0.0, 1e-9);
    CHECK_NEAR(hypot(m->x, m->y), 0.0, 1e-6);
    CHECK(m->atom >= 160); /* one of the ring's atoms */
    /* Points sorted by s, the first at 5 - 9, the last at 5 + 9. */
    CHECK_NEAR(p.pts[0].s, -4.0, 1e-9);
    CHECK_NEAR(p.pts[p.n - 1].s, 14.0, 1e-9);
    /* A plane 1 A off the ring: the ring's atoms are 1.0 A farther in z, so
     * the largest sphere is hypot(2.5, 1) - 1.5 on the axis (the tube is
     * farther: hypot(6, 0.3) - 1.5 at least). */
    long k = at_s(&p, 1.0);
    CHECK(k >= 0);
    if (k >= 0)
        CHECK_NEAR(p.pts[k].r, hypot(2.5, 1.0) - 1.5, 1e-6);
    CHECK(p.g_macro_pS > 0.0);
    vbc_pore_free(&p);
    vb_spheres_free(s);
}

/* A funnel: six rings of 12 atoms of 1.6 A, ring k at z = 2.6 k and
 * 2.6 + 0.6 k A from the axis (staggered by half a step). In each ring's
 * plane the largest sphere sits on the axis with radius 1.0 + 0.6 k (the
 * neighbouring rings are farther: hypot(rc', 2.6) > rc for rc < 5.3), the
 * narrowest at z = 0; past the narrow end the radius grows as
 * hypot(2.6, z) - 1.6. */
static void test_funnel(vb_ctx *ctx)
{
    vb_sphere_set *s = vb_test_spheres_alloc(6 * 12, 0);
    for (int k = 0; k < 6; k++)
        for (int a = 0; a < 12; a++) {
            size_t i = (size_t)(12 * k + a);
            double phi = 2.0 * PI * (a + 0.5 * (k % 2)) / 12.0, rc = 2.6 + 0.6 * k;
            s->x[i] = rc * cos(phi);
            s->y[i] = rc * sin(phi);
            s->z[i] = 2.6 * k;
            s->r[i] = 1.6;
        }
    vbc_pore p;
    CHECK_INT(sweep_z(ctx, s, 0.0, 0.65, 13.0, &p), VB_OK);
    CHECK_NEAR(p.pts[p.min_at].r, 1.0, 1e-6);
    CHECK_NEAR(p.pts[p.min_at].s, 0.0, 1e-9);
    for (int k = 0; k < 6; k++) {
        long i = at_s(&p, 2.6 * k);
        CHECK(i >= 0);
        if (i >= 0) {
            CHECK_NEAR(p.pts[i].r, 1.0 + 0.6 * k, 1e-6);
            CHECK_NEAR(hypot(p.pts[i].x, p.pts[i].y), 0.0, 1e-6);
        }
    }
    long i = at_s(&p, -1.3);
    CHECK(i >= 0);
    if (i >= 0)
        CHECK_NEAR(p.pts[i].r, hypot(2.6, 1.3) - 1.6, 1e-6);
    vbc_pore_free(&p);
    vb_spheres_free(s);
}

/* The tube closed by a gate: 6 atoms of 1.6 A at 1.0 A from the axis in the
 * plane z = 0 overlap on the axis, the radius there is 1.0 - 1.6 = -0.6 (a
 * closed pore), and a closed pore conducts nothing. */
static void test_closed_gate(vb_ctx *ctx)
{
    vb_sphere_set *s = with_ring(synth_cylinder(10, 16, 6.0, 1.5, 2.6), 6, 1.0, 1.6, 0.0);
    vbc_pore p;
    CHECK_INT(sweep_z(ctx, s, 2.0, 0.5, 6.0, &p), VB_OK);
    CHECK_NEAR(p.pts[p.min_at].r, -0.6, 1e-6);
    CHECK_NEAR(p.pts[p.min_at].s, 0.0, 1e-9);
    CHECK(isinf(p.F));
    CHECK_INT(p.g_macro_pS == 0.0, 1);
    vbc_pore_free(&p);
    vb_spheres_free(s);
}

/* HOLE's Ohmic estimate on a cylinder of radius 1 A sampled at 10 points
 * 1 A apart: every point holds a slab of 1 A (the ends too), F = 10 / pi,
 * G = 100 / (rho F) = 120 pi pS for 1 M KCl. */
static void test_conductance(void)
{
    vbc_pore_point pts[10];
    for (int k = 0; k < 10; k++)
        pts[k] = (vbc_pore_point){(double)k, 0.0, 0.0, (double)k, 1.0, 0};
    vbc_pore p;
    memset(&p, 0, sizeof p);
    p.pts = pts;
    p.n = 10;
    vbc_pore_conductance(&p, VBC_RHO_KCL);
    CHECK_NEAR(p.F, 10.0 / PI, 1e-12);
    CHECK_NEAR(p.g_macro_pS, 120.0 * PI, 1e-9);
    /* Half the radius at one point: that slab's resistance four times. */
    pts[4].r = 0.5;
    vbc_pore_conductance(&p, VBC_RHO_KCL);
    CHECK_NEAR(p.F, 13.0 / PI, 1e-12);
}

/* A porin-like trimer: three tubes (chains A, B, C) of 8 rings of 12 atoms
 * of 1.6 A, rings 2.5 A apart, their axes parallel to z at 5.5 A from it,
 * 120 degrees apart; B's rings 4.3 A from its axis (2.7 A clear at each
 * ring, z = +-1.25, +-3.75, ...), A's and C's 4.0 A (2.4 A). The trimer's
 * own axis is closed by the walls (atoms 1.5 A from it), so the pore is
 * B's: found from the chains alone, swept through B's axis, its narrowest
 * radius 2.7 A at a ring. The molecule (the mask that ends the sweep and
 * keeps the subunits' start points in) is the three tubes' outer cylinders
 * for |z| <= 10.5; the grooves between the tubes are outside, as a probe's
 * molecular surface leaves them. */
static void test_subunit_pore(vb_ctx *ctx)
{
    const int rings = 8, per = 12;
    vb_sphere_set *s = vb_test_spheres_alloc((size_t)(3 * rings * per), 0);
    s->info = calloc(s->n, sizeof *s->info);
    double cx[3], cy[3];
    for (int t = 0; t < 3; t++) {
        double th = 2.0 * PI * t / 3.0, rc = t == 1 ? 4.3 : 4.0;
        cx[t] = 5.5 * cos(th);
        cy[t] = 5.5 * sin(th);
        for (int k = 0; k < rings; k++)
            for (int a = 0; a < per; a++) {
                size_t i = (size_t)((t * rings + k) * per + a);
                double phi = 2.0 * PI * (a + 0.5 * (k % 2)) / per;
                s->x[i] = cx[t] + rc * cos(phi);
                s->y[i] = cy[t] + rc * sin(phi);
                s->z[i] = (k - 0.5 * (rings - 1)) * 2.5;
                s->r[i] = 1.6;
                s->info[i].chain[0] = (char)('A' + t);
            }
    }
    vbc_grid g = {64, 64, 56, 3, {-16.0, -16.0, -14.0}, 0.5};
    size_t nv = (size_t)g.nx * (size_t)g.ny * (size_t)g.nz;
    uint8_t *flags = calloc(nv, 1);
    for (size_t v = 0; v < nv; v++) {
        size_t i = v % (size_t)g.nx, j = v / (size_t)g.nx % (size_t)g.ny, k = v / ((size_t)g.nx * (size_t)g.ny);
        double x = g.origin[0] + g.h * ((double)i + 0.5), y = g.origin[1] + g.h * ((double)j + 0.5);
        double z = g.origin[2] + g.h * ((double)k + 0.5);
        int in = 0;
        for (int t = 0; t < 3; t++)
            in |= hypot(x - cx[t], y - cy[t]) <= (t == 1 ? 4.3 : 4.0) + 1.6;
        flags[v] = in && fabs(z) <= 10.5 ? VBC_F_MOLECULAR : 0;
    }
    vbc_cells *cells = NULL;
    CHECK_INT(vbc_cells_build(ctx, s, 3.0, &cells), VB_OK);
    vbc_result res;
    memset(&res, 0, sizeof res);
    vbc_pore_request req;
    memset(&req, 0, sizeof req);
    req.enabled = 1;
    req.sweep.step = 0.25;
    vbc_pore p;
    CHECK_INT(vbc_pore_find(ctx, &g, flags, cells, s, &res, &req, &p), VB_OK);
    CHECK_INT(p.axis.source, VBC_AXIS_SUBUNIT);
    CHECK_INT(p.axis.chains, 2);
    CHECK_NEAR(fabs(p.axis.u[2]), 1.0, 1e-9);
    CHECK_INT(p.open_lo && p.open_hi, 1);
    if (p.n > 0) {
        const vbc_pore_point *m = &p.pts[p.min_at];
        CHECK_NEAR(m->r, 2.7, 1e-6);
        CHECK_NEAR(fmod(fabs(m->s) + 1.25, 2.5), 0.0, 1e-9);
        CHECK_NEAR(hypot(m->x - cx[1], m->y - cy[1]), 0.0, 1e-4);
    }
    vbc_pore_free(&p);
    /* With the trimer's axis given, the sweep stays on it: closed there. */
    req.have_axis = 1;
    req.u[2] = 1.0;
    CHECK_INT(vbc_pore_find(ctx, &g, flags, cells, s, &res, &req, &p), VB_OK);
    CHECK_INT(p.axis.source, VBC_AXIS_GIVEN);
    CHECK(p.n > 0 && p.pts[p.min_at].r < 0.0);
    vbc_pore_free(&p);
    vbc_cells_free(cells);
    free(flags);
    vb_spheres_free(s);
}

/* The cell list's nearest-atom walks (pruned by the nearest bound, started
 * from a hint, the ring's box open past the grid) against brute force on a
 * random cloud, with points inside and far outside it: the same distance
 * (the same expression, so to the bit), the same atom (ties to the lower
 * index), the near lists of vbc_cells_nearest_near and
 * vbc_cells_nearest_among in vbc_cells_within's order, and
 * vbc_cells_near_set's list as a set. */
typedef struct {
    int32_t id[512];
    size_t n;
} visit_list;

static void visit_put(int32_t atom, void *user)
{
    visit_list *L = user;
    if (L->n < 512)
        L->id[L->n++] = atom;
}

static void test_cells_walks(vb_ctx *ctx)
{
    const size_t n = 1500;
    vb_sphere_set *s = vb_test_spheres_alloc(n, 0);
    uint64_t st = 12345;
#define RND() ((double)((st = st * 6364136223846793005ull + 1442695040888963407ull) >> 11) / 9007199254740992.0)
    for (size_t i = 0; i < n; i++) {
        s->x[i] = 40.0 * RND();
        s->y[i] = 30.0 * RND();
        s->z[i] = 35.0 * RND();
        s->r[i] = 1.2 + 0.8 * RND();
    }
    vbc_cells *c = NULL;
    CHECK_INT(vbc_cells_build(ctx, s, 3.0, &c), VB_OK);
    int bad = 0;
    for (int t = 0; t < 400; t++) {
        /* Some points well outside the cloud (the verdict's pixels). */
        double f = t % 4 == 0 ? 3.0 : 1.0;
        double p[3] = {f * (50.0 * RND() - 5.0), f * (40.0 * RND() - 5.0), f * (45.0 * RND() - 5.0)};
        double best = INFINITY;
        int32_t ba = -1;
        for (size_t i = 0; i < n; i++) {
            double dx = p[0] - s->x[i], dy = p[1] - s->y[i], dz = p[2] - s->z[i];
            double d = sqrt(dx * dx + dy * dy + dz * dz) - s->r[i];
            if (d < best) {
                best = d;
                ba = (int32_t)i;
            }
        }
        int32_t a, hint = (int32_t)(RND() * (double)n);
        bad += vbc_cells_clearance(c, p, &a) != best || a != ba;
        bad += vbc_cells_clearance_from(c, p, hint, &a) != best || a != ba;
        double R, lo;
        int32_t near[512];
        double dist[512];
        size_t nn;
        bad += vbc_cells_nearest_near(c, p, 0.1, hint, &R, &a, near, dist, 512, &nn) != 0 ||
               R != best || a != ba;
        visit_list W = {{0}, 0};
        vbc_cells_within(c, p, best + 0.1, visit_put, &W);
        size_t k = 0;
        for (size_t j = 0; j < nn; j++)
            if (dist[j] <= best + 0.1)
                bad += k >= W.n || near[j] != W.id[k++];
        bad += k != W.n;
        /* From a list taken 0.4 A away with slack 1.1 (valid within 0.5). */
        double p0[3] = {p[0] + 0.4 * 0.6, p[1] - 0.4 * 0.8, p[2]};
        int32_t ids[512];
        double d0[512];
        size_t n0;
        if (vbc_cells_nearest_near(c, p0, 1.1, -1, &R, &a, ids, d0, 512, &n0) == 0) {
            bad += vbc_cells_nearest_among(c, ids, n0, p, 0.1, &R, &a, near, dist, 512, &nn) != 0 ||
                   R != best || a != ba || nn != W.n;
            for (size_t j = 0; j < nn && j < W.n; j++)
                bad += near[j] != W.id[j];
        }
        /* vbc_cells_near_set: the same clearance and atom, and exactly the
         * spheres within it + slack (by the same expression), any order. */
        for (int q = 0; q < 3; q++) {
            double sl = q == 0 ? 0.1 : q == 1 ? 1.1 : 3.1;
            size_t ns = 0, want = 0;
            if (vbc_cells_near_set(c, p, sl, q ? -1 : hint, &R, &a, ids, d0, 512, &ns) != 0) {
                bad++;
                continue;
            }
            bad += R != best || a != ba;
            for (size_t i = 0; i < n; i++) {
                double dx = p[0] - s->x[i], dy = p[1] - s->y[i], dz = p[2] - s->z[i];
                double d = sqrt(dx * dx + dy * dy + dz * dz) - s->r[i];
                if (!(d <= best + sl))
                    continue;
                want++;
                size_t j = 0;
                while (j < ns && ids[j] != (int32_t)i)
                    j++;
                bad += j == ns || d0[j] != d;
            }
            bad += ns != want;
        }
        int any = 0;
        for (size_t i = 0; i < n && !any; i++) {
            double dx = p[0] - s->x[i], dy = p[1] - s->y[i], dz = p[2] - s->z[i];
            any = sqrt(dx * dx + dy * dy + dz * dz) - s->r[i] <= 1.0;
        }
        int32_t h = -1;
        int got = vbc_cells_any_within(c, p, 1.0, &h, &lo);
        bad += got != any || (!got && !(lo <= best + 1e-9));
    }
#undef RND
    CHECK_INT(bad, 0);
    vbc_cells_free(c);
    vb_spheres_free(s);
}

/* vbc_plane_widest within VBC_PLANE_LOOK (the sweep's lattice: a list of
 * the spheres near the start in buckets of distance, channel_pore.c) is
 * the lattice's first strictly widest point by vbc_cells_clearance at
 * every point, then the ascent from it (vbc_plane_maximise within the
 * same reach): random planes through a dense random cloud, where the
 * nearest sphere of a lattice point often lies in a later bucket than the
 * start's. */
static void test_lattice(vb_ctx *ctx)
{
    uint64_t seed = 2024;
    vb_sphere_set *s = vb_test_spheres_alloc(1500, 0);
    for (size_t i = 0; i < s->n; i++) {
        s->x[i] = 30.0 * synth_uniform(&seed);
        s->y[i] = 30.0 * synth_uniform(&seed);
        s->z[i] = 30.0 * synth_uniform(&seed);
        s->r[i] = 0.8 + 1.2 * synth_uniform(&seed);
    }
    vbc_cells *c = NULL;
    CHECK_INT(vbc_cells_build(ctx, s, 3.0, &c), VB_OK);
    int differ = 0, moved = 0;
    for (int k = 0; k < 300; k++) {
        double u[3] = {synth_uniform(&seed) - 0.5, synth_uniform(&seed) - 0.5, 0.5};
        double nu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        double p[3], e1[3], e2[3], q[3];
        for (int a = 0; a < 3; a++) {
            u[a] /= nu;
            p[a] = 5.0 + 20.0 * synth_uniform(&seed);
        }
        /* The lattice's frame: plane_frame's (the axis least along u). */
        double t[3] = {0.0, 0.0, 0.0};
        t[fabs(u[0]) <= fabs(u[1]) && fabs(u[0]) <= fabs(u[2]) ? 0 : fabs(u[1]) <= fabs(u[2]) ? 1 : 2] = 1.0;
        double d = t[0] * u[0] + t[1] * u[1] + t[2] * u[2], ne = 0.0;
        for (int a = 0; a < 3; a++) {
            e1[a] = t[a] - d * u[a];
            ne += e1[a] * e1[a];
        }
        for (int a = 0; a < 3; a++)
            e1[a] /= sqrt(ne);
        e2[0] = u[1] * e1[2] - u[2] * e1[1];
        e2[1] = u[2] * e1[0] - u[0] * e1[2];
        e2[2] = u[0] * e1[1] - u[1] * e1[0];
        int32_t atom, a0;
        double best = vbc_cells_clearance(c, p, &a0), w[3] = {p[0], p[1], p[2]};
        for (long i = -3; i <= 3; i++)
            for (long j = -3; j <= 3; j++) {
                double di = 0.5 * (double)i, dj = 0.5 * (double)j;
                if (di * di + dj * dj > VBC_PLANE_LOOK * VBC_PLANE_LOOK)
                    continue;
                for (int a = 0; a < 3; a++)
                    q[a] = p[a] + di * e1[a] + dj * e2[a];
                double Rq = vbc_cells_clearance(c, q, &atom);
                if (Rq > best) {
                    best = Rq;
                    memcpy(w, q, sizeof w);
                }
            }
        moved += w[0] != p[0] || w[1] != p[1] || w[2] != p[2];
        double Rw = vbc_plane_maximise(c, u, VBC_PLANE_LOOK, w, &atom);
        int32_t b;
        double Rp = vbc_plane_widest(c, u, VBC_PLANE_LOOK, NULL, NULL, p, &b);
        differ += Rp != Rw || b != atom || memcmp(p, w, sizeof w) != 0;
    }
    CHECK_INT(differ, 0);
    CHECK(moved > 100);
    vbc_cells_free(c);
    vb_spheres_free(s);
}

/* The lattice's bucket break at its edge: a plane z = 0 (u = +z: the
 * lattice's frame is e1 = +x, e2 = +y), the start p at the origin, three
 * unit spheres in the plane: A at (0, -2.2) (p's clearance, lo = 1.2,
 * bucket 0), C at (0, 3.1) (distance 2.1 from p: bucket 3) and B at
 * (4.05, 0) (3.05 from p: bucket 7, [2.95, 3.2)). At q1 = (1.5, 0) B is
 * nearest (1.55) though A (1.6627) is met first; B's bucket starts below
 * 1.6627 + |q1 - p| = 3.1627 but ends above it: a break one bucket early
 * skips it. Only p, q1 and q2 = (0, 0.5) (clearance 1.6, by C) are inside
 * (every other point and the ascent's end outside): the widest is q2. */
static const double lattice_keep[3][3] = {{0.0, 0.0, 0.0}, {1.5, 0.0, 0.0}, {0.0, 0.5, 0.0}};

static int lattice_outside(void *user, const double q[3])
{
    (void)user;
    for (int k = 0; k < 3; k++)
        if (fabs(q[0] - lattice_keep[k][0]) < 1e-12 && fabs(q[1] - lattice_keep[k][1]) < 1e-12 &&
            fabs(q[2] - lattice_keep[k][2]) < 1e-12)
            return 0;
    return 1;
}

static void test_lattice_bucket_edge(vb_ctx *ctx)
{
    vb_sphere_set *s = vb_test_spheres_alloc(3, 0);
    const double ctr[3][2] = {{0.0, -2.2}, {4.05, 0.0}, {0.0, 3.1}}; /* A, B, C */
    for (size_t i = 0; i < 3; i++) {
        s->x[i] = ctr[i][0];
        s->y[i] = ctr[i][1];
        s->z[i] = 0.0;
        s->r[i] = 1.0;
    }
    vbc_cells *c = NULL;
    CHECK_INT(vbc_cells_build(ctx, s, 3.0, &c), VB_OK);
    int32_t a;
    /* the geometry as stated */
    CHECK(fabs(vbc_cells_clearance(c, lattice_keep[0], &a) - 1.2) < 1e-12 && a == 0);
    CHECK(fabs(vbc_cells_clearance(c, lattice_keep[1], &a) - 1.55) < 1e-12 && a == 1);
    CHECK(fabs(vbc_cells_clearance(c, lattice_keep[2], &a) - 1.6) < 1e-12 && a == 2);
    double u[3] = {0.0, 0.0, 1.0}, p[3] = {0.0, 0.0, 0.0};
    int32_t b = -1;
    double R = vbc_plane_widest(c, u, VBC_PLANE_LOOK, lattice_outside, NULL, p, &b);
    CHECK(p[0] == 0.0 && p[1] == 0.5 && p[2] == 0.0);
    CHECK(fabs(R - 1.6) < 1e-12);
    CHECK_INT(b, 2);
    if (p[0] != 0.0 || p[1] != 0.5)
        fprintf(stderr, "  lattice edge: widest (%g, %g) R %.17g atom %d, want (0, 0.5) 1.6 C\n",
                p[0], p[1], R, (int)b);
    vbc_cells_free(c);
    vb_spheres_free(s);
}

int main(void)
{
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK)
        return 1;
    test_ring_hole(ctx);
    test_funnel(ctx);
    test_closed_gate(ctx);
    test_subunit_pore(ctx);
    test_conductance();
    test_cells_walks(ctx);
    test_lattice(ctx);
    test_lattice_bucket_edge(ctx);
    vb_close(ctx);
    VB_TEST_END();
}
