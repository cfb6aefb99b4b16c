/* The --stats table (vb_stat_field.h). */
#include "vb_stat_field.h"

#include <math.h>
#include <string.h>

#include "vb_json.h"

static vb_stat_field *next(vb_stat_fields *fs, const char *name, vb_stat_kind kind)
{
    if (fs->n >= VB_STAT_FIELDS_MAX)
        return NULL;
    vb_stat_field *e = &fs->f[fs->n++];
    *e = (vb_stat_field){name, kind, NULL, 0, 0.0, NULL};
    return e;
}

void vb_stat_uint(vb_stat_fields *fs, const char *name, uint64_t v)
{
    vb_stat_field *e = next(fs, name, VB_STAT_UINT);
    if (e)
        e->u = v;
}

void vb_stat_real(vb_stat_fields *fs, const char *name, const char *fmt, double v)
{
    vb_stat_field *e = next(fs, name, VB_STAT_REAL);
    if (e) {
        e->fmt = fmt;
        e->x = v;
    }
}

void vb_stat_text(vb_stat_fields *fs, const char *name, const char *s)
{
    vb_stat_field *e = next(fs, name, VB_STAT_TEXT);
    if (e)
        e->s = s;
}

void vb_stat_fields_write(FILE *f, const vb_stat_fields *fs, size_t from)
{
    for (size_t i = from; i < fs->n; i++) {
        const vb_stat_field *e = &fs->f[i];
        fprintf(f, "%s\t", e->name);
        if (e->kind == VB_STAT_UINT)
            fprintf(f, "%llu\n", (unsigned long long)e->u);
        else if (e->kind == VB_STAT_REAL) {
            fprintf(f, e->fmt, e->x);
            fputc('\n', f);
        } else
            fprintf(f, "%s\n", e->s);
    }
}

void vb_stat_fields_write_json(FILE *f, const vb_stat_fields *fs, size_t from, const char *prefix)
{
    size_t lp = prefix ? strlen(prefix) : 0;
    int first = 1;
    fputc('{', f);
    for (size_t i = from; i < fs->n; i++) {
        const vb_stat_field *e = &fs->f[i];
        if (lp && strncmp(e->name, prefix, lp) != 0)
            continue;
        fputs(first ? "" : ", ", f);
        first = 0;
        vb_json_write_string(f, e->name);
        fputs(": ", f);
        if (e->kind == VB_STAT_UINT)
            fprintf(f, "%llu", (unsigned long long)e->u);
        else if (e->kind == VB_STAT_REAL && isfinite(e->x))
            fprintf(f, e->fmt, e->x);
        else if (e->kind == VB_STAT_REAL)
            fputs("null", f);
        else
            vb_json_write_string(f, e->s);
    }
    fputc('}', f);
}
