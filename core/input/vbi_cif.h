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

#endif
