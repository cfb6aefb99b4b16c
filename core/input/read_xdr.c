/* XTC and TRR frames (vb_xdr.h): headers, raw and packed coordinates. */
#include "vb_xdr.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_diag.h"
#include "vbi_input.h"

/* An XTC frame's packed data larger than this is not a frame of the atom
 * count it claims (the packing never takes more than 4 bytes per
 * coordinate, plus slack). */
#define XTC_BYTES_PER_ATOM 16

/* A TRR frame header: the byte sizes of its parts. */
typedef struct {
    int32_t ir, e, box, vir, pres, top, sym, x, v, f, natoms, step, nre;
    int dbl;
    double time, lambda;
} trr_header;

struct vb_xdr_traj {
    FILE *f;
    char *name;
    int kind;             /* VBI_TRAJ_XTC or VBI_TRAJ_TRR */
    size_t natoms;
    long frame;           /* frames read so far */
    long long offset;     /* bytes consumed so far */
    int pending;          /* open read the first frame's header up to its atom count */
    trr_header trr;       /* TRR: that header */
    uint32_t first_magic; /* XTC: the first frame's magic (1995 or 2023) */
    unsigned char *packed; /* XTC packed bytes of one frame */
    size_t packed_cap;
    int32_t *ints;        /* XTC integers of one frame */
    void *raw;            /* TRR/XTC raw arrays of one frame */
    size_t raw_cap;
    long skipped;         /* TRR frames without coordinates */
};

static uint32_t be32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static uint64_t be64(const unsigned char *p)
{
    return (uint64_t)be32(p) << 32 | be32(p + 4);
}

static float be_float(const unsigned char *p)
{
    uint32_t u = be32(p);
    float f;
    memcpy(&f, &u, 4);
    return f;
}

static double be_double(const unsigned char *p)
{
    uint64_t u = be64(p);
    double d;
    memcpy(&d, &u, 8);
    return d;
}

/* Reads exactly n bytes; 1 on success, 0 at a clean end before any byte,
 * -1 when the file ends inside them. */
static int get(vb_xdr_traj *t, void *buf, size_t n)
{
    size_t got = fread(buf, 1, n, t->f);
    t->offset += (long long)got;
    if (got == n)
        return 1;
    return got == 0 && !ferror(t->f) ? 0 : -1;
}

static int damaged(vb_ctx *ctx, vb_xdr_traj *t, const char *what)
{
    if (ferror(t->f))
        return vbi_input_read_error(ctx, t->name);
    return vb_error(ctx, VB_EINPUT_TRAJECTORY, t->name, 0, "%s frame %ld (byte %lld): %s",
                    vbi_trajectory_name(t->kind), t->frame + 1, t->offset, what);
}

static int get_u32(vb_xdr_traj *t, uint32_t *v)
{
    unsigned char b[4];
    int r = get(t, b, 4);
    if (r == 1)
        *v = be32(b);
    return r;
}

/* Room for n bytes in *buf (capacity *cap). */
static int reserve(void **buf, size_t *cap, size_t n)
{
    if (n <= *cap)
        return 0;
    void *p = realloc(*buf, n);
    if (!p)
        return -1;
    *buf = p;
    *cap = n;
    return 0;
}

void vb_xdr_close(vb_xdr_traj *t)
{
    if (!t)
        return;
    if (t->f)
        fclose(t->f);
    free(t->name);
    free(t->packed);
    free(t->ints);
    free(t->raw);
    free(t);
}

size_t vb_xdr_atoms(const vb_xdr_traj *t) { return t->natoms; }
int vb_xdr_kind(const vb_xdr_traj *t) { return t->kind; }

/* The rest of a TRR header after its magic (and, when slen_read is not
 * NULL, after the version string's first length): version string, sizes,
 * atom count, step, time, lambda. 1, or -1 on a damaged header (message
 * set). */
