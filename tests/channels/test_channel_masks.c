/* Each stage of the reference mask pipeline (core/discrete/channel_masks_ref.c) on
 * synthetic molecules whose masks are known: one ball, two balls, a cylinder
 * with a pore along z, a closed shell; and (#33) the whole stage against the
 * plain per-voxel form it replaced (every voxel against every ball's box,
 * one vbc_ray_scan per ray, vbc_classify everywhere) on random atoms, in 3D
 * and 2D, byte for byte; and (chan41) the mask stage that reads labels
 * only around the interior, its exact labels and the reference engine that
 * runs it, against the whole stage. */
#include "channel_math.h"
#include "synth.h"
#include "vb_test.h"
#include "vbc_channel_pipe.h"

static size_t count_bits(const uint8_t *f, size_t n, unsigned bit)
{
    size_t c = 0;
    for (size_t v = 0; v < n; v++)
        c += (f[v] & bit) != 0;
    return c;
}

static size_t vox(const vbc_grid *g, int i, int j, int k)
{
    return (size_t)i + (size_t)g->nx * ((size_t)j + (size_t)g->ny * (size_t)k);
}

/* Voxel containing a point in Å. */
static size_t vox_at(const vbc_grid *g, double x, double y, double z)
{
    return vox(g, (int)((x - g->origin[0]) / g->h), (int)((y - g->origin[1]) / g->h),
               (int)((z - g->origin[2]) / g->h));
}

typedef struct {
    vbc_grid g;
    float *atoms;
    int32_t *labels;
    int *rb;
    uint8_t *flags;
} run;

static void run_ref(vb_ctx *ctx, const vb_sphere_set *s, double probe, int n, int dim, run *r)
{
    CHECK_INT(vbc_grid_fit(ctx, s, probe, n, dim, &r->g), VB_OK);
    size_t nv = vbc_grid_voxels(&r->g);
    r->atoms = malloc(4 * s->n * sizeof(float));
    r->labels = malloc(nv * sizeof(int32_t));
    r->rb = malloc((size_t)vbc_rb_size(r->g.nx, r->g.ny, r->g.nz) * sizeof(int));
    r->flags = malloc(nv);
    vbc_atoms_pack(&r->g, s, probe, r->atoms);
    synth_labels(&r->g, r->atoms, s->n, r->labels);
    vbc_masks_ref(&r->g, r->atoms, s->n, r->labels, dim == 3 ? 3 : 2, r->rb, r->flags);
}

static void run_free(run *r)
{
    free(r->atoms);
    free(r->labels);
    free(r->rb);
    free(r->flags);
}

/* One ball of radius 6 voxels centred on a voxel corner covers exactly the
 * voxel centres within 6 voxels (no centre lies on the sphere: a sum of three
 * odd squares is never 144); a ball is its own ray hull, so the molecular mask
 * equals the atomic one and nothing is interior. */
static void test_single_ball(vb_ctx *ctx)
{
    vb_sphere_set *s = vb_test_spheres_alloc(1, 0);
    s->r[0] = 1.0;
    run r;
    run_ref(ctx, s, 0.0, 16, 3, &r);
    /* Extent 2 Å over 16 - 4 margin voxels: h = 1/6 Å, R = 6 voxels. */
    CHECK_NEAR(r.g.h, 2.0 / 12.0, 1e-12);
    size_t nv = vbc_grid_voxels(&r.g);
    size_t expect = 0;
    for (int k = 0; k < 16; k++)
        for (int j = 0; j < 16; j++)
            for (int i = 0; i < 16; i++) {
                double dx = i + 0.5 - 8.0, dy = j + 0.5 - 8.0, dz = k + 0.5 - 8.0;
                expect += dx * dx + dy * dy + dz * dz <= 36.0;
            }
    CHECK(expect > 700 && expect < 930);
    CHECK_INT(count_bits(r.flags, nv, VBC_F_ATOMIC), expect);
    CHECK_INT(count_bits(r.flags, nv, VBC_F_MOLECULAR), expect);
    CHECK_INT(count_bits(r.flags, nv, VBC_F_INTERIOR), 0);
    CHECK_INT(count_bits(r.flags, nv, VBC_F_CHANNEL), 0);
    /* One seed: one label everywhere, no Voronoi edge. */
    CHECK_INT(count_bits(r.flags, nv, VBC_F_EDGE), 0);
    run_free(&r);
    vb_spheres_free(s);
}

