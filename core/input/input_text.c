/* Line and token helpers shared by the text readers. */
#include "vbi_input.h"

#include <stdlib.h>
#include <string.h>

void vbi_lines_init(vbi_lines *it, const char *buf, size_t len, long first_line)
{
    it->p = buf;
    it->end = buf + len;
    it->lineno = first_line - 1;
}

/* End of the line that starts at s: the first '\n', or a '\r' not followed
 * by '\n' (old Mac OS line ends), or `end`. */
static const char *line_end(const char *s, const char *end)
{
    for (const char *p = s; p < end; p++)
        if (*p == '\n' || (*p == '\r' && (p + 1 == end || p[1] != '\n')))
            return p;
    return end;
}

int vbi_lines_next(vbi_lines *it, const char **line, size_t *len)
{
    if (it->p >= it->end)
        return 0;
    const char *s = it->p;
    const char *e = line_end(s, it->end);
    it->p = e < it->end ? e + 1 : it->end;
    if (e > s && e[-1] == '\r')
        e--;
    *line = s;
    *len = (size_t)(e - s);
    it->lineno++;
    return 1;
}

size_t vbi_bom_length(const char *buf, size_t len)
{
    return len >= 3 && memcmp(buf, "\xef\xbb\xbf", 3) == 0 ? 3 : 0;
}

int vbi_has_lone_cr(const char *buf, size_t len)
{
    for (const char *p = buf, *end = buf + len; (p = memchr(p, '\r', (size_t)(end - p))); p++)
        if (p + 1 == end || p[1] != '\n')
            return 1;
    return 0;
}

void vbi_lone_cr_to_lf(char *buf, size_t len)
{
    for (size_t i = 0; i < len; i++)
        if (buf[i] == '\r' && (i + 1 == len || buf[i + 1] != '\n'))
            buf[i] = '\n';
}

int vbi_check_nul(vb_ctx *ctx, const char *name, const char *buf, size_t len, long first_line)
{
    const char *nul = memchr(buf, '\0', len);
    if (!nul)
        return VB_OK;
    vbi_lines it;
    vbi_lines_init(&it, buf, (size_t)(nul - buf) + 1, first_line);
    const char *line = buf;
    size_t n;
    while (vbi_lines_next(&it, &line, &n))
        ;
    return vb_error(ctx, VB_EINPUT_MALFORMED, name, it.lineno,
                    "NUL byte in column %zu (binary data in a text file?)",
                    (size_t)(nul - line) + 1);
}

static int is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

size_t vbi_token(const char **p, const char *end, const char **tok)
{
    const char *s = *p;
    while (s < end && is_space(*s))
        s++;
    const char *t = s;
    while (s < end && !is_space(*s))
        s++;
    *tok = t;
    *p = s;
    return (size_t)(s - t);
}

int vbi_parse_number(vb_ctx *ctx, const char *name, long line, const char *what,
                     const char *tok, size_t len, vb_decimal *e, double *d)
{
    int rc = vb_decimal_parse(tok, len, e, d);
    if (rc == VB_OK)
        return VB_OK;
    int shown = len > 40 ? 40 : (int)len;
    const char *more = len > 40 ? "..." : "";
    switch (rc) {
    case VB_EINPUT_NONFINITE:
        return vb_error(ctx, rc, name, line, "%s '%.*s' is not finite", what, shown, tok);
    case VB_EINPUT_MAGNITUDE:
        return vb_error(ctx, rc, name, line,
                        "%s '%.*s%s' has more than 18 significant digits or an absurd exponent",
                        what, shown, tok, more);
    default:
        return vb_error(ctx, rc, name, line, "%s '%.*s%s' is not a decimal number", what, shown,
                        tok, more);
    }
}

int vbi_parse_int(const char *s, size_t len, int32_t *out)
{
    char buf[16];
    if (vbi_copy_field(buf, sizeof buf, s, len) || buf[0] == '\0')
        return -1;
    char *end;
    long v = strtol(buf, &end, 10);
    if (*end != '\0' || v < INT32_MIN || v > INT32_MAX)
        return -1;
    *out = (int32_t)v;
    return 0;
}

int vbi_pdb_record(const char *line, size_t n, const char *rec)
{
    size_t k = strlen(rec);
    if (n < k || memcmp(line, rec, k) != 0)
        return 0;
    /* The record name fills columns 1-6: the rest of them must be blank
     * (HETATM has no room left, so "HETATM12345" is a record). */
    for (size_t i = k; i < 6 && i < n; i++)
        if (!is_space(line[i]))
            return 0;
    return 1;
}

int vbi_copy_field(char *dst, size_t cap, const char *src, size_t len)
{
    while (len > 0 && is_space(*src)) {
        src++;
        len--;
    }
    while (len > 0 && is_space(src[len - 1]))
        len--;
    int truncated = len > cap - 1;
    if (truncated)
        len = cap - 1;
    memcpy(dst, src, len);
    dst[len] = '\0';
    return truncated;
}