static int trr_header_rest(vb_ctx *ctx, vb_xdr_traj *t, trr_header *h, const uint32_t *slen_read)
{
    unsigned char b[13 * 4 + 8];
    uint32_t slen, len;
    if (slen_read)
        slen = *slen_read;
    else if (get_u32(t, &slen) != 1)
        return damaged(ctx, t, "header cut short"), -1;
    if (get_u32(t, &len) != 1)
        return damaged(ctx, t, "header cut short"), -1;
    if (slen != 13 || len != 12)
        return damaged(ctx, t, "no 'GMX_trn_file' version string"), -1;
    if (get(t, b, 12) != 1 || memcmp(b, "GMX_trn_file", 12) != 0)
        return damaged(ctx, t, "no 'GMX_trn_file' version string"), -1;
    if (get(t, b, 13 * 4) != 1)
        return damaged(ctx, t, "header cut short"), -1;
    int32_t v[13];
    for (int k = 0; k < 13; k++)
        v[k] = (int32_t)be32(b + 4 * k);
    h->ir = v[0], h->e = v[1], h->box = v[2], h->vir = v[3], h->pres = v[4], h->top = v[5];
    h->sym = v[6], h->x = v[7], h->v = v[8], h->f = v[9], h->natoms = v[10], h->step = v[11];
    h->nre = v[12];
    if (h->natoms <= 0)
        return damaged(ctx, t, "atom count out of range"), -1;
    for (int k = 0; k < 10; k++)
        if (v[k] < 0)
            return damaged(ctx, t, "negative block size"), -1;
    if (h->ir || h->e || h->top || h->sym)
        return damaged(ctx, t, "input record, energies or topology in the frame (not read)"), -1;
    /* The real size: from the box, else from x, v or f. */
    int64_t n3 = 3 * (int64_t)h->natoms;
    int64_t real = h->box ? h->box / 9
                   : h->x ? h->x / n3
                   : h->v ? h->v / n3
                   : h->f ? h->f / n3
                          : 4;
    if (real != 4 && real != 8)
        return damaged(ctx, t, "block sizes are neither float nor double"), -1;
    h->dbl = real == 8;
    if ((h->box && h->box != 9 * real) || (h->vir && h->vir != 9 * real) ||
        (h->pres && h->pres != 9 * real) || (h->x && h->x != n3 * real) ||
        (h->v && h->v != n3 * real) || (h->f && h->f != n3 * real))
        return damaged(ctx, t, "block sizes disagree with the atom count"), -1;
    if (get(t, b, 2 * (size_t)real) != 1)
        return damaged(ctx, t, "header cut short"), -1;
    h->time = h->dbl ? be_double(b) : be_float(b);
    h->lambda = h->dbl ? be_double(b + 8) : be_float(b + 4);
    return 1;
}

int vb_xdr_open_stream(vb_ctx *ctx, const char *name, FILE *f, vb_xdr_traj **out)
{
    *out = NULL;
    vb_xdr_traj *t = calloc(1, sizeof *t);
    if (!t || !(t->name = strdup(name))) {
        free(t);
        fclose(f);
        return vb_error(ctx, VB_ENOMEM, name, 0, "out of memory");
    }
    t->f = f;
    unsigned char head[8];
    int r = get(t, head, sizeof head);
    t->kind = r == 1 ? vbi_trajectory_kind(head, sizeof head) : VBI_TRAJ_NONE;
    int rc = VB_OK;
    if (t->kind == VBI_TRAJ_XTC) {
        uint32_t n = be32(head + 4);
        if (n == 0 || n > 0x7fffffffu)
            rc = damaged(ctx, t, "atom count out of range");
        t->natoms = n;
        t->first_magic = be32(head);
    } else if (t->kind == VBI_TRAJ_TRR) {
        /* The magic and the version string's first length were read. */
        uint32_t slen = be32(head + 4);
        if (trr_header_rest(ctx, t, &t->trr, &slen) != 1)
            rc = vb_errcode(ctx);
        else
            t->natoms = (size_t)t->trr.natoms;
    } else {
        rc = r < 0 && ferror(f) ? vbi_input_read_error(ctx, name)
                                : vb_error(ctx, VB_EINPUT_FORMAT, name, 0,
                                           "not an XTC or TRR trajectory (magic number)");
    }
    if (rc != VB_OK) {
        vb_xdr_close(t);
        return rc;
    }
    t->pending = 1;
    *out = t;
    return VB_OK;
}

