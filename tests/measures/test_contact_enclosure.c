/* The contacts of the contact's Taylor model (contact_tm.c) against values
 * made without it.
 * - Three balls (four cases, equal and unequal radii, a third ball cutting
 *   every face): each contact's interval at the tolerances 1e-6, 1e-8 and
 *   1e-10, integrated from both atoms and met (contacts_both), holds the
 *   area by mpmath quadrature to 30 digits
 *   (data/three_ball_contacts.txt, from three_ball_contacts.py beside it).
 * - Crambin's fragment (data/crn_frag.xyzr, 54 atoms), --contacts, one
 *   thread: at 1e-6 and 1e-8 every contact's interval meets the enclosure
 *   main 08bf0c8 gave at 1e-9 (data/crn_frag_contacts_ref.txt, %a ends,
 *   the remainder there from the contact's series over the whole piece,
 *   which the model replaced; written by this test's VB_CONTACT_REF_WRITE
 *   with main's library), and so does the two sides' meet at 1e-8 (the
 *   run fails if they are disjoint); the same pairs, no value looser than
 *   asked;
 * - the volume and SAS ends with --contacts are those without, bit for bit
 *   (a piece adds only the values it integrated: arc_integral.c's piece);
 * - fewer pieces than main's 9642 at 1e-6 (the reason for the model).
 * - no more pieces than f036ceb's 6447 at 1e-6 and 9098 at 1e-8 (the
 *   series near e_j taken wherever a piece is near: NEAR_PIECES_*).
 * An enclosure that leaves out the true value (a remainder too narrow)
 * misses the reference interval at one tolerance or the other. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vb_measures.h"
#include "vb_spheres.h"
#include "measures_balls.h"
#include "vb_test.h"

#define MAIN_PIECES_1E6 9642 /* main 558508e .. 08bf0c8 on crn_frag at 1e-6 */
/* crn_frag's pieces at 1e-6 and 1e-8 on main f036ceb, where arcs passing
 * near e_j go by the contact's series in 1 - z (contact_near): phi's
 * coefficients there made per arc (arc_integral.c near_of); an arc that
 * may come near left without them gives 6470 and 9138 */
#define NEAR_PIECES_1E6 6447
#define NEAR_PIECES_1E8 9098
#define MAX_BALLS 512        /* the three-ball file's text */

/* contacts 2: each contact integrated from both atoms and the two met
 * (contacts_both: the run fails when they are disjoint). */
static int run(vb_ctx *ctx, const vb_sphere_set *s, double tolerance, int contacts,
               vb_cell_measures *m)
{
    vb_measure_options opt;
    vb_measure_defaults(&opt);
    opt.threads = 1;
    opt.contacts = contacts != 0;
    opt.contacts_both = contacts == 2;
    opt.tolerance = tolerance;
    return vb_cell_measures_compute(ctx, s, &opt, m) == VB_OK;
}

typedef struct ref {
    unsigned i, j;
    double lo, hi;
} ref;

/* The reference contacts ("c i j lo hi" lines); *n their count. */
static ref *read_ref(const char *text, size_t *n)
{
    size_t cap = 4096, k = 0;
    ref *r = malloc(cap * sizeof *r);
    for (const char *p = text; r && p && *p; p = strchr(p, '\n'), p = p ? p + 1 : NULL) {
        ref x;
        if (sscanf(p, "c %u %u %la %la", &x.i, &x.j, &x.lo, &x.hi) == 4 && k < cap)
            r[k++] = x;
    }
    *n = k;
    return r;
}

/* Every contact of m meets its reference enclosure (both hold the true
 * area; main's at 1e-9 is not always the narrower: its floors and depth
 * limit); the same pairs. */
static int holds_ref(const vb_cell_measures *m, const ref *r, size_t nr, double tolerance)
{
    int ok = m->ncontacts == nr, shown = 0;
    for (size_t k = 0; ok && k < nr; k++) {
        const vb_contact *c = &m->contacts[k];
        int in = c->lo <= r[k].hi && r[k].lo <= c->hi;
        if (c->i != r[k].i || c->j != r[k].j)
            ok = 0;
        else if (!in && shown++ < 5) {
            fprintf(stderr, "  tolerance %g: contact %u %u [%a, %a] misses main's [%a, %a]\n",
                    tolerance, c->i, c->j, c->lo, c->hi, r[k].lo, r[k].hi);
        }
    }
    if (m->ncontacts != nr)
        fprintf(stderr, "  %zu contacts, main's %zu\n", m->ncontacts, nr);
    return ok && !shown;
}

/* The three-ball cases of data/three_ball_contacts.txt at `tolerance`:
 * every contact's interval holds mpmath's area and every area a contact;
 * the number of areas checked in *n. */
