/* The TSV writers of the cell measures (vb_measures.h). */
#include <stdio.h>
#include <string.h>

#include "vb_measures.h"
#include "vbm_text.h"

/* The midpoint, then the ends rounded outward (vbm_text.h). */
static void put_value(FILE *f, double lo, double hi)
{
    fprintf(f, "\t%.12g", vbm_text_mid(lo, hi));
    if (lo <= 0.0)
        fputs("\t0", f);
    else
        fprintf(f, "\t%.12g", vbm_text_lo(lo));
    fprintf(f, "\t%.12g", vbm_text_hi(hi));
}

static void put_field(FILE *f, const char *s)
{
    fprintf(f, "\t%s", s && s[0] && strcmp(s, " ") != 0 ? s : ".");
}

void vb_cell_measures_write_atoms_header(FILE *f, int frames)
{
    fputs(frames ? "frame\t" : "", f);
    fputs("id\tchain\tresname\tresseq\tatom\tvolume\tvolume_lo\tvolume_hi\tsas\tsas_lo\tsas_hi\n",
          f);
}

void vb_cell_measures_write_atom_rows(FILE *f, const vb_sphere_set *set, const vb_cell_measures *m,
                                      long frame)
{
    for (size_t i = 0; i < m->n; i++) {
        if (frame >= 0)
            fprintf(f, "%ld\t", frame);
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

void vb_cell_measures_write_atoms(FILE *f, const vb_sphere_set *set, const vb_cell_measures *m)
{
    vb_cell_measures_write_atoms_header(f, 0);
    vb_cell_measures_write_atom_rows(f, set, m, -1);
}

void vb_cell_measures_write_contacts_header(FILE *f, int frames)
{
    fputs(frames ? "frame\tid1\tid2\tarea\tarea_lo\tarea_hi\n" : "id1\tid2\tarea\tarea_lo\tarea_hi\n",
          f);
}

void vb_cell_measures_write_contact_rows(FILE *f, const vb_cell_measures *m, long frame)
{
    for (size_t k = 0; k < m->ncontacts; k++) {
        if (frame >= 0)
            fprintf(f, "%ld\t", frame);
        const vb_contact *c = &m->contacts[k];
        if (m->periodic)
            fprintf(f, "%u\t%u@(%d,%d,%d)", c->i, c->j, c->s[0], c->s[1], c->s[2]);
        else
            fprintf(f, "%u\t%u", c->i, c->j);
        put_value(f, c->lo, c->hi);
        fputc('\n', f);
    }
}

void vb_cell_measures_write_contacts(FILE *f, const vb_cell_measures *m)
{
    vb_cell_measures_write_contacts_header(f, 0);
    vb_cell_measures_write_contact_rows(f, m, -1);
}
