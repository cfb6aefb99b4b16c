/* The cell measures on the results page (vb_measures_page.h). */
#include <stdio.h>
#include <stdlib.h>

#include "vb_measures_page.h"
#include "vbm_text.h"

/* The figures of the frame, counts as the tables count them (the TSV's
 * rows, the contacts TSV's rows) and the sums of the printed values. */
static int add_facts(vb_page *p, int k, const vb_cell_measures *m, int contacts, double vol,
                     double sas)
{
    char v[64];
    int rc = vb_page_fact_count(p, k, "atoms", m->n);
    if (rc == VB_OK)
        rc = vb_page_fact_count(p, k, "empty cells", m->nempty);
    if (rc == VB_OK)
        rc = vb_page_fact_count(p, k, "atoms with a loose value", m->nloose);
    if (rc == VB_OK && contacts)
        rc = vb_page_fact_count(p, k, "contacts", m->ncontacts);
    snprintf(v, sizeof v, "%.6g", vol);
    if (rc == VB_OK)
        rc = vb_page_fact(p, k, "volume sum (Å³)", v);
    snprintf(v, sizeof v, "%.6g", sas);
    if (rc == VB_OK)
        rc = vb_page_fact(p, k, "SAS area sum (Å²)", v);
    return rc;
}

int vb_cell_measures_page_add(vb_ctx *ctx, vb_page *p, const char *label,
                              const vb_sphere_set *set, const vb_cell_measures *m, int contacts)
{
    if (m->n != set->n)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "results page: %zu measures for %zu atoms", m->n,
                        set->n);
    int k, rc = vb_page_frame_set(p, label, set, &k);
    if (rc != VB_OK || k < 0)
        return rc;
    size_t n = m->n ? m->n : 1;
    double *v = malloc(3 * n * sizeof *v);
    if (!v)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory for the results page");
    double *vol = v, *sas = v + n, *area = v + 2 * n, vsum = 0.0, ssum = 0.0;
    for (size_t i = 0; i < m->n; i++) {
        vol[i] = vbm_text_mid(m->vol_lo[i], m->vol_hi[i]);
        sas[i] = vbm_text_mid(m->sas_lo[i], m->sas_hi[i]);
        area[i] = 0.0;
        vsum += vol[i];
        ssum += sas[i];
    }
    for (size_t c = 0; c < m->ncontacts; c++) {
        double a = vbm_text_mid(m->contacts[c].lo, m->contacts[c].hi);
        area[m->contacts[c].i] += a;
        area[m->contacts[c].j] += a;
    }
    rc = vb_page_atom_values(p, k, VB_MEASURES_PAGE_VOLUME, vol);
    if (rc == VB_OK)
        rc = vb_page_atom_values(p, k, VB_MEASURES_PAGE_SAS, sas);
    if (rc == VB_OK && contacts)
        rc = vb_page_atom_values(p, k, VB_MEASURES_PAGE_CONTACT, area);
    if (rc == VB_OK)
        rc = add_facts(p, k, m, contacts, vsum, ssum);
    free(v);
    return rc == VB_ENOMEM ? vb_error(ctx, rc, NULL, 0, "out of memory for the results page") : rc;
}
