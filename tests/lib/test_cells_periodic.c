/* Periodic cell measures (vb_cells_run_periodic, issue 34) against facts
 * that hold whatever the integrator does:
 * - one atom in a box whose expanded ball covers its lattice cell: the
 *   volume is the box's, no SAS, and the contacts are the faces of the
 *   cell with the atom's own images (a cube of side 3: three faces of
 *   area 9, each written once, shift positive);
 * - the same in a triclinic box (volume the determinant, 27);
 * - random balls in a box (orthorhombic and triclinic) against the open
 *   run of their 3x3x3 replication: each atom's periodic volume, SAS and
 *   contacts enclose the same exact values as the central copy's (the
 *   enclosures meet), and the contacts match one to one. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vorball.h"

static unsigned long long lcg_state = 4242;

static double uniform(void)
{
    lcg_state = lcg_state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(lcg_state >> 11) / 9007199254740992.0;
}

static vb_sphere_set *read_set(vb_ctx *ctx, const char *text)
{
    vb_read_options ro = {0};
    vb_sphere_set *set = NULL;
    CHECK_INT(vb_spheres_read_buffer(ctx, "test", text, strlen(text), &ro, &set), VB_OK);
    return set;
}

static int meets(double alo, double ahi, double blo, double bhi)
{
    return alo <= bhi && blo <= ahi;
}

/* One atom whose ball covers its cell: volume det, SAS 0, self contacts. */
static void one_atom(vb_ctx *ctx, const char *const *boxarg, int nbox, double probe,
                     size_t faces, double face_area, double width, size_t patches)
{
    vb_sphere_set *set = read_set(ctx, "0.5 0.25 0.125 1\n");
    vb_box box;
    CHECK_INT(vb_box_parse_args(ctx, boxarg, nbox, &box), VB_OK);
    vb_measure_options opt;
    vb_measure_defaults(&opt);
    opt.probe = probe;
    opt.contacts = 1;
    opt.max_patches = patches; /* the cube's edges are degenerate: a budget, not 1e-6 */
    vb_cell_measures m;
    CHECK_INT(vb_cells_run_periodic(ctx, set, &box, &opt, &m), VB_OK);
    CHECK_INT((long)m.n, 1);
    CHECK(m.periodic == 1);
    CHECK(m.vol_lo[0] <= 27.0 && 27.0 <= m.vol_hi[0]);
    CHECK(m.vol_hi[0] - m.vol_lo[0] < width);
    CHECK(m.sas_lo[0] == 0.0 && m.sas_hi[0] < 1e-3);
    /* faces: the contacts written (each once), edges and corners of a cube
     * included */
    CHECK_INT((long)m.ncontacts, (long)faces);
    double sum_lo = 0.0, sum_hi = 0.0;
    for (size_t k = 0; k < m.ncontacts; k++) {
        const vb_contact *c = &m.contacts[k];
        CHECK(c->i == 0 && c->j == 0);
        int a = c->s[0] ? 0 : c->s[1] ? 1 : 2;
        CHECK(c->s[a] > 0); /* each face once: its positive shift */
        /* the cube: its 3 faces (unit shifts) have area 9; its edges and
         * corners meet the images in zero area (enclosures from 0) */
        int unit = abs(c->s[0]) + abs(c->s[1]) + abs(c->s[2]) == 1;
        if (face_area > 0.0 && unit)
            CHECK(c->lo <= face_area && face_area <= c->hi);
        if (face_area > 0.0 && !unit)
            CHECK(c->lo == 0.0);
        sum_lo += c->lo;
        sum_hi += c->hi;
    }
    printf("one atom, %d numbers: volume [%.9f, %.9f], %zu faces, area [%.6f, %.6f]\n", nbox,
           m.vol_lo[0], m.vol_hi[0], m.ncontacts, sum_lo, sum_hi);
    vb_cell_measures_free(&m);
    vb_spheres_free(set);
}

/* n random balls in the box of vectors v (rows), as xyzr text, and their
 * 3x3x3 replication (copy (s0, s1, s2) at index ((s0+1)*9 + (s1+1)*3 +
 * (s2+1)) * n + i; the centre is copy 13). */
static void make_sets(int n, const double v[9], char **one, char **rep)
{
    double c[64][4];
    for (int i = 0; i < n; i++) {
        double f[3] = {uniform(), uniform(), uniform()};
        for (int a = 0; a < 3; a++)
            c[i][a] = f[0] * v[a] + f[1] * v[3 + a] + f[2] * v[6 + a];
        c[i][3] = 0.9 + 0.7 * uniform();
    }
    *one = malloc((size_t)n * 80);
    *rep = malloc((size_t)n * 27 * 80);
    size_t w = 0, q = 0;
    for (int i = 0; i < n; i++)
        w += (size_t)sprintf(*one + w, "%.3f %.3f %.3f %.2f\n", c[i][0], c[i][1], c[i][2],
                             c[i][3]);
    for (int s0 = -1; s0 <= 1; s0++)
        for (int s1 = -1; s1 <= 1; s1++)
            for (int s2 = -1; s2 <= 1; s2++)
                for (int i = 0; i < n; i++) {
                    double p[3];
                    for (int a = 0; a < 3; a++)
                        p[a] = c[i][a] + s0 * v[a] + s1 * v[3 + a] + s2 * v[6 + a];
                    /* the 3-decimal centres plus 1-decimal edges print exactly */
                    q += (size_t)sprintf(*rep + q, "%.3f %.3f %.3f %.2f\n", p[0], p[1], p[2],
                                         c[i][3]);
                }
}

