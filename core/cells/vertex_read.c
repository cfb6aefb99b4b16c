/* Reader of vertex files: tsv, json and Voronota vertex lines, detected by
 * content. Every vertex remembers its source line so that `vorball verify`
 * can point at the line it judges. */
#include "vb_vertex_io.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "vb_array.h"

/* Reading state shared by the three parsers. */
typedef struct {
    vb_ctx *ctx;
    const char *name;
    vb_vertex_list *out;
    long *lines;        /* source line of each appended vertex */
    size_t nlines, lines_cap;
    uint32_t *ids;      /* scratch id list of the vertex being read */
    size_t nids, ids_cap;
} reader;

static int push_id(reader *r, uint32_t id)
{
    if (VB_ARRAY_FIT(r->ids, r->ids_cap, r->nids + 1, 16) != VB_OK)
        return vb_error(r->ctx, VB_ENOMEM, r->name, 0, "out of memory reading vertices");
    r->ids[r->nids++] = id;
    return VB_OK;
}

static int push_vertex(reader *r, long line, const double p[4], int status)
{
    /* A vertex names each of its spheres once: a repeat is a broken writer. */
    for (size_t a = 1; a < r->nids; a++)
        for (size_t b = 0; b < a; b++)
            if (r->ids[a] == r->ids[b])
                return vb_error(r->ctx, VB_EINPUT_MALFORMED, r->name, line,
                                "sphere %u is named twice", (unsigned)r->ids[a]);
    if (VB_ARRAY_FIT(r->lines, r->lines_cap, r->nlines + 1, 64) != VB_OK)
        return vb_error(r->ctx, VB_ENOMEM, r->name, 0, "out of memory reading vertices");
    if (vb_vertex_list_push(r->out, r->ids, r->nids, p[0], p[1], p[2], p[3], 0.0, status))
        return vb_error(r->ctx, VB_ENOMEM, r->name, 0, "out of memory reading vertices");
    r->lines[r->nlines++] = line;
    r->nids = 0;
    return VB_OK;
}

/* Parses a whole token as an id (decimal, < 2^32). */
static int parse_id(const char *s, size_t len, uint32_t *out)
{
    if (len == 0 || len > 10)
        return -1;
    uint64_t v = 0;
    for (size_t i = 0; i < len; i++) {
        if (s[i] < '0' || s[i] > '9')
            return -1;
        v = v * 10 + (uint64_t)(s[i] - '0');
    }
    if (v > UINT32_MAX)
        return -1;
    *out = (uint32_t)v;
    return 0;
}

/* Parses a whole token as a finite double. Returns VB_OK, or the input
 * error code (recorded with file:line). */
static int parse_number(reader *r, long line, const char *s, size_t len, const char *what,
                        double *out)
{
    char tmp[64];
    if (len == 0 || len >= sizeof tmp)
        return vb_error(r->ctx, VB_EINPUT_MALFORMED, r->name, line, "bad number for %s", what);
    memcpy(tmp, s, len);
    tmp[len] = '\0';
    char *end;
    errno = 0;
    double d = strtod(tmp, &end);
    if (end != tmp + len)
        return vb_error(r->ctx, VB_EINPUT_MALFORMED, r->name, line, "bad number '%s' for %s",
                        tmp, what);
    if (!isfinite(d))
        return vb_error(r->ctx, VB_EINPUT_NONFINITE, r->name, line, "%s is '%s'", what, tmp);
    *out = d;
    return VB_OK;
}

static int parse_status(const char *s, size_t len, int *out)
{
    static const struct {
        const char *name;
        int status;
    } names[] = {{"candidate", VB_VERTEX_CANDIDATE},
                 {"certified", VB_VERTEX_CERTIFIED},
                 {"rejected", VB_VERTEX_REJECTED}};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (strlen(names[i].name) == len && memcmp(names[i].name, s, len) == 0) {
            *out = names[i].status;
            return 0;
        }
    return -1;
}

/* ---- line formats (tsv, voronota) ---- */

typedef struct {
    const char *s;
    size_t len;
} token;