/* Two balls side by side along x: x rays that hit both fill the gap, so the
 * gap between them is molecular but not atomic (interior). */
static void test_two_balls(vb_ctx *ctx)
{
    vb_sphere_set *s = vb_test_spheres_alloc(2, 0);
    s->x[0] = -4.0;
    s->x[1] = 4.0;
    s->r[0] = s->r[1] = 2.0;
    run r;
    run_ref(ctx, s, 0.5, 32, 3, &r);
    size_t mid = vox_at(&r.g, 0.01, 0.01, 0.01);
    CHECK_INT(r.flags[mid] & (VBC_F_ATOMIC | VBC_F_MOLECULAR | VBC_F_INTERIOR),
              VBC_F_MOLECULAR | VBC_F_INTERIOR);
    /* Off the shadow of the balls (|y| > 2.5) nothing is molecular. */
    CHECK_INT(r.flags[vox_at(&r.g, 0.01, 3.0, 0.01)] & VBC_F_MOLECULAR, 0);
    CHECK_INT(r.flags[vox_at(&r.g, -4.01, 0.01, 0.01)] & VBC_F_ATOMIC, VBC_F_ATOMIC);
    /* Two regions only: a bisector plane, but no voxel sees three labels. */
    CHECK_INT(count_bits(r.flags, vbc_grid_voxels(&r.g), VBC_F_EDGE), 0);
    run_free(&r);
    vb_spheres_free(s);
}

/* Three atoms in the plane z = 0: their Voronoi edge is the line through the
 * circumcentre along z; in 2D the same input has boundary lines everywhere
 * two regions meet. */
static void test_edges(vb_ctx *ctx)
{
    vb_sphere_set *s = vb_test_spheres_alloc(3, 0);
    const double pi = 3.14159265358979323846;
    for (int a = 0; a < 3; a++) {
        s->x[a] = 5.0 * cos(2 * pi * a / 3 + 0.3);
        s->y[a] = 5.0 * sin(2 * pi * a / 3 + 0.3);
        s->r[a] = 1.5;
    }
    run r;
    run_ref(ctx, s, 0.0, 32, 3, &r);
    size_t nv = vbc_grid_voxels(&r.g);
    /* Every edge voxel is within one voxel of the z axis, and every z layer has one. */
    size_t far = 0;
    int layers = 0;
    for (int k = 0; k < r.g.nz; k++) {
        int has = 0;
        for (int j = 0; j < r.g.ny; j++)
            for (int i = 0; i < r.g.nx; i++)
                if (r.flags[vox(&r.g, i, j, k)] & VBC_F_EDGE) {
                    double x = r.g.origin[0] + (i + 0.5) * r.g.h, y = r.g.origin[1] + (j + 0.5) * r.g.h;
                    far += hypot(x, y) > 1.5 * r.g.h;
                    has = 1;
                }
        layers += has;
    }
    CHECK_INT(far, 0);
    CHECK_INT(layers, r.g.nz);
    CHECK(count_bits(r.flags, nv, VBC_F_EDGE) >= (size_t)r.g.nz);
    run_free(&r);

    run_ref(ctx, s, 0.0, 64, 2, &r);
    CHECK_INT(r.g.nz, 1);
    nv = vbc_grid_voxels(&r.g);
    /* 2D: three half-lines from the circumcentre; each crosses ~ (n/2) pixels. */
    size_t e2 = count_bits(r.flags, nv, VBC_F_EDGE);
    CHECK(e2 > 3 * 20 && e2 < 3 * 64 * 3);
    run_free(&r);
    vb_spheres_free(s);
}

