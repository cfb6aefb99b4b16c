/* The binary vertex file: a NumPy .npz archive (an uncompressed ZIP of .npy
 * arrays, NumPy format version 1.0) that np.load reads without pickle:
 *   ids     uint32 (nids,)   the members of every vertex, sorted per vertex
 *   start   uint64 (n+1,)    vertex k's members are ids[start[k]:start[k+1]]
 *   xyz     float64 (n, 3)   the exact vertex rounded to the nearest double
 *   t       float64 (n,)     the tangent radius (negative where spheres overlap)
 *   status  uint8 (n,)       0 candidate, 1 certified, 2 rejected
 *   comment unicode ()       the header the text formats carry (the certificate)
 * The same doubles as the text formats print with %.17g: bit for bit.
 * Entries over 4 GiB would need ZIP64 and are refused (VB_EMISUSE). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "vb_output.h"
#include "vb_vertex_io.h"

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "vertex_npz.c writes the host's bytes as little-endian NumPy arrays"
#endif

/* One array of the archive: the .npy header and the data, which `fill`
 * produces in chunks (so x, y, z interleave without a copy of the list). */
typedef struct npy_entry {
    const char *name;        /* "xyz.npy" */
    char header[128];        /* magic, version, header length, dict, padding */
    size_t header_len;
    uint64_t data_len;
    const vb_vertex_list *v;
    const void *plain;       /* data as it is in memory, or NULL: fill */
    size_t (*fill)(const struct npy_entry *e, uint64_t from, unsigned char *buf, size_t cap);
    const uint32_t *text;    /* comment as UTF-32 */
    uint32_t crc;
    uint64_t offset;         /* of its local header in the archive */
} npy_entry;

static void npy_header(npy_entry *e, const char *descr, const char *shape)
{
    char dict[96];
    int n = snprintf(dict, sizeof dict, "{'descr': '%s', 'fortran_order': False, 'shape': %s, }", descr,
                     shape);
    /* magic (6) + version (2) + length (2) + dict + spaces + '\n', a
     * multiple of 64 bytes as NumPy writes it. */
    size_t total = (10 + (size_t)n + 1 + 63) / 64 * 64;
    memcpy(e->header, "\x93NUMPY\x01\x00", 8);
    e->header[8] = (char)((total - 10) & 0xff);
    e->header[9] = (char)((total - 10) >> 8);
    memcpy(e->header + 10, dict, (size_t)n);
    memset(e->header + 10 + n, ' ', total - 10 - (size_t)n - 1);
    e->header[total - 1] = '\n';
    e->header_len = total;
}

static size_t fill_xyz(const npy_entry *e, uint64_t from, unsigned char *buf, size_t cap)
{
    const vb_vertex_list *v = e->v;
    size_t k = (size_t)(from / 24), done = 0;
    for (; k < v->n && done + 24 <= cap; k++, done += 24) {
        double p[3] = {v->x[k], v->y[k], v->z[k]};
        memcpy(buf + done, p, 24);
    }
    return done;
}

static size_t fill_start(const npy_entry *e, uint64_t from, unsigned char *buf, size_t cap)
{
    const vb_vertex_list *v = e->v;
    size_t k = (size_t)(from / 8), done = 0;
    for (; k <= v->n && done + 8 <= cap; k++, done += 8) {
        uint64_t s = v->start[k];
        memcpy(buf + done, &s, 8);
    }
    return done;
}

/* Passes the entry's bytes, chunk by chunk, to `sink` (CRC or write). */
static int each_chunk(const npy_entry *e, unsigned char *buf, size_t cap,
                      int (*sink)(void *arg, const unsigned char *p, size_t n), void *arg)
{
    if (sink(arg, (const unsigned char *)e->header, e->header_len))
        return -1;
    if (e->plain)
        return e->data_len ? sink(arg, e->plain, (size_t)e->data_len) : 0;
    for (uint64_t at = 0; at < e->data_len;) {
        size_t got = e->fill(e, at, buf, cap);
        if (got == 0 || sink(arg, buf, got))
            return -1;
        at += got;
    }
    return 0;
}

static int crc_sink(void *arg, const unsigned char *p, size_t n)
{
    uLong *crc = arg;
    while (n) {
        uInt k = n > (1u << 30) ? (1u << 30) : (uInt)n;
        *crc = crc32(*crc, p, k);
        p += k;
        n -= k;
    }
    return 0;
}

static int write_sink(void *arg, const unsigned char *p, size_t n)
{
    return fwrite(p, 1, n, (FILE *)arg) != n;
}

static void put16(FILE *f, unsigned v)
{
    fputc((int)(v & 0xff), f);
    fputc((int)((v >> 8) & 0xff), f);
}

static void put32(FILE *f, uint32_t v)
{
    put16(f, v & 0xffff);
    put16(f, v >> 16);
}

/* A ZIP local header (signature 0x04034b50) or central directory record
 * (0x02014b50) of a stored (method 0) entry; DOS date 1980-01-01 so the
 * archive's bytes depend on the vertices only. */
static void zip_record(FILE *f, const npy_entry *e, int central)
{
    uint32_t size = (uint32_t)(e->header_len + e->data_len);
    put32(f, central ? 0x02014b50u : 0x04034b50u);
    if (central)
        put16(f, 20); /* made by: version 2.0 */
    put16(f, 20);     /* needed to extract: 2.0 */
    put16(f, 0);      /* flags */
    put16(f, 0);      /* stored */
    put16(f, 0);      /* time */
    put16(f, 0x21);   /* date: 1980-01-01 */
    put32(f, e->crc);
    put32(f, size);
    put32(f, size);
    put16(f, (unsigned)strlen(e->name));
    put16(f, 0); /* extra */
    if (central) {
        put16(f, 0);  /* comment */
        put16(f, 0);  /* disk */
        put16(f, 0);  /* internal attributes */
        put32(f, 0);  /* external attributes */
        put32(f, (uint32_t)e->offset);
    }
    fputs(e->name, f);
}

