/* Opening an input file or stdin as the bytes it holds: gzip (.gz, as the
 * PDB distributes its files) and bzip2 streams are recognised by their
 * magic numbers, whatever the name, and decompressed on the fly; anything
 * else is read as it is. A directory is refused by name.
 *
 * Decompressed and stdin streams are glibc cookie streams (fopencookie), so
 * every reader keeps its FILE calls: fread, getline, and forward fseek
 * (DCD records are skipped that way); a backward seek fails. */
#define _GNU_SOURCE 1
#include "vbi_input.h"
#include "vb_diag.h"

#include <bzlib.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <zlib.h>

/* Bytes read from the compressed file at a time. */
#define VBI_INFLATE_CHUNK ((size_t)1 << 16)

typedef struct {
    vb_ctx *ctx;
    char *path;
    FILE *raw;              /* the file as stored */
    int own_raw;            /* 0 for stdin */
    int kind;               /* VBI_PLAIN, VBI_GZIP, VBI_BZIP2 */
    unsigned char head[4];  /* bytes read to see the magic, served again */
    size_t head_len, head_pos;
    unsigned char *in;      /* compressed bytes not yet inflated */
    size_t in_len, in_pos;
    int raw_eof;
    int ended;              /* the last compressed stream ended cleanly */
    int failed;
    z_stream z;
    bz_stream bz;
    int z_open, bz_open;
    int64_t pos;            /* bytes delivered so far */
} vbi_cookie;

int vbi_compression_of(const unsigned char *p, size_t n)
{
    if (n >= 2 && p[0] == 0x1f && p[1] == 0x8b)
        return VBI_GZIP;
    if (n >= 4 && p[0] == 'B' && p[1] == 'Z' && p[2] == 'h' && p[3] >= '1' && p[3] <= '9')
        return VBI_BZIP2;
    return VBI_PLAIN;
}

const char *vbi_compression_name(int kind)
{
    return kind == VBI_GZIP ? "gzip" : kind == VBI_BZIP2 ? "bzip2" : "plain";
}

/* The next raw byte run: the magic bytes first, then the file. */
static size_t raw_read(vbi_cookie *c, unsigned char *dst, size_t n)
{
    size_t got = 0;
    if (c->head_pos < c->head_len) {
        size_t k = c->head_len - c->head_pos;
        if (k > n)
            k = n;
        memcpy(dst, c->head + c->head_pos, k);
        c->head_pos += k;
        got = k;
    }
    if (got < n && !c->raw_eof) {
        size_t k = fread(dst + got, 1, n - got, c->raw);
        if (k < n - got)
            c->raw_eof = 1;
        got += k;
    }
    return got;
}

static int refill(vbi_cookie *c)
{
    if (c->in_pos < c->in_len)
        return 1;
    c->in_len = raw_read(c, c->in, VBI_INFLATE_CHUNK);
    c->in_pos = 0;
    if (c->in_len == 0 && ferror(c->raw)) {
        c->failed = 1;
        vb_error(c->ctx, VB_EIO, c->path, 0, "read error: %s", strerror(errno));
        return -1;
    }
    return c->in_len > 0;
}

static ssize_t fail_damaged(vbi_cookie *c, const char *what)
{
    c->failed = 1;
    vb_error(c->ctx, VB_EINPUT_COMPRESSED, c->path, 0, "%s data %s after %lld decompressed bytes",
             vbi_compression_name(c->kind), what, (long long)c->pos);
    errno = EBADMSG;
    return -1;
}

/* After a stream's end: another stream may follow (gzip members, pbzip2
 * blocks); anything else is reported once and ignored, as gzip does. */
static int next_stream(vbi_cookie *c)
{
    int more = refill(c);
    if (more <= 0)
        return more;
    const unsigned char *p = c->in + c->in_pos;
    size_t left = c->in_len - c->in_pos;
    unsigned char probe[4] = {0, 0, 0, 0};
    memcpy(probe, p, left < 4 ? left : 4);
    if (vbi_compression_of(probe, left < 4 ? left : 4) != c->kind) {
        vb_warn(c->ctx, VB_W_COMPRESSED_TRAILING, c->path, 0,
                "bytes after the end of the %s data ignored", vbi_compression_name(c->kind));
        c->in_pos = c->in_len;
        c->raw_eof = 1;
        return 0;
    }
    if (c->kind == VBI_GZIP)
        return inflateReset(&c->z) == Z_OK ? 1 : -1;
    BZ2_bzDecompressEnd(&c->bz);
    c->bz_open = 0;
    memset(&c->bz, 0, sizeof c->bz);
    if (BZ2_bzDecompressInit(&c->bz, 0, 0) != BZ_OK)
        return -1;
    c->bz_open = 1;
    return 1;
}

static ssize_t inflate_read(vbi_cookie *c, char *buf, size_t size)
{
    size_t out = 0;
    while (out < size) {
        if (c->ended) {
            int more = next_stream(c);
            if (more < 0)
                return c->failed ? -1 : fail_damaged(c, "cannot be restarted");
            if (more == 0)
                break;
            c->ended = 0;
        }
        int have = refill(c);
        if (have < 0)
            return -1;
        if (have == 0)
            return fail_damaged(c, "ends before its end marker (truncated file?)");
        if (c->kind == VBI_GZIP) {
            c->z.next_in = c->in + c->in_pos;
            c->z.avail_in = (uInt)(c->in_len - c->in_pos);
            c->z.next_out = (Bytef *)buf + out;
            c->z.avail_out = (uInt)(size - out);
            int r = inflate(&c->z, Z_NO_FLUSH);
            c->in_pos = c->in_len - c->z.avail_in;
            out = size - c->z.avail_out;
            if (r == Z_STREAM_END)
                c->ended = 1;
            else if (r != Z_OK && r != Z_BUF_ERROR)
                return fail_damaged(c, r == Z_DATA_ERROR ? "is damaged" : "cannot be read");
        } else {
            c->bz.next_in = (char *)c->in + c->in_pos;
            c->bz.avail_in = (unsigned)(c->in_len - c->in_pos);
            c->bz.next_out = buf + out;
            c->bz.avail_out = (unsigned)(size - out);
            int r = BZ2_bzDecompress(&c->bz);
            c->in_pos = c->in_len - c->bz.avail_in;
            out = size - c->bz.avail_out;
            if (r == BZ_STREAM_END)
                c->ended = 1;
            else if (r != BZ_OK)
                return fail_damaged(c, r == BZ_DATA_ERROR || r == BZ_DATA_ERROR_MAGIC
                                           ? "is damaged"
                                           : "cannot be read");
        }
    }
    return (ssize_t)out;
}