/* A cylinder of 8 rings x 12 atoms (rc 6, r 1.6): with probe 1 a pore of
 * clearance 4.4 Å runs along z and opens at both ends. */
static void test_cylinder(vb_ctx *ctx)
{
    vb_sphere_set *s = synth_cylinder(8, 12, 6.0, 1.6, 2.6);
    run r;
    run_ref(ctx, s, 1.0, 64, 3, &r);
    size_t nv = vbc_grid_voxels(&r.g);
    size_t axis = vox_at(&r.g, 0.01, 0.01, 0.01);
    CHECK_INT(r.flags[axis] & 31u, VBC_F_MOLECULAR | VBC_F_EDGE | VBC_F_INTERIOR | VBC_F_CHANNEL);
    CHECK_INT(r.flags[vox_at(&r.g, s->x[0], s->y[0], s->z[0])] & VBC_F_ATOMIC, VBC_F_ATOMIC);
    /* Outside the wall: neither molecular nor a channel. */
    CHECK_INT(r.flags[vox_at(&r.g, 9.5, 0.01, 0.01)] & (VBC_F_MOLECULAR | VBC_F_CHANNEL), 0);
    CHECK_INT(r.flags[0], 0);
    /* The pore is interior along its whole length: every axis voxel between
     * the outermost rings is a channel voxel. */
    int axis_channel = 1;
    for (double z = -9.0; z <= 9.0; z += r.g.h)
        axis_channel &= (r.flags[vox_at(&r.g, 0.01, 0.01, z)] & VBC_F_CHANNEL) != 0;
    CHECK(axis_channel);
    /* The pore opens beyond the last rings (|z| > 9.1): mouths on the pore
     * (within 2 Å of the axis) lie there. The union of axis-ray hulls also
     * makes the grooves between atoms on the outer wall interior, and their
     * Voronoi edges are short "channels" with mouths of their own (pruned by
     * length later), so mouths away from the axis are allowed. */
    size_t mouths = 0, pore_mouths = 0, misplaced = 0;
    for (size_t v = 0; v < nv; v++)
        if (r.flags[v] & VBC_F_MOUTH) {
            int i = (int)(v % (size_t)r.g.nx), j = (int)((v / (size_t)r.g.nx) % (size_t)r.g.ny);
            int k = (int)(v / ((size_t)r.g.nx * r.g.ny));
            double x = r.g.origin[0] + (i + 0.5) * r.g.h, y = r.g.origin[1] + (j + 0.5) * r.g.h;
            double z = r.g.origin[2] + (k + 0.5) * r.g.h;
            mouths++;
            if (hypot(x, y) < 2.0) {
                pore_mouths++;
                misplaced += fabs(z) < 9.1;
            }
        }
    CHECK(pore_mouths > 0);
    CHECK_INT(misplaced, 0);
    /* Interior = molecular and not atomic, exactly. */
    size_t bad = 0;
    for (size_t v = 0; v < nv; v++) {
        unsigned f = r.flags[v];
        int want = (f & VBC_F_MOLECULAR) && !(f & VBC_F_ATOMIC);
        bad += want != ((f & VBC_F_INTERIOR) != 0);
        bad += ((f & VBC_F_CHANNEL) != 0) != ((f & VBC_F_EDGE) && (f & VBC_F_INTERIOR));
        bad += (f & VBC_F_ATOMIC) && !(f & VBC_F_MOLECULAR);
    }
    CHECK_INT(bad, 0);

    /* Compaction lists exactly the channel voxels, mouths flagged. */
    uint32_t *list;
    size_t nl;
    CHECK_INT(vbc_flags_compact(ctx, &r.g, r.flags, &list, &nl), VB_OK);
    CHECK_INT(nl, count_bits(r.flags, nv, VBC_F_CHANNEL));
    size_t lm = 0;
    for (size_t t = 0; t < nl; t++)
        lm += (list[t] & VBC_MOUTH_BIT) != 0;
    CHECK_INT(lm, mouths);
    free(list);
    run_free(&r);

    /* A probe wider than the pore (clearance 4.4 < 4.6) closes it: no channel. */
    run_ref(ctx, s, 4.6, 64, 3, &r);
    CHECK_INT(r.flags[vox_at(&r.g, 0.01, 0.01, 0.01)] & VBC_F_CHANNEL, 0);
    run_free(&r);
    vb_spheres_free(s);
}

