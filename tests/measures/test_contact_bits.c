/* The contact pieces' order of work against main 558508e's bits: crambin's
 * fragment (data/crn_frag.xyzr, 54 atoms) with --contacts at the default
 * tolerance and at 1e-8, one thread, every atom's volume and SAS ends, every
 * contact's ends (as %a, exact) and the pieces integrated, equal to those
 * main gave (data/crn_frag_bits_558508e.txt). arc_integral.c computes a
 * contact piece's box before its middle and halves it without the middle
 * where the box's remainder alone is wider than the target
 * (contact_box_first): the same pieces, so the same bits and counts; a
 * piece halved that main kept, or kept that main halved, changes the count
 * and the contacts' ends. VB_CONTACT_BITS_WRITE=FILE writes the table
 * (how the data file was made, with main's arc_integral.c). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vb_measures.h"
#include "vb_spheres.h"
#include "measures_balls.h"
#include "vb_test.h"

/* The run's table: one line per atom, per contact and the pieces. */
static char *table(vb_ctx *ctx, const vb_sphere_set *s, double tolerance)
{
    vb_measure_options opt;
    vb_measure_defaults(&opt);
    opt.threads = 1;
    opt.contacts = 1;
    opt.tolerance = tolerance;
    vb_cell_measures m;
    if (vb_cell_measures_compute(ctx, s, &opt, &m) != VB_OK)
        return NULL;
    size_t cap = 128 * (m.n + m.ncontacts + 2), len = 0;
    char *t = malloc(cap);
    if (t) {
        len += (size_t)snprintf(t + len, cap - len, "tolerance %a pieces %zu closed %zu\n",
                                tolerance, m.patches, m.nclosed);
        for (size_t i = 0; i < m.n; i++)
            len += (size_t)snprintf(t + len, cap - len, "a %zu %a %a %a %a\n", i, m.vol_lo[i],
                                    m.vol_hi[i], m.sas_lo[i], m.sas_hi[i]);
        for (size_t k = 0; k < m.ncontacts; k++)
            len += (size_t)snprintf(t + len, cap - len, "c %u %u %a %a\n", m.contacts[k].i,
                                    m.contacts[k].j, m.contacts[k].lo, m.contacts[k].hi);
    }
    vb_cell_measures_free(&m);
    return t;
}

/* The first line where a and b differ, on stderr; 1 when they are equal. */
static int same_lines(const char *a, const char *b)
{
    for (int line = 1;; line++) {
        size_t na = strcspn(a, "\n"), nb = strcspn(b, "\n");
        if (na != nb || memcmp(a, b, na) != 0) {
            fprintf(stderr, "  line %d: %.*s\n  main's:  %.*s\n", line, (int)na, a, (int)nb, b);
            return 0;
        }
        if (!a[na] || !b[nb])
            return !a[na] && !b[nb];
        a += na + 1;
        b += nb + 1;
    }
}

int main(void)
{
    const char *dir = getenv("VORBALL_SOURCE_DIR");
    vb_ctx *ctx;
    if (!dir || vb_open(&ctx, NULL) != VB_OK)
        return 1;
    vb_set_verbosity(ctx, 0);
    char path[4096];
    vb_sphere_set *s = data_spheres(ctx, dir, "tests/measures/data/crn_frag.xyzr");
    CHECK(s != NULL);
    char *t1 = s ? table(ctx, s, 1e-6) : NULL, *t2 = s ? table(ctx, s, 1e-8) : NULL;
    CHECK(t1 && t2);
    const char *out = getenv("VB_CONTACT_BITS_WRITE");
    if (t1 && t2 && out) {
        FILE *f = fopen(out, "w");
        CHECK(f != NULL);
        if (f) {
            fputs(t1, f);
            fputs(t2, f);
            fclose(f);
        }
    } else if (t1 && t2) {
        snprintf(path, sizeof path, "%s/tests/measures/data/crn_frag_bits_558508e.txt", dir);
        char *pinned = slurp(path), *both = malloc(strlen(t1) + strlen(t2) + 1);
        CHECK(pinned && both);
        if (pinned && both) {
            strcpy(both, t1);
            strcat(both, t2);
            CHECK(same_lines(both, pinned));
            CHECK(strstr(both, "\nc ") != NULL); /* contacts were measured */
        }
        free(pinned);
        free(both);
    }
    free(t1);
    free(t2);
    vb_spheres_free(s);
    vb_close(ctx);
    VB_TEST_END();
}
