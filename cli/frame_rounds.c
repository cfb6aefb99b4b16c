/* Frame outputs written by rank 0 in frame order (frame_rounds.h). A
 * rank's round travels as one message:
 *   frames (u64), then per frame VB_CLI_ROUND_SINKS lengths (u64), then
 *   per frame the bytes of each sink in turn. */
#include "vb_array.h"
#include "frame_rounds.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vb_world.h"

struct vb_cli_rounds {
    FILE *f[VB_CLI_ROUND_SINKS];
    char *buf[VB_CLI_ROUND_SINKS];
    size_t len[VB_CLI_ROUND_SINKS];
    size_t *ends;           /* per frame, the streams' sizes at its end */
    size_t nframes, cap;
};

static void streams_close(vb_cli_rounds *r)
{
    for (int k = 0; k < VB_CLI_ROUND_SINKS; k++) {
        if (r->f[k])
            fclose(r->f[k]);
        free(r->buf[k]);
        r->f[k] = NULL;
        r->buf[k] = NULL;
        r->len[k] = 0;
    }
    r->nframes = 0;
}

static int streams_open(vb_ctx *ctx, vb_cli_rounds *r)
{
    for (int k = 0; k < VB_CLI_ROUND_SINKS; k++)
        if (!(r->f[k] = open_memstream(&r->buf[k], &r->len[k])))
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (frame outputs)");
    return VB_OK;
}

int vb_cli_rounds_open(vb_ctx *ctx, vb_cli_rounds **out)
{
    *out = calloc(1, sizeof **out);
    if (!*out)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (frame outputs)");
    int rc = streams_open(ctx, *out);
    if (rc != VB_OK) {
        vb_cli_rounds_close(*out);
        *out = NULL;
    }
    return rc;
}

void vb_cli_rounds_close(vb_cli_rounds *r)
{
    if (!r)
        return;
    streams_close(r);
    free(r->ends);
    free(r);
}

long vb_cli_rounds_length(void)
{
    return (long)VB_CLI_ROUND_FRAMES * vb_world_size();
}

int vb_cli_rounds_mine(long j)
{
    return j % vb_world_size() == vb_world_rank();
}

FILE *vb_cli_rounds_stream(vb_cli_rounds *r, int k)
{
    return r->f[k];
}

int vb_cli_rounds_frame_done(vb_ctx *ctx, vb_cli_rounds *r)
{
    r->ends = vb_array_grow(r->ends, &r->cap, r->nframes + 1,
                            VB_CLI_ROUND_SINKS * sizeof *r->ends, VB_CLI_ROUND_FRAMES);
    if (r->cap < r->nframes + 1)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (frame outputs)");
    for (int k = 0; k < VB_CLI_ROUND_SINKS; k++) {
        if (fflush(r->f[k]) != 0)
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (frame outputs)");
        r->ends[r->nframes * VB_CLI_ROUND_SINKS + k] = r->len[k];
    }
    r->nframes++;
    return VB_OK;
}

/* This rank's round as one message (malloc'd). */
static unsigned char *pack(vb_cli_rounds *r, size_t *len)
{
    size_t n = r->nframes, head = 8 * (1 + n * VB_CLI_ROUND_SINKS), body = 0;
    for (int k = 0; k < VB_CLI_ROUND_SINKS; k++)
        body += n ? r->ends[(n - 1) * VB_CLI_ROUND_SINKS + k] : 0;
    unsigned char *b = malloc(head + body), *p = b + head;
    if (!b)
        return NULL;
    uint64_t u = n;
    memcpy(b, &u, 8);
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < VB_CLI_ROUND_SINKS; k++) {
            size_t from = i ? r->ends[(i - 1) * VB_CLI_ROUND_SINKS + k] : 0;
            size_t to = r->ends[i * VB_CLI_ROUND_SINKS + k];
            u = to - from;
            memcpy(b + 8 * (1 + i * VB_CLI_ROUND_SINKS + k), &u, 8);
            memcpy(p, r->buf[k] + from, to - from);
            p += to - from;
        }
    *len = head + body;
    return b;
}