/* A closed shell: the hollow is interior, its Voronoi edges are channel
 * voxels, and none of those inside the wall touches the outside (no mouth). */
static void test_shell(vb_ctx *ctx)
{
    vb_sphere_set *s = synth_shell(240, 9.0, 1.6);
    run r;
    run_ref(ctx, s, 1.0, 48, 3, &r);
    size_t nv = vbc_grid_voxels(&r.g);
    CHECK_INT(r.flags[vox_at(&r.g, 0.01, 0.01, 0.01)] & (VBC_F_ATOMIC | VBC_F_MOLECULAR | VBC_F_INTERIOR),
              VBC_F_MOLECULAR | VBC_F_INTERIOR);
    CHECK(count_bits(r.flags, nv, VBC_F_CHANNEL) > 10);
    /* Inside the wall (|p| < 9), interior voxels lie in the hollow that a
     * probe can reach (|p| < 9 - 1.6 - 1.0, plus a voxel) and are no mouths. */
    size_t outside = 0, inner_mouths = 0;
    for (size_t v = 0; v < nv; v++)
        if (r.flags[v] & VBC_F_INTERIOR) {
            int i = (int)(v % (size_t)r.g.nx), j = (int)((v / (size_t)r.g.nx) % (size_t)r.g.ny);
            int k = (int)(v / ((size_t)r.g.nx * r.g.ny));
            double p = sqrt(pow(r.g.origin[0] + (i + 0.5) * r.g.h, 2) +
                            pow(r.g.origin[1] + (j + 0.5) * r.g.h, 2) +
                            pow(r.g.origin[2] + (k + 0.5) * r.g.h, 2));
            outside += p < 9.0 && p > 6.4 + r.g.h;
            inner_mouths += p < 9.0 && (r.flags[v] & VBC_F_MOUTH);
        }
    CHECK_INT(outside, 0);
    CHECK_INT(inner_mouths, 0);
    run_free(&r);
    vb_spheres_free(s);
}

static void test_grid_fit_errors(vb_ctx *ctx)
{
    vb_sphere_set *s = vb_test_spheres_alloc(1, 0);
    s->r[0] = 1.0;
    vbc_grid g;
    CHECK_INT(vbc_grid_fit(ctx, s, 1.4, 4, 3, &g), VB_EMISUSE);
    CHECK_INT(vbc_grid_fit(ctx, s, -1.0, 64, 3, &g), VB_EMISUSE);
    CHECK_INT(vbc_grid_fit(ctx, s, 1.4, 64, 4, &g), VB_EMISUSE);
    s->n = 0;
    free(s->source);
    s->source = strdup("frame.pdb");
    CHECK_INT(vbc_grid_fit(ctx, s, 1.4, 64, 3, &g), VB_EINPUT_EMPTY);
    /* The message names the input (issue 17). */
    CHECK(strncmp(vb_errmsg(ctx), "frame.pdb: no atoms", 19) == 0);
    s->n = 1;
    vb_spheres_free(s);
}

/* The mask stage as it was written first, from the per-voxel functions alone. */
static void masks_plain(const vbc_grid *g, const float *atoms4, size_t natoms, const int32_t *labels,
                        int min_labels, int *rb, uint8_t *flags)
{
    int nx = g->nx, ny = g->ny, nz = g->nz;
    memset(flags, 0, vbc_grid_voxels(g));
    for (size_t a = 0; a < natoms; a++) {
        const float *p = atoms4 + 4 * a;
        for (int k = vbc_box_lo(p[2], p[3]); k < vbc_box_hi(p[2], p[3], nz); k++)
            for (int j = vbc_box_lo(p[1], p[3]); j < vbc_box_hi(p[1], p[3], ny); j++)
                for (int i = vbc_box_lo(p[0], p[3]); i < vbc_box_hi(p[0], p[3], nx); i++)
                    if (vbc_ball_contains(p[0], p[1], p[2], p[3], i, j, k))
                        flags[vox(g, i, j, k)] = VBC_F_ATOMIC;
    }
    vbc_ray_bounds_plain(flags, nx, ny, nz, rb);
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < nx; i++)
                flags[vox(g, i, j, k)] =
                    (uint8_t)vbc_classify(labels, flags, rb, nx, ny, nz, min_labels, i, j, k);
}