static const vb_contact *find_contact(const vb_cell_measures *m, uint32_t i, uint32_t j,
                                      const int s[3])
{
    for (size_t k = 0; k < m->ncontacts; k++) {
        const vb_contact *c = &m->contacts[k];
        if (c->i == i && c->j == j && c->s[0] == s[0] && c->s[1] == s[1] && c->s[2] == s[2])
            return c;
    }
    return NULL;
}

/* The periodic face of atom a (central copy) and sphere b of the
 * replication, as the periodic run writes it: (i, j, s) canonical. */
static void canonical(uint32_t a, uint32_t b, int n, uint32_t *i, uint32_t *j, int s[3])
{
    uint32_t ia = a % (uint32_t)n, ib = b % (uint32_t)n;
    int ca = (int)(a / (uint32_t)n), cb = (int)(b / (uint32_t)n);
    int d[3] = {cb / 9 - ca / 9, (cb / 3) % 3 - (ca / 3) % 3, cb % 3 - ca % 3};
    int k = d[0] ? 0 : d[1] ? 1 : 2;
    int flip = ib < ia || (ib == ia && d[k] < 0);
    *i = flip ? ib : ia;
    *j = flip ? ia : ib;
    for (int a3 = 0; a3 < 3; a3++)
        s[a3] = flip ? -d[a3] : d[a3];
}

static void against_replication(vb_ctx *ctx, const char *name, const double v[9],
                                const char *const *boxarg)
{
    const int n = 8;
    char *one, *rep;
    make_sets(n, v, &one, &rep);
    vb_sphere_set *set = read_set(ctx, one), *big = read_set(ctx, rep);
    vb_box box;
    CHECK_INT(vb_box_parse_args(ctx, boxarg, 9, &box), VB_OK);
    vb_measure_options opt;
    vb_measure_defaults(&opt);
    opt.probe = 0.6;
    opt.tolerance = 1e-3;
    opt.max_patches = 400;
    opt.contacts = 1;
    vb_cell_measures p, o;
    CHECK_INT(vb_cells_run_periodic(ctx, set, &box, &opt, &p), VB_OK);
    CHECK_INT(vb_cells_run(ctx, big, &opt, &o), VB_OK);
    CHECK_INT((long)p.n, n);
    double vol = 0.0;
    for (int i = 0; i < n; i++) {
        size_t c = 13 * (size_t)n + (size_t)i;
        CHECK(meets(p.vol_lo[i], p.vol_hi[i], o.vol_lo[c], o.vol_hi[c]));
        CHECK(meets(p.sas_lo[i], p.sas_hi[i], o.sas_lo[c], o.sas_hi[c]));
        vol += p.vol_hi[i];
    }
    CHECK(vol > 0.0);
    /* Every open contact of a central atom is a periodic contact, and the
     * periodic contacts are exactly those (each once). */
    size_t seen = 0;
    uint8_t *hit = calloc(p.ncontacts + 1, 1);
    for (size_t k = 0; k < o.ncontacts; k++) {
        const vb_contact *c = &o.contacts[k];
        for (int side = 0; side < 2; side++) {
            uint32_t a = side ? c->j : c->i, b = side ? c->i : c->j;
            if (a / (uint32_t)n != 13)
                continue;
            uint32_t i, j;
            int s[3];
            canonical(a, b, n, &i, &j, s);
            const vb_contact *q = find_contact(&p, i, j, s);
            CHECK(q != NULL);
            if (!q)
                continue;
            CHECK(meets(q->lo, q->hi, c->lo, c->hi));
            hit[q - p.contacts] = 1;
        }
    }
    for (size_t k = 0; k < p.ncontacts; k++)
        seen += hit[k];
    CHECK_INT((long)seen, (long)p.ncontacts);
    CHECK(p.ncontacts >= (size_t)n);
    printf("%s: %d atoms, %zu periodic contacts, volume sum <= %.6f\n", name, n, p.ncontacts, vol);
    free(hit);
    vb_cell_measures_free(&p);
    vb_cell_measures_free(&o);
    vb_spheres_free(set);
    vb_spheres_free(big);
    free(one);
    free(rep);
}

int main(void)
{
    vb_config cfg = {0, NULL};
    vb_ctx *ctx;
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 1;
    const char *cube[3] = {"3", "3", "3"};
    one_atom(ctx, cube, 3, 2.0, 13, 9.0, 20.0, 400);
    const char *tri[9] = {"3", "0", "0", "1", "3", "0", "0.5", "1", "3"};
    one_atom(ctx, tri, 9, 3.0, 7, 0.0, 1e-4, 0);
    const double rect[9] = {8, 0, 0, 0, 9, 0, 0, 0, 10};
    const char *rect_arg[9] = {"8", "0", "0", "0", "9", "0", "0", "0", "10"};
    against_replication(ctx, "orthorhombic", rect, rect_arg);
    const double skew[9] = {8, 0, 0, 1.5, 9, 0, -1, 2, 10};
    const char *skew_arg[9] = {"8", "0", "0", "1.5", "9", "0", "-1", "2", "10"};
    against_replication(ctx, "triclinic", skew, skew_arg);
    /* Two atoms equal modulo the box are one: refused. */
    vb_sphere_set *dup = read_set(ctx, "1 1 1 1\n4 1 1 1\n");
    vb_box box;
    CHECK_INT(vb_box_parse_args(ctx, cube, 3, &box), VB_OK);
    vb_measure_options opt;
    vb_measure_defaults(&opt);
    vb_cell_measures m;
    CHECK_INT(vb_cells_run_periodic(ctx, dup, &box, &opt, &m), VB_EINPUT_DUPLICATE);
    vb_spheres_free(dup);
    vb_close(ctx);
    VB_TEST_END();
}
