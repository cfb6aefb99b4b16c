/* The sphere table (vb_atoms_write): what every 0-based sphere id of a
 * vertex, cell or contact file stands for. */
#include <stdio.h>

#include "vb_numtext.h"
#include "vb_output.h"
#include "vb_spheres.h"

/* A text field, or '.' where the input has none. */
static const char *field(const char *s)
{
    return s && s[0] && !(s[0] == ' ' && !s[1]) ? s : ".";
}

/* Coordinate i as written (its exact decimal), or the double as %.17g in a
 * set without decimals (a trajectory's frame, a channel analysis's copy). */
static void coordinate(const vb_decimal *e, const double *d, size_t i, char out[48])
{
    if (e)
        vb_decimal_format(e[i], out, 48);
    else
        vb_format_g17(d[i], out);
}

int vb_atoms_write(vb_ctx *ctx, FILE *f, const vb_sphere_set *s)
{
    fprintf(f, "# vorball atoms: %s, %zu spheres\n", s->source ? s->source : "-", s->n);
    fputs("id\tchain\tresname\tresseq\ticode\tatom\telement\taltloc\tserial\tline\tx\ty\tz\tr\n", f);
    for (size_t i = 0; i < s->n; i++) {
        const vb_atom_info *a = s->info ? &s->info[i] : NULL;
        char x[48], y[48], z[48], r[48], icode[2] = {0, 0}, altloc[2] = {0, 0};
        coordinate(s->ex, s->x, i, x);
        coordinate(s->ey, s->y, i, y);
        coordinate(s->ez, s->z, i, z);
        coordinate(s->er, s->r, i, r);
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
