/* DCD reader and writer. A DCD is a sequence of Fortran unformatted records:
 * each payload is framed by its length as a 4-byte integer before and after.
 * Header: "CORD" + 20 control integers (ICNTRL), a title record, the atom
 * count, and with fixed atoms the list of free atoms. Frames: an optional
 * unit cell (6 doubles, CHARMM with ICNTRL[10]), then X, Y, Z as float32 -
 * after the first frame only the free atoms when some are fixed - and a 4th
 * coordinate record when ICNTRL[11] is set. */
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "vb_dcd.h"
#include "vb_diag.h"
#include "vbi_input.h"

struct vb_dcd {
    FILE *f;
    char *path;
    int swap;           /* file byte order differs from ours */
    int charmm;         /* ICNTRL[19] != 0 */
    int has_cell, has_4d;
    size_t natoms, nfree;
    long nset;
    double delta;
    int32_t *free_idx;  /* 0-based indices of the free atoms (nfree of them) */
    float *buf;         /* natoms floats, allocated with the first frame */
    double *fixed[3];   /* first-frame coordinates when atoms are fixed */
    long frame;         /* frames read so far */
    long long size;     /* file size in bytes, -1 when it cannot be told */
};

/* Bytes between the read position and the end of the file (LLONG_MAX when
 * the size is unknown): no record longer than this is allocated or read, so
 * a header that claims 2^31 atoms costs nothing. */
static long long bytes_left(vb_dcd *d)
{
    long pos = ftell(d->f);
    if (d->size < 0 || pos < 0)
        return LLONG_MAX;
    return pos <= d->size ? d->size - pos : 0;
}

