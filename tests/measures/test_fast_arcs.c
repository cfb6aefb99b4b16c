/* The arcs' integrands as quotients of polynomials (series_rat.c, used by
 * stokes_cell.c) against the old path's enclosures: a fragment of crambin
 * (1crn residues 1-8, 54 atoms with vorball's radii, data/crn_frag.xyzr)
 * measured by main 4545813 (series products and reciprocals per arc;
 * data/crn_frag_old.txt). Every atom in closed form, no value loose, each
 * new enclosure meets the old one and holds the tolerance; with --contacts
 * the same pairs, each contact meeting its old enclosure. Also the double
 * interval log (integrands.c, which replaced MPFR's there) against MPFR's
 * correctly rounded log on 20000 arguments from 1e-300 to 1e300, near 1,
 * and subnormal: it holds it, within 16 ulps of max(|log x|, 1). */
#include <float.h>
#include <math.h>
#include <mpfr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vb_measures.h"
#include "vb_spheres.h"
#include "measures_balls.h"
#include "vbm_piece.h"
#include "vb_test.h"

#define NATOM 54

typedef struct old_values {
    double vol[NATOM][2], sas[NATOM][2];
    uint32_t ci[512], cj[512];
    double con[512][2];
    size_t ncon;
} old_values;

static int read_old(const char *dir, old_values *o)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/tests/measures/data/crn_frag_old.txt", dir);
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    char line[256];
    size_t na = 0;
    o->ncon = 0;
    while (fgets(line, sizeof line, f)) {
        unsigned i, j;
        double a, b, c, d;
        if (sscanf(line, "a %u %lf %lf %lf %lf", &i, &a, &b, &c, &d) == 5 && i < NATOM) {
            o->vol[i][0] = a, o->vol[i][1] = b, o->sas[i][0] = c, o->sas[i][1] = d;
            na++;
        } else if (sscanf(line, "c %u %u %lf %lf", &i, &j, &a, &b) == 4 && o->ncon < 512) {
            o->ci[o->ncon] = i, o->cj[o->ncon] = j;
            o->con[o->ncon][0] = a, o->con[o->ncon][1] = b;
            o->ncon++;
        }
    }
    fclose(f);
    return na == NATOM;
}

static int meets(double alo, double ahi, const double *old)
{
    int ok = alo <= old[1] && old[0] <= ahi;
    if (!ok)
        fprintf(stderr, "  [%.12g, %.12g] misses the old [%.12g, %.12g]\n", alo, ahi, old[0],
                old[1]);
    return ok;
}

static void run(vb_ctx *ctx, const vb_sphere_set *s, const old_values *o, int contacts)
{
    vb_measure_options opt;
    vb_measure_defaults(&opt);
    opt.threads = 1;
    opt.contacts = contacts;
    vb_cell_measures m;
    CHECK_INT(vb_cell_measures_compute(ctx, s, &opt, &m), VB_OK);
    CHECK_INT(m.n, NATOM);
    CHECK_INT(m.nclosed, NATOM);
    CHECK_INT(m.nloose, 0);
    for (size_t i = 0; i < m.n && i < NATOM; i++) {
        double v = 0.5 * (m.vol_lo[i] + m.vol_hi[i]), a = 0.5 * (m.sas_lo[i] + m.sas_hi[i]);
        double fv = 1e-3 * 4.0 / 3.0 * PI * 8.0, fa = 1e-3 * 4.0 * PI * 4.0; /* r >= 2 */
        CHECK(m.vol_hi[i] - m.vol_lo[i] <= 1e-6 * (v > fv ? v : fv));
        CHECK(m.sas_hi[i] - m.sas_lo[i] <= 1e-6 * (a > fa ? a : fa));
        if (!contacts) { /* the old volumes-only run's targets */
            CHECK(meets(m.vol_lo[i], m.vol_hi[i], o->vol[i]));
            CHECK(meets(m.sas_lo[i], m.sas_hi[i], o->sas[i]));
        }
    }
    if (contacts) {
        CHECK_INT(m.ncontacts, o->ncon);
        for (size_t k = 0; k < m.ncontacts && k < o->ncon; k++) {
            CHECK(m.contacts[k].i == o->ci[k] && m.contacts[k].j == o->cj[k]);
            CHECK(meets(m.contacts[k].lo, m.contacts[k].hi, o->con[k]));
        }
    }
    vb_cell_measures_free(&m);
}

static int log_holds(double x)
{
    mpfr_t t;
    mpfr_init2(t, 53);
    mpfr_set_d(t, x, MPFR_RNDN);
    mpfr_log(t, t, MPFR_RNDN);
    double l = mpfr_get_d(t, MPFR_RNDN);
    mpfr_clear(t);
    vbx_ia r = vbm_ia_log(vbx_ia_point(x));
    double w = (fabs(l) + 1.0) * 0x1p-52 * 16.0; /* 16 ulps of max(|log x|, 1) */
    int ok = r.lo <= l && l <= r.hi && r.hi - r.lo <= w;
    if (!ok)
        fprintf(stderr, "  log(%.17g): [%.17g, %.17g] vs %.17g\n", x, r.lo, r.hi, l);
    return ok;
}

static void test_log(void)
{
    size_t bad = 0;
    srand(40);
    for (int i = 0; i < 10000; i++) {
        double u = (double)rand() / RAND_MAX;
        bad += !log_holds(pow(10.0, 600.0 * u - 300.0));
        bad += !log_holds(1.0 + (u - 0.5) * 1e-3 * pow(10.0, -(i % 12)));
    }
    bad += !log_holds(1.0) + !log_holds(2.0) + !log_holds(0.5) + !log_holds(4.9406564584124654e-324) +
           !log_holds(DBL_MAX) + !log_holds(0.70710678118654746) + !log_holds(1.4142135623730949);
    CHECK_INT(bad, 0);
    vbm_ia_release();
}

int main(void)
{
    test_log();
    {
    const char *dir = getenv("VORBALL_SOURCE_DIR");
    vb_ctx *ctx;
    if (!dir || vb_open(&ctx, NULL) != VB_OK)
        return 1;
    vb_set_verbosity(ctx, 0);
    old_values *o = calloc(1, sizeof *o);
    CHECK(o && read_old(dir, o));
    vb_sphere_set *s = data_spheres(ctx, dir, "tests/measures/data/crn_frag.xyzr");
    CHECK(s != NULL);
    if (s && o) {
        CHECK_INT(s->n, NATOM);
        run(ctx, s, o, 0);
        run(ctx, s, o, 1);
    }
    vb_spheres_free(s);
    free(o);
    vb_close(ctx);
    }
    VB_TEST_END();
}