static ssize_t cookie_read(void *cookie, char *buf, size_t size)
{
    vbi_cookie *c = cookie;
    if (c->failed) {
        errno = EBADMSG;
        return -1;
    }
    ssize_t got;
    if (c->kind == VBI_PLAIN) {
        got = (ssize_t)raw_read(c, (unsigned char *)buf, size);
        if (got == 0 && ferror(c->raw))
            return -1;
    } else {
        got = inflate_read(c, buf, size);
    }
    if (got > 0)
        c->pos += got;
    return got;
}

/* Forward seeks read and drop bytes; a backward one fails (EINVAL). */
static int cookie_seek(void *cookie, off64_t *offset, int whence)
{
    vbi_cookie *c = cookie;
    int64_t target;
    if (whence == SEEK_SET)
        target = *offset;
    else if (whence == SEEK_CUR)
        target = c->pos + *offset;
    else {
        errno = EINVAL;
        return -1;
    }
    if (target < c->pos) {
        errno = EINVAL;
        return -1;
    }
    char scratch[4096];
    while (c->pos < target) {
        int64_t want = target - c->pos;
        ssize_t got = cookie_read(c, scratch, want < (int64_t)sizeof scratch ? (size_t)want
                                                                             : sizeof scratch);
        if (got <= 0)
            break;
    }
    *offset = c->pos;
    return 0;
}

static void cookie_free(vbi_cookie *c)
{
    if (c->z_open)
        inflateEnd(&c->z);
    if (c->bz_open)
        BZ2_bzDecompressEnd(&c->bz);
    if (c->raw && c->own_raw)
        fclose(c->raw);
    free(c->in);
    free(c->path);
    free(c);
}

static int cookie_close(void *cookie)
{
    cookie_free(cookie);
    return 0;
}

int vbi_input_read_error(vb_ctx *ctx, const char *path)
{
    if (errno == EBADMSG && vb_errcode(ctx) == VB_EINPUT_COMPRESSED)
        return VB_EINPUT_COMPRESSED;
    return vb_error(ctx, VB_EIO, path, 0, "read error: %s", strerror(errno));
}

FILE *vbi_open_input(vb_ctx *ctx, const char *path, int *kind)
{
    int is_stdin = strcmp(path, "-") == 0;
    if (kind)
        *kind = VBI_PLAIN;
    struct stat st;
    if (!is_stdin && stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
        vb_error(ctx, VB_EIO, path, 0, "is a directory, not a file");
        return NULL;
    }
    FILE *raw = is_stdin ? stdin : fopen(path, "rb");
    if (!raw) {
        vb_error(ctx, VB_EIO, path, 0, "cannot open: %s", strerror(errno));
        return NULL;
    }
    if (is_stdin && fstat(fileno(raw), &st) == 0 && S_ISDIR(st.st_mode)) {
        vb_error(ctx, VB_EIO, path, 0, "standard input is a directory");
        return NULL;
    }
    vbi_cookie *c = calloc(1, sizeof *c);
    if (!c || !(c->path = strdup(path))) {
        free(c);
        if (!is_stdin)
            fclose(raw);
        vb_error(ctx, VB_ENOMEM, path, 0, "out of memory");
        return NULL;
    }
    c->ctx = ctx;
    c->raw = raw;
    c->own_raw = !is_stdin;
    c->head_len = fread(c->head, 1, sizeof c->head, raw);
    if (c->head_len < sizeof c->head && ferror(raw)) {
        vb_error(ctx, VB_EIO, path, 0, "read error: %s", strerror(errno));
        cookie_free(c);
        return NULL;
    }
    c->kind = vbi_compression_of(c->head, c->head_len);
    if (kind)
        *kind = c->kind;
    /* A plain file keeps its own stream (and with it seeking and size). */
    if (c->kind == VBI_PLAIN && !is_stdin && fseek(raw, 0, SEEK_SET) == 0) {
        c->raw = NULL;
        cookie_free(c);
        return raw;
    }
    int ok = 1;
    if (c->kind != VBI_PLAIN)
        ok = (c->in = malloc(VBI_INFLATE_CHUNK)) != NULL;
    if (ok && c->kind == VBI_GZIP)
        ok = c->z_open = inflateInit2(&c->z, 15 + 16) == Z_OK;
    if (ok && c->kind == VBI_BZIP2)
        ok = c->bz_open = BZ2_bzDecompressInit(&c->bz, 0, 0) == BZ_OK;
    cookie_io_functions_t io = {cookie_read, NULL, cookie_seek, cookie_close};
    FILE *f = ok ? fopencookie(c, "rb", io) : NULL;
    if (!f) {
        vb_error(ctx, VB_ENOMEM, path, 0, "out of memory (%s reader)",
                 vbi_compression_name(c->kind));
        cookie_free(c);
        return NULL;
    }
    return f;
}
