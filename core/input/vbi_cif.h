/* Internal: the CIF tokenizer used by the mmCIF reader. */
#ifndef VBI_CIF_H
#define VBI_CIF_H

#include <stddef.h>

typedef enum {
    VBI_CIF_VALUE, /* bare, quoted or text-field value (quotes removed) */
    VBI_CIF_TAG,   /* _category.item */
    VBI_CIF_LOOP,  /* loop_ */
    VBI_CIF_BLOCK, /* data_, save_, global_, stop_ */
    VBI_CIF_END,   /* end of input */
    VBI_CIF_ERROR  /* unterminated quote or text field at .line */
} vbi_cif_kind;

typedef struct {
    vbi_cif_kind kind;
    const char *text;
    size_t len;
    long line; /* line where the token starts */
} vbi_cif_token;

typedef struct {
    const char *p, *start, *end;
    long line;
} vbi_cif;

void vbi_cif_init(vbi_cif *c, const char *buf, size_t len);

/* Next token into *t; returns 0 at the end or on an error (t->kind says). */
int vbi_cif_next(vbi_cif *c, vbi_cif_token *t);

/* A category of the first data block: rows x cols cells (tokens pointing
 * into the text; kind VBI_CIF_END for an item the row lacks). */
typedef struct {
    size_t rows, cols;
    vbi_cif_token *cell; /* row-major */
    long error_line;     /* where a malformed category was met */
} vbi_cif_table;

/* Reads category `cat` (e.g. "_pdbx_struct_oper_list") into *out, one
 * column per name of items (e.g. "matrix[1][1]", case-insensitive), from a
 * loop or from item-value pairs. Returns 0 when found, 1 when the category
 * is absent, -1 when it is malformed (out->error_line), -2 out of memory.
 * Free with vbi_cif_table_free (always). */
int vbi_cif_table_read(const char *buf, size_t len, const char *cat, const char *const *items,
                       size_t nitems, vbi_cif_table *out);
void vbi_cif_table_free(vbi_cif_table *t);

#endif