int vb_xdr_open(vb_ctx *ctx, const char *path, vb_xdr_traj **out)
{
    *out = NULL;
    FILE *f = vbi_open_input(ctx, path, NULL);
    if (!f)
        return vb_errcode(ctx);
    return vb_xdr_open_stream(ctx, path, f, out);
}

/* n reals of `size` bytes (4 or 8) into dst as doubles (dst NULL: skip). */
static int get_reals(vb_ctx *ctx, vb_xdr_traj *t, size_t n, int size, double *dst,
                     const char *what)
{
    size_t bytes = n * (size_t)size;
    if (reserve(&t->raw, &t->raw_cap, bytes) != 0)
        return vb_error(ctx, VB_ENOMEM, t->name, 0, "out of memory for a frame of %zu atoms",
                        t->natoms);
    if (get(t, t->raw, bytes) != 1)
        return damaged(ctx, t, what);
    const unsigned char *p = t->raw;
    for (size_t i = 0; dst && i < n; i++)
        dst[i] = size == 8 ? be_double(p + 8 * i) : be_float(p + 4 * i);
    return VB_OK;
}

static int next_trr(vb_ctx *ctx, vb_xdr_traj *t, double *xyz, vb_xdr_frame *fr, int *got)
{
    for (;;) {
        trr_header h;
        if (t->pending) {
            h = t->trr;
            t->pending = 0;
        } else {
            uint32_t magic;
            int r = get_u32(t, &magic);
            if (r == 0)
                return VB_OK;
            if (r < 0 || magic != 1993)
                return damaged(ctx, t, r < 0 ? "a few stray bytes at the end" : "no TRR magic number");
            if (trr_header_rest(ctx, t, &h, NULL) != 1)
                return vb_errcode(ctx);
        }
        if ((size_t)h.natoms != t->natoms)
            return vb_error(ctx, VB_EINPUT_TOPOLOGY, t->name, 0,
                            "TRR frame %ld has %d atoms, the first %zu", t->frame + 1, h.natoms,
                            t->natoms);
        int real = h.dbl ? 8 : 4;
        double box[9] = {0};
        int rc = VB_OK;
        if (h.box)
            rc = get_reals(ctx, t, 9, real, box, "box cut short");
        if (rc == VB_OK && h.vir)
            rc = get_reals(ctx, t, 9, real, NULL, "virial cut short");
        if (rc == VB_OK && h.pres)
            rc = get_reals(ctx, t, 9, real, NULL, "pressure cut short");
        if (rc == VB_OK && h.x)
            rc = get_reals(ctx, t, 3 * t->natoms, real, xyz, "coordinates cut short");
        if (rc == VB_OK && h.v)
            rc = get_reals(ctx, t, 3 * t->natoms, real, NULL, "velocities cut short");
        if (rc == VB_OK && h.f)
            rc = get_reals(ctx, t, 3 * t->natoms, real, NULL, "forces cut short");
        if (rc != VB_OK)
            return rc;
        t->frame++;
        if (!h.x) {
            t->skipped++;
            continue;
        }
        if (fr) {
            fr->step = h.step;
            fr->time = h.time;
            memcpy(fr->box, box, sizeof box);
            fr->precision = 0;
            fr->is_double = h.dbl;
        }
        *got = 1;
        return VB_OK;
    }
}

