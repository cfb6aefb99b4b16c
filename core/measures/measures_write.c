/* The TSV writers of the cell measures (vb_measures.h). */
#include <stdio.h>
#include <string.h>

#include "vb_measures.h"
#include "vbx_ia.h"

/* Decimal text of an enclosure's ends, rounded outward: lo is moved down by
 * 1e-11 of itself before printing 12 significant digits (which move it by at
 * most 5e-12 of itself), hi up likewise, so the printed interval contains the
 * computed one. Measures are >= 0. */
static void put_lo(FILE *f, double x)
{
    if (x <= 0.0) {
        fputs("\t0", f);
        return;
    }
    fprintf(f, "\t%.12g", vbx_pred(x - x * 1e-11));
}

static void put_hi(FILE *f, double x)
{
    fprintf(f, "\t%.12g", x <= 0.0 ? 0.0 : vbx_succ(x + x * 1e-11));
}

static void put_value(FILE *f, double lo, double hi)
{
    fprintf(f, "\t%.12g", 0.5 * lo + 0.5 * hi);
    put_lo(f, lo);
    put_hi(f, hi);
}

static void put_field(FILE *f, const char *s)
{
    fprintf(f, "\t%s", s && s[0] && strcmp(s, " ") != 0 ? s : ".");
}

void vb_cell_measures_write_atoms(FILE *f, const vb_sphere_set *set, const vb_cell_measures *m)
{
    fputs("id\tchain\tresname\tresseq\tatom\tvolume\tvolume_lo\tvolume_hi\tsas\tsas_lo\tsas_hi\n",
          f);
    for (size_t i = 0; i < m->n; i++) {
        fprintf(f, "%zu", i);
        if (set->info) {
            const vb_atom_info *a = &set->info[i];
            put_field(f, a->chain);
            put_field(f, a->resname);
            fprintf(f, "\t%d", (int)a->resseq);
            put_field(f, a->name);
        } else {
            fputs("\t.\t.\t.\t.", f);
        }
        put_value(f, m->vol_lo[i], m->vol_hi[i]);
        put_value(f, m->sas_lo[i], m->sas_hi[i]);
        fputc('\n', f);
    }
}

void vb_cell_measures_write_contacts(FILE *f, const vb_cell_measures *m)
{
    fputs("id1\tid2\tarea\tarea_lo\tarea_hi\n", f);
    for (size_t k = 0; k < m->ncontacts; k++) {
        fprintf(f, "%u\t%u", m->contacts[k].i, m->contacts[k].j);
        put_value(f, m->contacts[k].lo, m->contacts[k].hi);
        fputc('\n', f);
    }
}