static uint32_t bswap32(uint32_t v)
{
    return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

static int32_t fix32(const vb_dcd *d, int32_t v)
{
    return d->swap ? (int32_t)bswap32((uint32_t)v) : v;
}

static void fix_floats(const vb_dcd *d, float *p, size_t n)
{
    if (!d->swap)
        return;
    for (size_t i = 0; i < n; i++) {
        uint32_t u;
        memcpy(&u, &p[i], 4);
        u = bswap32(u);
        memcpy(&p[i], &u, 4);
    }
}

/* Reads one record of exactly `len` bytes into buf (NULL = skip). Returns
 * 1 on success, 0 at a clean end of file before the record, -1 when the file
 * ends inside it, -2 when the markers disagree with `len`. */
static int read_record(vb_dcd *d, void *buf, size_t len)
{
    int32_t m0, m1;
    size_t got = fread(&m0, 1, 4, d->f);
    if (got == 0 && feof(d->f))
        return 0;
    if (got != 4)
        return -1;
    if ((size_t)(uint32_t)fix32(d, m0) != len)
        return -2;
    if ((unsigned long long)len + 4 > (unsigned long long)bytes_left(d))
        return -1;
    if (buf) {
        if (fread(buf, 1, len, d->f) != len)
            return -1;
    } else if (fseek(d->f, (long)len, SEEK_CUR) != 0) {
        return -1;
    }
    if (fread(&m1, 4, 1, d->f) != 1)
        return -1;
    return fix32(d, m1) == fix32(d, m0) ? 1 : -2;
}

/* Reads a record of unknown length (the title) and skips it. */
static int skip_record(vb_dcd *d)
{
    int32_t m0, m1;
    if (fread(&m0, 4, 1, d->f) != 1)
        return -1;
    long len = (long)(uint32_t)fix32(d, m0);
    if (len < 0 || fseek(d->f, len, SEEK_CUR) != 0 || fread(&m1, 4, 1, d->f) != 1)
        return -1;
    return m1 == m0 ? 1 : -2;
}

void vb_dcd_close(vb_dcd *d)
{
    if (!d)
        return;
    if (d->f)
        fclose(d->f);
    free(d->path);
    free(d->free_idx);
    free(d->buf);
    for (int a = 0; a < 3; a++)
        free(d->fixed[a]);
    free(d);
}

static int bad_header(vb_ctx *ctx, vb_dcd *d, const char *what)
{
    int rc = vb_error(ctx, VB_EINPUT_MALFORMED, d->path, 0, "DCD header: %s", what);
    vb_dcd_close(d);
    return rc;
}

int vb_dcd_open(vb_ctx *ctx, const char *path, vb_dcd **out)
{
    *out = NULL;
    vb_dcd *d = calloc(1, sizeof *d);
    if (!d)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "DCD reader");
    d->path = malloc(strlen(path) + 1);
    if (!d->path) {
        vb_dcd_close(d);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "DCD reader");
    }
    strcpy(d->path, path);
    d->f = vbi_open_input(ctx, path, NULL);
    if (!d->f) {
        vb_dcd_close(d);
        return vb_errcode(ctx);
    }
    unsigned char hdr[92];
    d->size = -1;
    if (fseek(d->f, 0, SEEK_END) == 0) {
        long end = ftell(d->f);
        d->size = end >= 0 ? end : -1;
    }
    if (fseek(d->f, 0, SEEK_SET) != 0)
        d->size = -1;
    if (fread(hdr, 1, sizeof hdr, d->f) != sizeof hdr || memcmp(hdr + 4, "CORD", 4) != 0) {
        int rc = vb_error(ctx, VB_EINPUT_FORMAT, path, 0, "not a DCD file (no CORD header)");
        vb_dcd_close(d);
        return rc;
    }
    int32_t m0, m1;
    memcpy(&m0, hdr, 4);
    memcpy(&m1, hdr + 88, 4);
    if (m0 == 84)
        d->swap = 0;
    else if (bswap32((uint32_t)m0) == 84)
        d->swap = 1;
    else
        return bad_header(ctx, d, "first record is not 84 bytes (8-byte markers are not supported)");
    if (m1 != m0)
        return bad_header(ctx, d, "first record markers disagree");
    int32_t ic[20];
    memcpy(ic, hdr + 8, sizeof ic);
    for (int i = 0; i < 20; i++)
        ic[i] = fix32(d, ic[i]);
    d->nset = ic[0];
    d->charmm = ic[19] != 0;
    if (d->charmm) {
        float delta;
        uint32_t u = (uint32_t)ic[9];
        memcpy(&delta, &u, 4);
        d->delta = delta;
        d->has_cell = ic[10] != 0;
        d->has_4d = ic[11] != 0;
    } else {
        double delta;
        memcpy(&delta, hdr + 8 + 9 * 4, 8);
        if (d->swap) {
            uint32_t w[2];
            memcpy(w, &delta, 8);
            uint32_t t = bswap32(w[0]);
            w[0] = bswap32(w[1]);
            w[1] = t;
            memcpy(&delta, w, 8);
        }
        d->delta = delta;
    }
    if (skip_record(d) != 1)
        return bad_header(ctx, d, "title record");
    int32_t na;
    if (read_record(d, &na, 4) != 1)
        return bad_header(ctx, d, "atom count record");
    na = fix32(d, na);
    int32_t nfixed = ic[8];
    if (na <= 0 || nfixed < 0 || nfixed >= na)
        return bad_header(ctx, d, "atom counts out of range");
    d->natoms = (size_t)na;
    d->nfree = (size_t)(na - nfixed);
    if (nfixed > 0) {
        if (4ull * d->nfree + 8 > (unsigned long long)bytes_left(d))
            return bad_header(ctx, d, "free atom list runs past the end of the file");
        d->free_idx = malloc(d->nfree * sizeof *d->free_idx);
        if (!d->free_idx) {
            vb_dcd_close(d);
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "DCD fixed-atom tables");
        }
        if (read_record(d, d->free_idx, d->nfree * 4) != 1)
            return bad_header(ctx, d, "free atom list");
        for (size_t i = 0; i < d->nfree; i++) {
            int32_t v = fix32(d, d->free_idx[i]);
            if (v < 1 || v > na)
                return bad_header(ctx, d, "free atom index out of range");
            d->free_idx[i] = v - 1;
        }
    }
    *out = d;
    return VB_OK;
}