static int next_xtc(vb_ctx *ctx, vb_xdr_traj *t, double *xyz, vb_xdr_frame *fr, int *got)
{
    unsigned char b[64];
    uint32_t magic, natoms;
    if (t->pending) {
        /* open read this frame's magic and atom count */
        t->pending = 0;
        magic = t->first_magic;
    } else {
        int r = get(t, b, 8);
        if (r == 0)
            return VB_OK;
        if (r < 0)
            return damaged(ctx, t, "a few stray bytes at the end");
        magic = be32(b);
        natoms = be32(b + 4);
        if (magic != 1995 && magic != 2023)
            return damaged(ctx, t, "no XTC magic number");
        if (natoms != t->natoms)
            return vb_error(ctx, VB_EINPUT_TOPOLOGY, t->name, 0,
                            "XTC frame %ld has %u atoms, the first %zu", t->frame + 1, natoms,
                            t->natoms);
    }
    /* step, time, box (9 floats), the atom count again. */
    if (get(t, b, 4 + 4 + 36 + 4) != 1)
        return damaged(ctx, t, "header cut short");
    int64_t step = (int32_t)be32(b);
    double time = be_float(b + 4), box[9];
    for (int k = 0; k < 9; k++)
        box[k] = be_float(b + 8 + 4 * k);
    if (be32(b + 44) != t->natoms)
        return damaged(ctx, t, "the two atom counts of the frame differ");
    double precision = 0;
    size_t n3 = 3 * t->natoms;
    if (t->natoms <= 9) {
        int rc = get_reals(ctx, t, n3, 4, xyz, "coordinates cut short");
        if (rc != VB_OK)
            return rc;
    } else {
        if (get(t, b, 4 + 24 + 4) != 1)
            return damaged(ctx, t, "coordinate header cut short");
        float prec = be_float(b);
        int32_t minint[3], maxint[3];
        for (int k = 0; k < 3; k++) {
            minint[k] = (int32_t)be32(b + 4 + 4 * k);
            maxint[k] = (int32_t)be32(b + 16 + 4 * k);
        }
        int32_t smallidx = (int32_t)be32(b + 28);
        uint64_t nbytes;
        int wide = magic == 2023;
        if (get(t, b, wide ? 8 : 4) != 1)
            return damaged(ctx, t, "byte count cut short");
        nbytes = wide ? be64(b) : be32(b);
        if (!(prec > 0) || !isfinite(prec))
            return damaged(ctx, t, "precision is not a positive number");
        if (nbytes > (uint64_t)XTC_BYTES_PER_ATOM * t->natoms + 64)
            return damaged(ctx, t, "packed data larger than its atoms can take");
        size_t padded = (size_t)((nbytes + 3) & ~(uint64_t)3);
        if (reserve((void **)&t->packed, &t->packed_cap, padded ? padded : 1) != 0 ||
            (!t->ints && !(t->ints = malloc(n3 * sizeof *t->ints))))
            return vb_error(ctx, VB_ENOMEM, t->name, 0, "out of memory for a frame of %zu atoms",
                            t->natoms);
        if (padded && get(t, t->packed, padded) != 1)
            return damaged(ctx, t, "packed coordinates cut short");
        if (vb_xtc_unpack(t->packed, (size_t)nbytes, t->natoms, minint, maxint, smallidx,
                          t->ints) != 0)
            return damaged(ctx, t, "packed coordinates do not decode");
        /* As the format computes it: each integer times the float nearest
         * 1/precision, in float arithmetic. */
        float inv = (float)(1.0 / (double)prec);
        for (size_t i = 0; xyz && i < n3; i++)
            xyz[i] = (double)((float)t->ints[i] * inv);
        precision = prec;
    }
    t->frame++;
    if (fr) {
        fr->step = step;
        fr->time = time;
        memcpy(fr->box, box, sizeof box);
        fr->precision = precision;
        fr->is_double = 0;
    }
    *got = 1;
    return VB_OK;
}

int vb_xdr_next(vb_ctx *ctx, vb_xdr_traj *t, double *xyz, vb_xdr_frame *fr, int *got)
{
    *got = 0;
    int rc = t->kind == VBI_TRAJ_TRR ? next_trr(ctx, t, xyz, fr, got) : next_xtc(ctx, t, xyz, fr, got);
    if (rc == VB_OK && !*got && t->skipped)
        vb_warn(ctx, VB_W_TRR_NO_COORDINATES, t->name, 0,
                "%ld TRR frame%s without coordinates (velocities or forces only) skipped",
                t->skipped, t->skipped == 1 ? "" : "s");
    return rc;
}