/* n atoms uniform in [0, span)^dim (z 0 in 2D), radii r0 + [0, dr). */
static vb_sphere_set *random_atoms(uint64_t *seed, size_t n, int dim, double span, double r0,
                                   double dr)
{
    vb_sphere_set *s = vb_test_spheres_alloc(n, 0);
    for (size_t i = 0; i < n; i++) {
        s->x[i] = span * synth_uniform(seed);
        s->y[i] = span * synth_uniform(seed);
        s->z[i] = dim == 3 ? span * synth_uniform(seed) : 0.0;
        s->r[i] = r0 + dr * synth_uniform(seed);
    }
    return s;
}

/* Random atoms (radii 0.9 to 2.4 A, probe 1.4 A, some balls past the grid's
 * edge after the fit as 2D cuts have them) on grids of 16 to 64: the same
 * flag bytes and ray bounds as masks_plain. */
static void test_same_as_plain(vb_ctx *ctx)
{
    uint64_t seed = 12345;
    int differ = 0, runs = 0;
    for (int n = 16; n <= 64; n *= 2)
        for (int dim = 2; dim <= 3; dim++)
            for (int rep = 0; rep < 3; rep++) {
                size_t natoms = (size_t)(30 + 70 * rep);
                vb_sphere_set *s = random_atoms(&seed, natoms, dim, 20.0, 0.9, 1.5);
                run r;
                run_ref(ctx, s, 1.4, n, dim, &r);
                /* Shift some balls half out of the grid: the rows clip,
                 * and in y and z the row nearest the centre is the box's
                 * first or last (ball_mark walks out from it). */
                for (size_t i = 0; i < natoms; i += 7)
                    r.atoms[4 * i] = -0.3f * r.atoms[4 * i + 3];
                for (size_t i = 3; i < natoms; i += 11)
                    r.atoms[4 * i + 1] = (float)r.g.ny + 0.4f * r.atoms[4 * i + 3];
                for (size_t i = 5; i < natoms && dim == 3; i += 13)
                    r.atoms[4 * i + 2] = -0.6f * r.atoms[4 * i + 3];
                size_t nv = vbc_grid_voxels(&r.g), nrb = (size_t)vbc_rb_size(r.g.nx, r.g.ny, r.g.nz);
                uint8_t *want = malloc(nv);
                int *rb = malloc(nrb * sizeof *rb);
                int ml = dim == 3 ? 3 : 2;
                vbc_masks_ref(&r.g, r.atoms, natoms, r.labels, ml, r.rb, r.flags);
                masks_plain(&r.g, r.atoms, natoms, r.labels, ml, rb, want);
                differ += memcmp(want, r.flags, nv) != 0 || memcmp(rb, r.rb, nrb * sizeof *rb) != 0;
                runs++;
                CHECK(count_bits(r.flags, nv, VBC_F_ATOMIC) > 0);
                free(want);
                free(rb);
                run_free(&r);
                vb_spheres_free(s);
            }
    CHECK_INT(differ, 0);
    CHECK_INT(runs, 18);
}

/* Random molecules as test_same_as_plain's: vbc_masks_shape, vbc_masks_need
 * and vbc_masks_edges, with every label that need leaves out spoiled, give
 * vbc_masks_ref's bytes less the edge bit of voxels that are not interior,
 * the ray bounds, the interior in index order and vbc_flags_compact's
 * channel voxel list. */