size_t vb_dcd_atoms(const vb_dcd *d) { return d->natoms; }
long vb_dcd_header_frames(const vb_dcd *d) { return d->nset; }
double vb_dcd_delta(const vb_dcd *d) { return d->delta; }

/* Bytes of the next frame: optional cell, X, Y, Z, optional 4th record. */
static unsigned long long frame_bytes(const vb_dcd *d, size_t n)
{
    unsigned long long rec = 4ull * n + 8;
    return (d->has_cell ? 6 * 8 + 8 : 0) + 3 * rec + (d->has_4d ? rec : 0);
}

/* The frame buffers, allocated when the file holds a whole first frame. */
static int frame_buffers(vb_ctx *ctx, vb_dcd *d)
{
    if (d->buf)
        return VB_OK;
    d->buf = malloc(d->natoms * sizeof *d->buf);
    for (int a = 0; d->free_idx && a < 3; a++)
        d->fixed[a] = malloc(d->natoms * sizeof(double));
    if (!d->buf || (d->free_idx && (!d->fixed[0] || !d->fixed[1] || !d->fixed[2])))
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "DCD frame of %zu atoms", d->natoms);
    return VB_OK;
}

int vb_dcd_next(vb_ctx *ctx, vb_dcd *d, double *x, double *y, double *z, double cell[6], int *got)
{
    *got = 0;
    int partial = d->free_idx && d->frame > 0;
    size_t n = partial ? d->nfree : d->natoms;
    int r;
    /* What is left must be a whole frame: fewer bytes are a truncated last
     * frame or stray bytes after the last one, and are reported. */
    long long left = bytes_left(d);
    if (left == 0)
        return VB_OK;
    if ((unsigned long long)left < frame_bytes(d, n)) {
        vb_warn(ctx, VB_W_DCD_PARTIAL_FRAME, d->path, 0,
                "DCD ends with %lld byte%s after frame %ld, less than a frame of %zu atoms: "
                "ignored", left, left == 1 ? "" : "s", d->frame, n);
        fseek(d->f, 0, SEEK_END);
        return VB_OK;
    }
    int rc = frame_buffers(ctx, d);
    if (rc != VB_OK)
        return rc;
    if (d->has_cell) {
        double c[6];
        r = read_record(d, c, sizeof c);
        if (r == 0)
            return VB_OK;
        if (r == 1 && cell) {
            for (int i = 0; i < 6; i++) {
                if (d->swap) {
                    uint32_t w[2];
                    memcpy(w, &c[i], 8);
                    uint32_t t = bswap32(w[0]);
                    w[0] = bswap32(w[1]);
                    w[1] = t;
                    memcpy(&c[i], w, 8);
                }
                cell[i] = c[i];
            }
        }
        if (r < 0)
            goto bad;
    }
    double *dst[3] = {x, y, z};
    for (int a = 0; a < 3; a++) {
        r = read_record(d, d->buf, n * sizeof(float));
        if (r == 0 && a == 0 && !d->has_cell)
            return VB_OK;
        if (r != 1)
            goto bad;
        fix_floats(d, d->buf, n);
        if (partial) {
            memcpy(dst[a], d->fixed[a], d->natoms * sizeof(double));
            for (size_t i = 0; i < n; i++)
                dst[a][d->free_idx[i]] = d->buf[i];
        } else {
            for (size_t i = 0; i < n; i++)
                dst[a][i] = d->buf[i];
            if (d->free_idx)
                memcpy(d->fixed[a], dst[a], d->natoms * sizeof(double));
        }
    }
    if (d->has_4d && (r = read_record(d, NULL, n * sizeof(float))) != 1)
        goto bad;
    d->frame++;
    *got = 1;
    return VB_OK;
bad:
    if (r == -1 || r == 0) {
        vb_warn(ctx, VB_W_DCD_PARTIAL_FRAME, d->path, 0, "DCD ends inside frame %ld; the partial frame is ignored",
                d->frame + 1);
        return VB_OK;
    }
    return vb_error(ctx, VB_EINPUT_MALFORMED, d->path, 0,
                    "DCD frame %ld: record length does not match %zu atoms", d->frame + 1, n);
}

