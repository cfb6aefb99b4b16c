/* The sphere table (vb_atoms_write): what every 0-based sphere id of a
 * vertex, cell or contact file stands for. */
#include <stdio.h>

#include "vb_output.h"
#include "vb_spheres.h"

/* A text field, or '.' where the input has none. */
static const char *field(const char *s)
{
    return s && s[0] && !(s[0] == ' ' && !s[1]) ? s : ".";
}

int vb_atoms_write(vb_ctx *ctx, FILE *f, const vb_sphere_set *s)
{
    fprintf(f, "# vorball atoms: %s, %zu spheres\n", s->source ? s->source : "-", s->n);
    fputs("id\tchain\tresname\tresseq\ticode\tatom\telement\taltloc\tserial\tline\tx\ty\tz\tr\n", f);
    for (size_t i = 0; i < s->n; i++) {
        const vb_atom_info *a = s->info ? &s->info[i] : NULL;
        char x[48], y[48], z[48], r[48], icode[2] = {0, 0}, altloc[2] = {0, 0};
        vb_decimal_format(s->ex[i], x, sizeof x);
        vb_decimal_format(s->ey[i], y, sizeof y);
        vb_decimal_format(s->ez[i], z, sizeof z);
        vb_decimal_format(s->er[i], r, sizeof r);
        fprintf(f, "%zu\t", i);
        if (a) {
            icode[0] = a->icode;
            altloc[0] = a->altloc;
            fprintf(f, "%s\t%s\t%d\t%s\t%s\t%s\t%s\t%d\t", field(a->chain), field(a->resname),
                    (int)a->resseq, field(icode), field(a->name), field(a->element), field(altloc),
                    (int)a->serial);
        } else {
            fputs(".\t.\t.\t.\t.\t.\t.\t.\t", f);
        }
        fprintf(f, "%ld\t%s\t%s\t%s\t%s\n", s->line ? s->line[i] : 0L, x, y, z, r);
    }
    if (ferror(f))
        return vb_error(ctx, VB_EIO, vb_output_name(f), 0, "writing the atom table failed");
    return VB_OK;
}