/* The comment as the code points of UTF-8 text (a malformed byte stands for
 * itself). *n gets the count. NULL without memory. */
static uint32_t *utf32(const char *s, size_t *n)
{
    size_t len = strlen(s), k = 0;
    uint32_t *out = malloc((len ? len : 1) * sizeof *out);
    if (!out)
        return NULL;
    for (const unsigned char *p = (const unsigned char *)s; *p;) {
        int extra = *p >= 0xf0 ? 3 : *p >= 0xe0 ? 2 : *p >= 0xc0 ? 1 : 0;
        uint32_t c = extra ? (uint32_t)(*p & (0x3f >> extra)) : *p;
        int ok = 1;
        for (int j = 1; j <= extra; j++)
            ok = ok && (p[j] & 0xc0) == 0x80;
        if (!ok)
            extra = 0, c = *p;
        for (int j = 1; j <= extra; j++)
            c = c << 6 | (p[j] & 0x3f);
        out[k++] = c;
        p += 1 + extra;
    }
    *n = k;
    return out;
}

int vb_vertex_write_npz(vb_ctx *ctx, FILE *f, const vb_vertex_list *v, const char *comment)
{
    size_t nchar = 0;
    uint32_t *text = utf32(comment ? comment : "", &nchar);
    unsigned char *buf = malloc(1 << 16);
    if (!text || !buf) {
        free(text);
        free(buf);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (writing vertices)");
    }
    char shape[4][48], descr_u[24];
    snprintf(shape[0], sizeof shape[0], "(%zu,)", v->nids);
    snprintf(shape[1], sizeof shape[1], "(%zu,)", v->n + 1);
    snprintf(shape[2], sizeof shape[2], "(%zu, 3)", v->n);
    snprintf(shape[3], sizeof shape[3], "(%zu,)", v->n);
    snprintf(descr_u, sizeof descr_u, "<U%zu", nchar ? nchar : 1);
    npy_entry e[6];
    memset(e, 0, sizeof e);
    e[0] = (npy_entry){.name = "ids.npy", .data_len = 4 * (uint64_t)v->nids, .plain = v->ids};
    npy_header(&e[0], "<u4", shape[0]);
    e[1] = (npy_entry){.name = "start.npy", .data_len = 8 * (uint64_t)(v->n + 1), .v = v, .fill = fill_start};
    npy_header(&e[1], "<u8", shape[1]);
    e[2] = (npy_entry){.name = "xyz.npy", .data_len = 24 * (uint64_t)v->n, .v = v, .fill = fill_xyz};
    npy_header(&e[2], "<f8", shape[2]);
    e[3] = (npy_entry){.name = "t.npy", .data_len = 8 * (uint64_t)v->n, .plain = v->t};
    npy_header(&e[3], "<f8", shape[3]);
    e[4] = (npy_entry){.name = "status.npy", .data_len = v->n, .plain = v->status};
    npy_header(&e[4], "|u1", shape[3]);
    /* A 0-d unicode array holds one string of <U{nchar}; an empty comment
     * is one NUL code point (NumPy reads it as ""). */
    uint32_t nul = 0;
    e[5] = (npy_entry){.name = "comment.npy", .data_len = 4 * (uint64_t)(nchar ? nchar : 1),
                       .plain = nchar ? (const void *)text : &nul};
    npy_header(&e[5], descr_u, "()");
    int rc = VB_OK;
    uint64_t at = 0;
    for (int k = 0; k < 6 && rc == VB_OK; k++) {
        uLong crc = crc32(0L, Z_NULL, 0);
        if (e[k].header_len + e[k].data_len >= 0xffffffffu || at >= 0xffffffffu)
            rc = vb_error(ctx, VB_EMISUSE, NULL, 0,
                          "%s would exceed 4 GiB (%zu vertices): write tsv for a list this large",
                          e[k].name, v->n);
        else if (each_chunk(&e[k], buf, 1 << 16, crc_sink, &crc))
            rc = vb_error(ctx, VB_EINTERNAL, NULL, 0, "npz: %s came out short", e[k].name);
        e[k].crc = (uint32_t)crc;
        e[k].offset = at;
        if (rc == VB_OK) {
            zip_record(f, &e[k], 0);
            if (each_chunk(&e[k], buf, 1 << 16, write_sink, f))
                rc = vb_error(ctx, VB_EIO, vb_output_name(f), 0, "writing vertices failed");
        }
        at += 30 + strlen(e[k].name) + e[k].header_len + e[k].data_len;
    }
    if (rc == VB_OK) {
        uint64_t dir = at, dir_len = 0;
        for (int k = 0; k < 6; k++) {
            zip_record(f, &e[k], 1);
            dir_len += 46 + strlen(e[k].name);
        }
        put32(f, 0x06054b50u); /* end of central directory */
        put16(f, 0);
        put16(f, 0);
        put16(f, 6);
        put16(f, 6);
        put32(f, (uint32_t)dir_len);
        put32(f, (uint32_t)dir);
        put16(f, 0);
    }
    free(text);
    free(buf);
    return rc;
}
