/* One category of a CIF data block as a table, whether the file writes it
 * as a loop or as item-value pairs (a one-row category usually is). */
#include "vbi_cif.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

/* True when token t is the tag cat + "." + item, case-insensitively
 * (item NULL: any item of the category); *item_at gets the item's start. */
static int tag_of(const vbi_cif_token *t, const char *cat, const char **item_at)
{
    size_t k = strlen(cat);
    if (t->kind != VBI_CIF_TAG || t->len <= k + 1 || t->text[k] != '.')
        return 0;
    for (size_t i = 0; i < k; i++)
        if (tolower((unsigned char)t->text[i]) != tolower((unsigned char)cat[i]))
            return 0;
    *item_at = t->text + k + 1;
    return 1;
}

static int item_index(const vbi_cif_token *t, const char *cat, const char *const *items,
                      size_t nitems)
{
    const char *it;
    if (!tag_of(t, cat, &it))
        return -2;
    size_t n = t->len - (size_t)(it - t->text);
    for (size_t k = 0; k < nitems; k++) {
        size_t m = strlen(items[k]);
        if (m != n)
            continue;
        size_t i = 0;
        while (i < m && tolower((unsigned char)it[i]) == tolower((unsigned char)items[k][i]))
            i++;
        if (i == m)
            return (int)k;
    }
    return -1;
}

void vbi_cif_table_free(vbi_cif_table *t)
{
    free(t->cell);
    memset(t, 0, sizeof *t);
}

/* Appends a row of nitems cells (absent cells kind VBI_CIF_END). */
static int add_row(vbi_cif_table *t, size_t *cap)
{
    if (t->rows == *cap) {
        size_t c = *cap ? 2 * *cap : 16;
        vbi_cif_token *p = realloc(t->cell, c * t->cols * sizeof *p);
        if (!p)
            return -1;
        t->cell = p;
        *cap = c;
    }
    for (size_t k = 0; k < t->cols; k++) {
        memset(&t->cell[t->rows * t->cols + k], 0, sizeof t->cell[0]);
        t->cell[t->rows * t->cols + k].kind = VBI_CIF_END;
    }
    t->rows++;
    return 0;
}

int vbi_cif_table_read(const char *buf, size_t len, const char *cat, const char *const *items,
                       size_t nitems, vbi_cif_table *out)
{
    memset(out, 0, sizeof *out);
    out->cols = nitems;
    size_t cap = 0;
    vbi_cif c;
    vbi_cif_init(&c, buf, len);
    vbi_cif_token t;
    int blocks = 0;
    vbi_cif_next(&c, &t);
    while (t.kind != VBI_CIF_END) {
        if (t.kind == VBI_CIF_ERROR) {
            out->error_line = t.line;
            return -1;
        }
        if (t.kind == VBI_CIF_BLOCK && t.len >= 5 && strncmp(t.text, "data_", 5) == 0 &&
            blocks++ > 0)
            break; /* the next data block is another entry */
        if (t.kind == VBI_CIF_TAG) {
            /* item-value pairs */
            int k = item_index(&t, cat, items, nitems);
            if (k == -2) {
                vbi_cif_next(&c, &t);
                continue;
            }
            if (out->rows == 0 && add_row(out, &cap) != 0)
                return -2;
            long line = t.line;
            vbi_cif_next(&c, &t);
            if (t.kind != VBI_CIF_VALUE) {
                out->error_line = line;
                return -1;
            }
            if (k >= 0)
                out->cell[k] = t;
            vbi_cif_next(&c, &t);
            continue;
        }
        if (t.kind != VBI_CIF_LOOP) {
            vbi_cif_next(&c, &t);
            continue;
        }
        vbi_cif_next(&c, &t);
        const char *it;
        if (t.kind != VBI_CIF_TAG || !tag_of(&t, cat, &it))
            continue;
        /* The loop's columns: which item each one is (-1: not wanted). */
        int col[256];
        size_t ncols = 0;
        while (t.kind == VBI_CIF_TAG) {
            if (ncols == sizeof col / sizeof col[0]) {
                out->error_line = t.line;
                return -1;
            }
            col[ncols++] = item_index(&t, cat, items, nitems);
            vbi_cif_next(&c, &t);
        }
        size_t k = 0;
        while (t.kind == VBI_CIF_VALUE) {
            if (k == 0 && add_row(out, &cap) != 0)
                return -2;
            if (col[k] >= 0)
                out->cell[(out->rows - 1) * nitems + (size_t)col[k]] = t;
            k = (k + 1) % ncols;
            vbi_cif_next(&c, &t);
        }
        if (k != 0) {
            out->error_line = t.line;
            return -1;
        }
        return out->rows ? 0 : 1;
    }
    return out->rows ? 0 : 1;
}