static int three_balls(vb_ctx *ctx, const char *text, double tolerance, int *n)
{
    int ok = 1;
    char name[64], prev[64] = "";
    for (const char *p = text; p && *p; p = strchr(p, '\n'), p = p ? p + 1 : NULL) {
        if (sscanf(p, "ball %63s", name) != 1 || !strcmp(name, prev))
            continue;
        snprintf(prev, sizeof prev, "%s", name);
        char xyzr[MAX_BALLS] = "", line[128];
        size_t len = 0;
        unsigned i, j;
        double x, y, z, r, area;
        for (const char *q = p; q && *q; q = strchr(q, '\n'), q = q ? q + 1 : NULL)
            if (sscanf(q, "ball %63s %lf %lf %lf %lf", line, &x, &y, &z, &r) == 5 &&
                !strcmp(line, name) && len + 128 < sizeof xyzr)
                len += (size_t)snprintf(xyzr + len, sizeof xyzr - len, "%.17g %.17g %.17g %.17g\n",
                                        x, y, z, r);
        vb_sphere_set *s = spheres(ctx, xyzr);
        vb_cell_measures m;
        if (!s || !run(ctx, s, tolerance, 2, &m)) {
            vb_spheres_free(s);
            return 0;
        }
        size_t found = 0;
        for (const char *q = text; q && *q; q = strchr(q, '\n'), q = q ? q + 1 : NULL) {
            if (sscanf(q, "area %63s %u %u %lf", line, &i, &j, &area) != 4 || strcmp(line, name))
                continue;
            ++*n;
            for (size_t k = 0; k < m.ncontacts; k++) {
                const vb_contact *c = &m.contacts[k];
                if (c->i != i || c->j != j)
                    continue;
                found++;
                if (!(c->lo <= area && area <= c->hi)) {
                    fprintf(stderr, "  %s %u %u at %g: [%.17g, %.17g] misses %.17g\n", name, i,
                            j, tolerance, c->lo, c->hi, area);
                    ok = 0;
                }
            }
        }
        ok = ok && found == m.ncontacts && m.nloose == 0;
        vb_cell_measures_free(&m);
        vb_spheres_free(s);
    }
    return ok;
}

static int same_atoms(const vb_cell_measures *a, const vb_cell_measures *b)
{
    size_t n = a->n * sizeof(double);
    return a->n == b->n && !memcmp(a->vol_lo, b->vol_lo, n) && !memcmp(a->vol_hi, b->vol_hi, n) &&
           !memcmp(a->sas_lo, b->sas_lo, n) && !memcmp(a->sas_hi, b->sas_hi, n);
}

int main(void)
{
    const char *dir = getenv("VORBALL_SOURCE_DIR");
    vb_ctx *ctx;
    if (!dir || vb_open(&ctx, NULL) != VB_OK)
        return 1;
    vb_set_verbosity(ctx, 0);
    vb_sphere_set *s = data_spheres(ctx, dir, "tests/measures/data/crn_frag.xyzr");
    CHECK(s != NULL);
    const char *out = getenv("VB_CONTACT_REF_WRITE");
    if (s && out) { /* the reference, from main's library */
        vb_cell_measures m;
        FILE *f = fopen(out, "w");
        CHECK(f && run(ctx, s, 1e-10, 1, &m));
        if (f) {
            for (size_t k = 0; k < m.ncontacts; k++)
                fprintf(f, "c %u %u %a %a\n", m.contacts[k].i, m.contacts[k].j,
                        m.contacts[k].lo, m.contacts[k].hi);
            fclose(f);
            vb_cell_measures_free(&m);
        }
    } else if (s) {
        char path[4096];
        snprintf(path, sizeof path, "%s/tests/measures/data/three_ball_contacts.txt", dir);
        char *tb = slurp(path);
        CHECK(tb != NULL);
        for (int t = 0; tb && t < 3; t++) {
            int n = 0;
            double tol = t == 0 ? 1e-6 : t == 1 ? 1e-8 : 1e-10;
            CHECK(three_balls(ctx, tb, tol, &n));
            CHECK_INT(n, 12);
        }
        free(tb);
        snprintf(path, sizeof path, "%s/tests/measures/data/crn_frag_contacts_ref.txt", dir);
        char *text = slurp(path);
        size_t nr = 0;
        ref *r = text ? read_ref(text, &nr) : NULL;
        CHECK(r && nr > 100);
        vb_cell_measures m6, m8, plain, both;
        CHECK(run(ctx, s, 1e-6, 1, &m6) && run(ctx, s, 1e-8, 1, &m8) &&
              run(ctx, s, 1e-6, 0, &plain) && run(ctx, s, 1e-8, 2, &both));
        if (r) {
            CHECK(holds_ref(&m6, r, nr, 1e-6));
            CHECK(holds_ref(&m8, r, nr, 1e-8));
            CHECK(holds_ref(&both, r, nr, 1e-8));
        }
        CHECK(m6.nloose == 0 && m8.nloose == 0);
        CHECK(same_atoms(&m6, &plain));
        fprintf(stderr, "  pieces at 1e-6: %zu (main %d), at 1e-8: %zu\n", m6.patches,
                MAIN_PIECES_1E6, m8.patches);
        CHECK(m6.patches < MAIN_PIECES_1E6);
        CHECK(m6.patches <= NEAR_PIECES_1E6 && m8.patches <= NEAR_PIECES_1E8);
        vb_cell_measures_free(&m6);
        vb_cell_measures_free(&m8);
        vb_cell_measures_free(&plain);
        vb_cell_measures_free(&both);
        free(r);
        free(text);
    }
    vb_spheres_free(s);
    vb_close(ctx);
    VB_TEST_END();
}