enum { MAX_FIELDS = 9 };

/* Splits a line on blanks and tabs into at most MAX_FIELDS tokens; returns
 * the number of tokens, MAX_FIELDS meaning "too many". */
static size_t split(const char *s, size_t len, token *tok)
{
    size_t n = 0, i = 0;
    while (i < len && n < MAX_FIELDS) {
        while (i < len && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r'))
            i++;
        if (i == len)
            break;
        size_t b = i;
        while (i < len && s[i] != ' ' && s[i] != '\t' && s[i] != '\r')
            i++;
        tok[n++] = (token){s + b, i - b};
    }
    return n;
}

/* True for blank lines and '#' comments, which every line format skips. */
static int skippable(const char *s, size_t len)
{
    size_t i = 0;
    while (i < len && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r'))
        i++;
    return i == len || s[i] == '#';
}

/* The point of a line: x, y, z and the fourth coordinate (named `fourth`
 * in messages: t, or voronota's r) from tok[0 .. 3]. VB_OK or the input
 * error (parse_number). */
static int parse_point(reader *r, long line, const token *tok, const char *fourth, double p[4])
{
    const char *what[4] = {"x", "y", "z", fourth};
    for (int c = 0; c < 4; c++) {
        int rc = parse_number(r, line, tok[c].s, tok[c].len, what[c], &p[c]);
        if (rc)
            return rc;
    }
    return VB_OK;
}

static int parse_tsv_line(reader *r, long line, const token *tok, size_t n)
{
    if (n < 5 || n > 6)
        return vb_error(r->ctx, VB_EINPUT_MALFORMED, r->name, line,
                        "expected 'ids x y z t [status]', found %zu fields", n);
    const char *s = tok[0].s;
    size_t len = tok[0].len, b = 0;
    r->nids = 0;
    for (size_t i = 0; i <= len; i++) {
        if (i < len && s[i] != ',')
            continue;
        uint32_t id;
        if (parse_id(s + b, i - b, &id))
            return vb_error(r->ctx, VB_EINPUT_MALFORMED, r->name, line,
                            "ids must be comma-separated integers below 2^32");
        int rc = push_id(r, id);
        if (rc)
            return rc;
        b = i + 1;
    }
    double p[4];
    int rc = parse_point(r, line, tok + 1, "t", p);
    if (rc)
        return rc;
    int status = VB_VERTEX_CANDIDATE;
    if (n == 6 && parse_status(tok[5].s, tok[5].len, &status))
        return vb_error(r->ctx, VB_EINPUT_MALFORMED, r->name, line,
                        "status must be candidate, certified or rejected");
    return push_vertex(r, line, p, status);
}

static int parse_voronota_line(reader *r, long line, const token *tok, size_t n)
{
    if (n != 8)
        return vb_error(r->ctx, VB_EINPUT_MALFORMED, r->name, line,
                        "expected 'q1 q2 q3 q4 x y z r', found %zu fields", n);
    r->nids = 0;
    for (int i = 0; i < 4; i++) {
        uint32_t id;
        if (parse_id(tok[i].s, tok[i].len, &id))
            return vb_error(r->ctx, VB_EINPUT_MALFORMED, r->name, line,
                            "sphere id %d is not an integer below 2^32", i + 1);
        int rc = push_id(r, id);
        if (rc)
            return rc;
    }
    double p[4];
    int rc = parse_point(r, line, tok + 4, "r", p);
    return rc ? rc : push_vertex(r, line, p, VB_VERTEX_CANDIDATE);
}

/* The fields of the next line from buf[*i] that is neither blank nor a
 * comment, in tok[0 .. *n); *i moves past it and *line counts the lines
 * read. 0 at the end of buf. */
static int next_fields(const char *buf, size_t len, size_t *i, long *line,
                       token tok[MAX_FIELDS], size_t *n)
{
    while (*i < len) {
        const char *s = buf + *i;
        const char *nl = memchr(s, '\n', len - *i);
        size_t l = nl ? (size_t)(nl - s) : len - *i;
        *i += l + (nl != NULL);
        ++*line;
        if (!skippable(s, l)) {
            *n = split(s, l, tok);
            return 1;
        }
    }
    return 0;
}

static int parse_lines(reader *r, const char *buf, size_t len, vb_vertex_format fmt)
{
    long line = 0;
    size_t i = 0, n;
    token tok[MAX_FIELDS];
    while (next_fields(buf, len, &i, &line, tok, &n)) {
        int rc = fmt == VB_VFMT_TSV ? parse_tsv_line(r, line, tok, n)
                                    : parse_voronota_line(r, line, tok, n);
        if (rc)
            return rc;
    }
    return VB_OK;
}

/* ---- json ---- */

typedef struct {
    reader *r;
    const char *s;
    size_t len, pos;
    long line;
} jcursor;

enum { JSON_MAX_DEPTH = 64 };

static int jfail(jcursor *j, const char *what)
{
    return vb_error(j->r->ctx, VB_EINPUT_MALFORMED, j->r->name, j->line, "json: %s", what);
}

static void jws(jcursor *j)
{
    while (j->pos < j->len) {
        char c = j->s[j->pos];
        if (c == '\n')
            j->line++;
        else if (c != ' ' && c != '\t' && c != '\r')
            return;
        j->pos++;
    }
}

/* Consumes `c` after blanks; 0 when found. */
static int jeat(jcursor *j, char c)
{
    jws(j);
    if (j->pos < j->len && j->s[j->pos] == c) {
        j->pos++;
        return 0;
    }
    return -1;
}

/* Reads a string; the raw (still escaped) bytes go to *s, *len. Keys and
 * status words we compare never contain escapes. */
static int jstring(jcursor *j, const char **s, size_t *len)
{
    if (jeat(j, '"'))
        return jfail(j, "expected a string");
    size_t b = j->pos;
    while (j->pos < j->len && j->s[j->pos] != '"') {
        if (j->s[j->pos] == '\n')
            return jfail(j, "newline inside a string");
        if (j->s[j->pos] == '\\')
            j->pos++;
        j->pos++;
    }
    if (j->pos >= j->len)
        return jfail(j, "unterminated string");
    *s = j->s + b;
    *len = j->pos - b;
    j->pos++;
    return VB_OK;
}

/* Reads a number token (or `null`, returned as an empty token). */
static int jtoken(jcursor *j, const char **s, size_t *len)
{
    jws(j);
    size_t b = j->pos;
    if (j->len - b >= 4 && memcmp(j->s + b, "null", 4) == 0) {
        j->pos += 4;
        *s = j->s + b;
        *len = 0;
        return VB_OK;
    }
    while (j->pos < j->len && strchr("+-0123456789.eE", j->s[j->pos]))
        j->pos++;
    if (j->pos == b)
        return jfail(j, "expected a number");
    *s = j->s + b;
    *len = j->pos - b;
    return VB_OK;
}

static int jskip(jcursor *j, int depth)
{
    if (depth > JSON_MAX_DEPTH)
        return jfail(j, "nested too deeply");
    jws(j);
    if (j->pos >= j->len)
        return jfail(j, "unexpected end");
    char c = j->s[j->pos];
    const char *s;
    size_t len;
    if (c == '"')
        return jstring(j, &s, &len);
    if (c == '{' || c == '[') {
        char close = c == '{' ? '}' : ']';
        j->pos++;
        if (jeat(j, close) == 0)
            return VB_OK;
        do {
            int rc;
            if (c == '{') {
                if ((rc = jstring(j, &s, &len)))
                    return rc;
                if (jeat(j, ':'))
                    return jfail(j, "expected ':'");
            }
            if ((rc = jskip(j, depth + 1)))
                return rc;
        } while (jeat(j, ',') == 0);
        return jeat(j, close) ? jfail(j, "unterminated object or array") : VB_OK;
    }
    static const char *words[] = {"true", "false"};
    for (int i = 0; i < 2; i++) {
        size_t l = strlen(words[i]);
        if (j->len - j->pos >= l && memcmp(j->s + j->pos, words[i], l) == 0) {
            j->pos += l;
            return VB_OK;
        }
    }
    return jtoken(j, &s, &len);
}

static int key_is(const char *s, size_t len, const char *key)
{
    return strlen(key) == len && memcmp(s, key, len) == 0;
}

static int jvertex(jcursor *j)
{
    reader *r = j->r;
    jws(j);
    long line = j->line;
    if (jeat(j, '{'))
        return jfail(j, "expected a vertex object");
    double p[4];
    int have = 0, status = VB_VERTEX_CANDIDATE;
    static const char *what[4] = {"x", "y", "z", "t"};
    r->nids = 0;
    if (jeat(j, '}') == 0)
        return jfail(j, "empty vertex object");
    do {
        const char *k, *s;
        size_t klen, len;
        int rc = jstring(j, &k, &klen);
        if (rc)
            return rc;
        if (jeat(j, ':'))
            return jfail(j, "expected ':'");
        int c = -1;
        for (int i = 0; i < 4; i++)
            if (key_is(k, klen, what[i]))
                c = i;
        if (c >= 0) {
            if ((rc = jtoken(j, &s, &len)))
                return rc;
            if (len == 0)
                return vb_error(r->ctx, VB_EINPUT_NONFINITE, r->name, j->line, "%s is null",
                                what[c]);
            if ((rc = parse_number(r, j->line, s, len, what[c], &p[c])))
                return rc;
            have |= 1 << c;
        } else if (key_is(k, klen, "ids")) {
            if (jeat(j, '['))
                return jfail(j, "ids must be an array");
            r->nids = 0;
            if (jeat(j, ']')) {
                do {
                    uint32_t id;
                    if ((rc = jtoken(j, &s, &len)))
                        return rc;
                    if (parse_id(s, len, &id))
                        return jfail(j, "ids must be integers below 2^32");
                    if ((rc = push_id(r, id)))
                        return rc;
                } while (jeat(j, ',') == 0);
                if (jeat(j, ']'))
                    return jfail(j, "unterminated ids array");
            }
            if (r->nids == 0)
                return jfail(j, "ids must not be empty");
            have |= 1 << 4;
        } else if (key_is(k, klen, "status")) {
            if ((rc = jstring(j, &s, &len)))
                return rc;
            if (parse_status(s, len, &status))
                return jfail(j, "status must be candidate, certified or rejected");
        } else if ((rc = jskip(j, 2))) {
            return rc;
        }
    } while (jeat(j, ',') == 0);
    if (jeat(j, '}'))
        return jfail(j, "unterminated vertex object");
    if (have != 0x1f)
        return vb_error(r->ctx, VB_EINPUT_MALFORMED, r->name, line,
                        "json: vertex needs ids, x, y, z and t");
    return push_vertex(r, line, p, status);
}

static int parse_json(reader *r, const char *buf, size_t len)
{
    jcursor j = {r, buf, len, 0, 1};
    if (jeat(&j, '{'))
        return jfail(&j, "expected '{'");
    int rc, seen = 0;
    if (jeat(&j, '}')) {
        do {
            const char *k;
            size_t klen;
            if ((rc = jstring(&j, &k, &klen)))
                return rc;
            if (jeat(&j, ':'))
                return jfail(&j, "expected ':'");
            if (!key_is(k, klen, "vertices")) {
                if ((rc = jskip(&j, 1)))
                    return rc;
                continue;
            }
            seen = 1;
            if (jeat(&j, '['))
                return jfail(&j, "vertices must be an array");
            if (jeat(&j, ']') == 0)
                continue;
            do {
                if ((rc = jvertex(&j)))
                    return rc;
            } while (jeat(&j, ',') == 0);
            if (jeat(&j, ']'))
                return jfail(&j, "unterminated vertices array");
        } while (jeat(&j, ',') == 0);
        if (jeat(&j, '}'))
            return jfail(&j, "unterminated object");
    }
    jws(&j);
    if (j.pos != j.len)
        return jfail(&j, "text after the closing '}'");
    if (!seen)
        return jfail(&j, "no \"vertices\" array");
    return VB_OK;
}

/* ---- detection and entry points ---- */

/* The first line that is neither blank nor a comment decides: '{' is json,
 * eight fields with an id-only first field are Voronota, anything else tsv
 * (whose first field, the id list, always holds commas). */
static vb_vertex_format detect(const char *buf, size_t len)
{
    long line = 0;
    size_t i = 0, n;
    token tok[MAX_FIELDS];
    if (!next_fields(buf, len, &i, &line, tok, &n))
        return VB_VFMT_TSV;
    if (tok[0].s[0] == '{')
        return VB_VFMT_JSON;
    if (n == 8 && !memchr(tok[0].s, ',', tok[0].len))
        return VB_VFMT_VORONOTA;
    return VB_VFMT_TSV;
}

int vb_vertex_read_buffer(vb_ctx *ctx, const char *name, const char *buf, size_t len,
                          vb_vertex_list *out, vb_vertex_format *detected, long **lines)
{
    reader r = {ctx, name, out, NULL, 0, 0, NULL, 0, 0};
    size_t n0 = out->n;
    if (len >= 4 && memcmp(buf, "PK\x03\x04", 4) == 0)
        return vb_error(ctx, VB_EINPUT_FORMAT, name, 0,
                        "an npz vertex file is for NumPy (np.load); vorball reads tsv, json and "
                        "voronota vertex files");
    vb_vertex_format fmt = detect(buf, len);
    int rc = fmt == VB_VFMT_JSON ? parse_json(&r, buf, len) : parse_lines(&r, buf, len, fmt);
    free(r.ids);
    if (rc != VB_OK) {
        /* Drop the partial vertices so the caller's list is as it was. */
        out->n = n0;
        out->nids = out->start ? out->start[n0] : 0;
        free(r.lines);
        return rc;
    }
    if (detected)
        *detected = fmt;
    if (lines)
        *lines = r.lines;
    else
        free(r.lines);
    return VB_OK;
}

static int too_large(vb_ctx *ctx, const char *path)
{
    return vb_error(ctx, VB_EINPUT_TOOLARGE, path, 0, "vertex file is larger than %zu MiB",
                    VB_VERTEX_MAX_FILE_BYTES >> 20);
}

int vb_vertex_read_file(vb_ctx *ctx, const char *path, vb_vertex_list *out,
                        vb_vertex_format *detected, long **lines)
{
    int is_stdin = strcmp(path, "-") == 0;
    FILE *f = is_stdin ? stdin : fopen(path, "rb");
    if (!f)
        return vb_error(ctx, VB_EIO, path, 0, "cannot open: %s", strerror(errno));
    char *buf = NULL;
    size_t len = 0, cap = 0;
    int rc = VB_OK;
    struct stat st;
    /* A regular file says its size; a pipe is cut one byte past the limit. */
    if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode) &&
        (uint64_t)st.st_size > VB_VERTEX_MAX_FILE_BYTES)
        rc = too_large(ctx, path);
    for (; rc == VB_OK;) {
        if (len > VB_VERTEX_MAX_FILE_BYTES) {
            rc = too_large(ctx, path);
            break;
        }
        if (len == cap) {
            size_t ncap = cap ? 2 * cap : 65536;
            if (ncap > VB_VERTEX_MAX_FILE_BYTES + 1)
                ncap = VB_VERTEX_MAX_FILE_BYTES + 1;
            char *p = realloc(buf, ncap);
            if (!p) {
                rc = vb_error(ctx, VB_ENOMEM, path, 0, "out of memory reading vertices");
                break;
            }
            buf = p;
            cap = ncap;
        }
        size_t got = fread(buf + len, 1, cap - len, f);
        len += got;
        if (got == 0)
            break;
    }
    if (rc == VB_OK && ferror(f))
        rc = vb_error(ctx, VB_EIO, path, 0, "read failed");
    if (!is_stdin)
        fclose(f);
    if (rc == VB_OK)
        rc = vb_vertex_read_buffer(ctx, is_stdin ? "<stdin>" : path, buf, len, out, detected,
                                   lines);
    free(buf);
    return rc;
}