struct vb_dcd_writer {
    FILE *f;
    char *path;
    size_t natoms;
    int32_t frames;
    float *buf;
};

static int put_record(FILE *f, const void *p, size_t len)
{
    int32_t m = (int32_t)len;
    return fwrite(&m, 4, 1, f) == 1 && (len == 0 || fwrite(p, 1, len, f) == len) &&
           fwrite(&m, 4, 1, f) == 1;
}

int vb_dcd_writer_open(vb_ctx *ctx, const char *path, size_t natoms, double delta,
                       const char *title, vb_dcd_writer **out)
{
    *out = NULL;
    if (natoms == 0 || natoms > 0x7fffffff)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "DCD writer: %zu atoms", natoms);
    vb_dcd_writer *w = calloc(1, sizeof *w);
    if (!w || !(w->buf = malloc(natoms * sizeof *w->buf)) || !(w->path = malloc(strlen(path) + 1))) {
        if (w)
            free(w->buf);
        free(w);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "DCD writer");
    }
    strcpy(w->path, path);
    w->natoms = natoms;
    w->f = fopen(path, "wb");
    if (!w->f) {
        free(w->buf);
        free(w->path);
        free(w);
        return vb_error(ctx, VB_EIO, path, 0, "cannot create DCD file");
    }
    unsigned char hdr[84];
    memset(hdr, 0, sizeof hdr);
    memcpy(hdr, "CORD", 4);
    int32_t ic[20] = {0};
    ic[1] = 1; /* ISTART */
    ic[2] = 1; /* NSAVC */
    float fd = (float)delta;
    memcpy(&ic[9], &fd, 4);
    ic[19] = 24; /* CHARMM version: marks the CHARMM layout */
    memcpy(hdr + 4, ic, sizeof ic);
    char titles[4 + 80];
    int32_t nt = 1;
    memcpy(titles, &nt, 4);
    memset(titles + 4, ' ', 80);
    size_t tl = strlen(title ? title : "");
    memcpy(titles + 4, title ? title : "", tl > 80 ? 80 : tl);
    int32_t na = (int32_t)natoms;
    if (!put_record(w->f, hdr, sizeof hdr) || !put_record(w->f, titles, sizeof titles) ||
        !put_record(w->f, &na, 4)) {
        int rc = vb_error(ctx, VB_EIO, path, 0, "cannot write DCD header");
        fclose(w->f);
        free(w->buf);
        free(w->path);
        free(w);
        return rc;
    }
    *out = w;
    return VB_OK;
}

int vb_dcd_writer_frame(vb_ctx *ctx, vb_dcd_writer *w, const double *x, const double *y,
                        const double *z)
{
    const double *src[3] = {x, y, z};
    for (int a = 0; a < 3; a++) {
        for (size_t i = 0; i < w->natoms; i++)
            w->buf[i] = (float)src[a][i];
        if (!put_record(w->f, w->buf, w->natoms * sizeof(float)))
            return vb_error(ctx, VB_EIO, w->path, 0, "cannot write DCD frame");
    }
    w->frames++;
    return VB_OK;
}

int vb_dcd_writer_close(vb_ctx *ctx, vb_dcd_writer *w)
{
    if (!w)
        return VB_OK;
    int ok = fseek(w->f, 8, SEEK_SET) == 0 && fwrite(&w->frames, 4, 1, w->f) == 1;
    ok = (fclose(w->f) == 0) && ok;
    int rc = ok ? VB_OK : vb_error(ctx, VB_EIO, w->path, 0, "cannot finish DCD file");
    free(w->buf);
    free(w->path);
    free(w);
    return rc;
}