static void test_interior_only(vb_ctx *ctx)
{
    uint64_t seed = 777;
    int differ = 0, runs = 0;
    size_t interior = 0, needed = 0, voxels = 0, channels = 0;
    for (int n = 16; n <= 64; n *= 2)
        for (int dim = 2; dim <= 3; dim++)
            for (int rep = 0; rep < 3; rep++) {
                size_t natoms = (size_t)(40 + 80 * rep);
                vb_sphere_set *s = random_atoms(&seed, natoms, dim, 20.0, 0.9, 1.5);
                run r;
                run_ref(ctx, s, 1.4, n, dim, &r);
                /* Some balls half out of the grid (rows and the box clip),
                 * the whole stage again on them. */
                for (size_t i = 3; i < natoms; i += 11)
                    r.atoms[4 * i + 1] = (float)r.g.ny + 0.4f * r.atoms[4 * i + 3];
                vbc_masks_ref(&r.g, r.atoms, natoms, r.labels, dim == 3 ? 3 : 2, r.rb, r.flags);
                size_t nv = vbc_grid_voxels(&r.g), nrb = (size_t)vbc_rb_size(r.g.nx, r.g.ny, r.g.nz);
                uint8_t *f = malloc(nv), *need = malloc(nv);
                int *rb = malloc(nrb * sizeof *rb);
                int32_t *lab = malloc(nv * sizeof *lab);
                uint32_t *list = NULL, *want = NULL;
                size_t m = 0, nwant = 0, t = 0;
                CHECK_INT(vbc_masks_shape(ctx, &r.g, r.atoms, natoms, rb, f, &list, &m), VB_OK);
                vbc_masks_need(&r.g, list, m, need);
                for (size_t v = 0; v < nv; v++) {
                    lab[v] = need[v] ? r.labels[v] : (int32_t)(v % 5) - 9;
                    needed += need[v] != 0;
                    /* The list: the interior voxels, in order. */
                    if (r.flags[v] & VBC_F_INTERIOR)
                        differ += t >= m || list[t++] != v;
                    r.flags[v] &= (r.flags[v] & VBC_F_INTERIOR) ? 0xffu : (unsigned)~VBC_F_EDGE;
                }
                differ += t != m;
                size_t c = vbc_masks_edges(&r.g, lab, dim == 3 ? 3 : 2, rb, list, m, f);
                CHECK_INT(vbc_flags_compact(ctx, &r.g, r.flags, &want, &nwant), VB_OK);
                differ += c != nwant || (c && memcmp(list, want, c * sizeof *list) != 0);
                differ += memcmp(f, r.flags, nv) != 0 || memcmp(rb, r.rb, nrb * sizeof *rb) != 0;
                interior += m;
                channels += c;
                voxels += nv;
                runs++;
                free(f);
                free(need);
                free(rb);
                free(lab);
                free(list);
                free(want);
                run_free(&r);
                vb_spheres_free(s);
            }
    CHECK_INT(differ, 0);
    CHECK_INT(runs, 18);
    /* Not vacuous: interior and channel voxels exist, and fewer labels are read. */
    CHECK(interior > 100 && channels > 10);
    CHECK(needed > interior && needed < voxels / 2);
}

/* vbj_ref_exact_need: the exact labels of the wanted voxels (random masks,
 * one with a single voxel, one with none: no work then). */