/* Where frame i of a rank's message starts, and its sinks' lengths;
 * checks the message against the frames the rank owes. */
typedef struct part {
    const unsigned char *data;
    uint64_t n;
    const unsigned char *lens;
    size_t *off;            /* per frame, offset of its bytes */
} part;

static int unpack(const unsigned char *b, size_t len, uint64_t want, part *p)
{
    if (len < 8)
        return -1;
    memcpy(&p->n, b, 8);
    if (p->n != want || len < 8 * (1 + p->n * VB_CLI_ROUND_SINKS))
        return -1;
    p->lens = b + 8;
    p->data = b + 8 * (1 + p->n * VB_CLI_ROUND_SINKS);
    p->off = malloc((p->n + 1) * sizeof *p->off);
    if (!p->off)
        return -2;
    size_t at = 0, room = len - (size_t)(p->data - b);
    for (uint64_t i = 0; i < p->n; i++) {
        p->off[i] = at;
        for (int k = 0; k < VB_CLI_ROUND_SINKS; k++) {
            uint64_t l;
            memcpy(&l, p->lens + 8 * (i * VB_CLI_ROUND_SINKS + k), 8);
            if (l > room - at)
                return -1;
            at += (size_t)l;
        }
    }
    return at == room ? 0 : -1;
}

/* Rank 0: every rank's frames, checked, then written in selection order. */
static int write_round(vb_ctx *ctx, unsigned char **parts, const size_t *lens, long j0, long j1,
                       FILE *sinks[VB_CLI_ROUND_SINKS])
{
    int size = vb_world_size(), rc = VB_OK;
    part *p = calloc((size_t)size, sizeof *p);
    if (!p)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (frame outputs)");
    for (int r = 0; r < size && rc == VB_OK; r++) {
        uint64_t want = 0;
        for (long j = j0; j < j1; j++)
            want += j % size == r;
        int e = unpack(parts[r], lens[r], want, &p[r]);
        if (e == -2)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (frame outputs)");
        else if (e != 0)
            rc = vb_error(ctx, VB_EINTERNAL, NULL, 0,
                          "the frame outputs of rank %d (frames %ld..%ld) are garbled", r, j0,
                          j1 - 1);
    }
    for (long j = j0; j < j1 && rc == VB_OK; j++) {
        const part *q = &p[j % size];
        uint64_t i = (uint64_t)((j - j0) / size);
        const unsigned char *d = q->data + q->off[i];
        for (int k = 0; k < VB_CLI_ROUND_SINKS; k++) {
            uint64_t l;
            memcpy(&l, q->lens + 8 * (i * VB_CLI_ROUND_SINKS + k), 8);
            if (sinks[k] && l)
                fwrite(d, 1, (size_t)l, sinks[k]);
            d += l;
        }
    }
    for (int r = 0; r < size; r++)
        free(p[r].off);
    free(p);
    return rc;
}

int vb_cli_rounds_flush(vb_ctx *ctx, vb_cli_rounds *r, int rc, long j0, long j1,
                        FILE *sinks[VB_CLI_ROUND_SINKS])
{
    rc = vb_world_agree(ctx, rc);
    if (rc != VB_OK)
        return rc;
    size_t len = 0;
    unsigned char *mine = pack(r, &len), **parts = NULL;
    size_t *lens = NULL;
    /* A rank out of memory sends nothing, which rank 0 refuses; the agree
     * below then stops every rank before another collective. */
    if (!mine)
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (frame outputs)");
    int rg = vb_world_gather(ctx, mine, mine ? len : 0, &parts, &lens);
    rc = rc == VB_OK ? rg : rc;
    free(mine);
    if (rc == VB_OK && parts)
        rc = write_round(ctx, parts, lens, j0, j1, sinks);
    for (int k = 0; parts && k < vb_world_size(); k++)
        free(parts[k]);
    free(parts);
    free(lens);
    streams_close(r);
    if (rc == VB_OK)
        rc = streams_open(ctx, r);
    return vb_world_agree(ctx, rc);
}
