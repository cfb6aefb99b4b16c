/* CIF tokenizer: whitespace-separated words, '#' comments, 'single' and
 * "double" quoted values (a quote closes only before whitespace), and
 * ;-delimited text fields that start and end at the beginning of a line. */
#include "vbi_cif.h"

#include <ctype.h>
#include <string.h>

void vbi_cif_init(vbi_cif *c, const char *buf, size_t len)
{
    c->p = buf;
    c->start = buf;
    c->end = buf + len;
    c->line = 1;
}

static int is_ws(char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

static int at_line_start(const vbi_cif *c)
{
    return c->p == c->start || c->p[-1] == '\n';
}

static int word_is(const vbi_cif_token *t, const char *w)
{
    size_t k = strlen(w);
    if (t->len < k)
        return 0;
    for (size_t i = 0; i < k; i++)
        if (tolower((unsigned char)t->text[i]) != w[i])
            return 0;
    return 1;
}

int vbi_cif_next(vbi_cif *c, vbi_cif_token *t)
{
    for (;;) {
        while (c->p < c->end && is_ws(*c->p)) {
            if (*c->p == '\n')
                c->line++;
            c->p++;
        }
        if (c->p >= c->end) {
            t->kind = VBI_CIF_END;
            t->line = c->line;
            return 0;
        }
        if (*c->p != '#')
            break;
        while (c->p < c->end && *c->p != '\n')
            c->p++;
    }
    t->line = c->line;
    char q = *c->p;
    if (q == ';' && at_line_start(c)) {
        /* Text field: up to the next line that starts with ';'. */
        const char *s = ++c->p;
        for (;;) {
            const char *nl = memchr(c->p, '\n', (size_t)(c->end - c->p));
            if (!nl) {
                t->kind = VBI_CIF_ERROR;
                return 0;
            }
            c->line++;
            c->p = nl + 1;
            if (c->p < c->end && *c->p == ';') {
                t->text = s;
                t->len = (size_t)(nl - s);
                c->p++;
                t->kind = VBI_CIF_VALUE;
                return 1;
            }
        }
    }
    if (q == '\'' || q == '"') {
        const char *s = ++c->p;
        while (c->p < c->end && *c->p != '\n') {
            if (*c->p == q && (c->p + 1 == c->end || is_ws(c->p[1]))) {
                t->text = s;
                t->len = (size_t)(c->p - s);
                c->p++;
                t->kind = VBI_CIF_VALUE;
                return 1;
            }
            c->p++;
        }
        t->kind = VBI_CIF_ERROR;
        return 0;
    }
    const char *s = c->p;
    while (c->p < c->end && !is_ws(*c->p))
        c->p++;
    t->text = s;
    t->len = (size_t)(c->p - s);
    if (*s == '_')
        t->kind = VBI_CIF_TAG;
    else if (t->len == 5 && word_is(t, "loop_"))
        t->kind = VBI_CIF_LOOP;
    else if (word_is(t, "data_") || word_is(t, "save_") || word_is(t, "global_") ||
             (t->len == 5 && word_is(t, "stop_")))
        t->kind = VBI_CIF_BLOCK;
    else
        t->kind = VBI_CIF_VALUE;
    return 1;
}