static void test_exact_need(vb_ctx *ctx)
{
    vbj_backend *be = NULL;
    CHECK_INT(vbj_ref_open(ctx, &be), VB_OK);
    uint64_t seed = 99;
    for (int dim = 2; dim <= 3; dim++)
        for (int rep = 0; rep < 3; rep++) {
            uint32_t n = dim == 3 ? 32 : 128;
            vbj_seeds sd;
            CHECK_INT(vbj_seeds_alloc(ctx, dim, n, 60, &sd), VB_OK);
            for (size_t i = 0; i < 60; i++) {
                double x = (n - 1) * synth_uniform(&seed), y = (n - 1) * synth_uniform(&seed);
                double z = dim == 3 ? (n - 1) * synth_uniform(&seed) : 0.0;
                CHECK_INT(vbj_seed_set(ctx, &sd, i, x, y, z), VB_OK);
            }
            vbj_options o = {VBJ_EXACT, 0, VBJ_WANT_LABELS, 0};
            vbj_result full, part;
            CHECK_INT(vbj_run(ctx, be, &sd, &o, &full), VB_OK);
            uint8_t *need = calloc(full.pixels, 1);
            if (rep == 0)
                for (size_t v = 0; v < full.pixels; v++)
                    need[v] = synth_uniform(&seed) < 0.05;
            else if (rep == 1)
                need[full.pixels / 3] = 1;
            CHECK_INT(vbj_ref_exact_need(ctx, &sd, need, &part), VB_OK);
            size_t bad = 0, wanted = 0;
            for (size_t v = 0; v < full.pixels; v++) {
                wanted += need[v] != 0;
                bad += need[v] && part.labels[v] != full.labels[v];
            }
            CHECK_INT(bad, 0);
            CHECK(rep == 2 ? wanted == 0 : wanted > 0);
            CHECK(rep == 2 ? part.counts.tiles_uniform + part.counts.survivors == 0
                           : part.counts.survivors > 0);
            free(need);
            vbj_result_free(&full);
            vbj_result_free(&part);
            vbj_seeds_free(&sd);
        }
    vbj_backend_close(be);
}

/* The reference engine without VBC_WANT_EDGES (the interior-only stage)
 * against the same engine asked for labels (the whole stage): the same
 * channel voxel list, and the same flags but the edge bit of voxels that
 * are not interior. */
static void test_engine_interior(vb_ctx *ctx)
{
    vbc_engine *e = NULL;
    CHECK_INT(vbc_engine_ref_open(ctx, VBJ_EXACT, &e), VB_OK);
    uint64_t seed = 4242;
    size_t channels = 0;
    for (int rep = 0; rep < 4; rep++) {
        vb_sphere_set *s = rep == 0 ? synth_cylinder(6, 10, 4.0, 1.6, 1.5)
                                    : random_atoms(&seed, 150, 3, 25.0, 1.2, 0.8);
        vbc_grid g;
        CHECK_INT(vbc_grid_fit(ctx, s, 1.4, 64, 3, &g), VB_OK);
        float *atoms = malloc(4 * s->n * sizeof *atoms);
        vbc_atoms_pack(&g, s, 1.4, atoms);
        vbc_frame_out a, b;
        CHECK_INT(e->frame(ctx, e, &g, atoms, s->n, 1.4, VBC_WANT_FLAGS | VBC_WANT_LABELS, &a), VB_OK);
        CHECK_INT(e->frame(ctx, e, &g, atoms, s->n, 1.4, VBC_WANT_FLAGS, &b), VB_OK);
        CHECK(b.labels == NULL);
        CHECK_INT(a.nvoxels, b.nvoxels);
        CHECK(a.nvoxels == b.nvoxels && memcmp(a.voxels, b.voxels, a.nvoxels * sizeof *a.voxels) == 0);
        size_t nv = vbc_grid_voxels(&g), bad = 0;
        for (size_t v = 0; v < nv; v++) {
            unsigned want = a.flags[v] & ((a.flags[v] & VBC_F_INTERIOR) ? 0xffu : (unsigned)~VBC_F_EDGE);
            bad += b.flags[v] != want;
        }
        CHECK_INT(bad, 0);
        channels += a.nvoxels;
        vbc_frame_out_free(&a);
        vbc_frame_out_free(&b);
        free(atoms);
        vb_spheres_free(s);
    }
    CHECK(channels > 0);
    vbc_engine_close(e);
}

int main(void)
{
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK)
        return 1;
    test_single_ball(ctx);
    test_two_balls(ctx);
    test_edges(ctx);
    test_cylinder(ctx);
    test_shell(ctx);
    test_grid_fit_errors(ctx);
    test_same_as_plain(ctx);
    test_interior_only(ctx);
    test_exact_need(ctx);
    test_engine_interior(ctx);
    vb_close(ctx);
    VB_TEST_END();
}
