/* Multi-model input read one frame at a time. PDB and PQR are streamed: the
 * lines of one MODEL..ENDMDL block are gathered and handed to the format's
 * parser, so a long trajectory never sits in memory whole. mmCIF (rarely a
 * trajectory) is held as text and read model by model; XYZR is one frame. */
#include "vb_array.h"
#include "vbi_input.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

/* The first read of a stream: enough for the magic numbers of the binary
 * formats refused here; detection reads on by whole lines. */
#define VBI_HEAD_BYTES ((size_t)1 << 16)

struct vb_frame_reader {
    vb_format fmt;
    char *name;
    vb_read_options opt;
    FILE *f;
    int own_file;
    char *head;            /* text read ahead for detection, served first */
    size_t head_len, head_pos;
    char *line;            /* getline buffer */
    size_t line_cap;
    const char *rest;      /* what is left of the physical line to serve */
    size_t rest_len;
    int open_at_eof;       /* the last block ended with the input, inside a MODEL */
    long lineno;           /* lines consumed so far */
    int unread;            /* serve the last line again */
    const char *last;      /* the last line served */
    size_t last_len;
    char *chunk;           /* the block being gathered */
    size_t chunk_len, chunk_cap;
    int seen_model;        /* a MODEL record was met in the stream */
    vb_box box;            /* the last CRYST1 between models (trajectories as PDB
                            * write one before each MODEL): the next block's box */
    int has_box, block_box;
    int frames;            /* frames returned */
    int done;
    vbi_dropped dr;
    char *text;            /* whole input (mmCIF, XYZR, GRO) */
    size_t text_len;
    size_t text_off;       /* GRO: where the next frame starts */
    long text_line;        /* GRO: its first line */
};

static int next_line_raw(vb_frame_reader *rd, const char **s, size_t *n);

/* Next line of the stream (with its '\n' if any) into *s, *n; 0 at the end,
 * -1 on a read or allocation error. */
static int next_line(vb_frame_reader *rd, const char **s, size_t *n)
{
    if (rd->unread) {
        rd->unread = 0;
        *s = rd->last;
        *n = rd->last_len;
        rd->lineno++;
        return 1;
    }
    int got = next_line_raw(rd, s, n);
    if (got > 0) {
        rd->last = *s;
        rd->last_len = *n;
    }
    return got;
}

static int next_physical(vb_frame_reader *rd, const char **s, size_t *n);

/* The next line of the physical lines (getline's, ending in '\n'), split
 * after each '\r' not followed by '\n' (old Mac OS files): every line
 * served ends in its own terminator. */
static int next_line_raw(vb_frame_reader *rd, const char **s, size_t *n)
{
    if (rd->rest_len == 0) {
        int got = next_physical(rd, &rd->rest, &rd->rest_len);
        if (got <= 0)
            return got;
    }
    const char *p = rd->rest;
    size_t len = rd->rest_len, k = 0;
    while (k < len && p[k] != '\n' && !(p[k] == '\r' && (k + 1 == len || p[k + 1] != '\n')))
        k++;
    if (k < len)
        k++;
    *s = p;
    *n = k;
    rd->rest += k;
    rd->rest_len -= k;
    rd->lineno++;
    return 1;
}

/* The next physical line, from the head read ahead, then from the file (a
 * file with lone CRs only is one physical line: read whole, then split). */
static int next_physical(vb_frame_reader *rd, const char **s, size_t *n)
{
    if (rd->head_pos < rd->head_len) {
        const char *p = rd->head + rd->head_pos;
        size_t left = rd->head_len - rd->head_pos;
        const char *nl = memchr(p, '\n', left);
        /* The head's last line may continue in the file: finish it there. */
        if (nl) {
            *s = p;
            *n = (size_t)(nl - p) + 1;
            rd->head_pos += *n;
            return 1;
        }
        ssize_t got = getline(&rd->line, &rd->line_cap, rd->f);
        size_t tail = got > 0 ? (size_t)got : 0;
        char *joined = malloc(left + tail + 1);
        if (!joined)
            return -1;
        memcpy(joined, p, left);
        if (tail)
            memcpy(joined + left, rd->line, tail);
        free(rd->line);
        rd->line = joined;
        rd->line_cap = left + tail + 1;
        rd->head_pos = rd->head_len;
        *s = rd->line;
        *n = left + tail;
        return 1;
    }
    ssize_t got = getline(&rd->line, &rd->line_cap, rd->f);
    if (got < 0)
        return ferror(rd->f) ? -1 : 0;
    *s = rd->line;
    *n = (size_t)got;
    return 1;
}

static int chunk_add(vb_frame_reader *rd, const char *s, size_t n)
{
    if (VB_ARRAY_FIT(rd->chunk, rd->chunk_cap, rd->chunk_len + n, (size_t)1 << 16) != VB_OK)
        return -1;
    memcpy(rd->chunk + rd->chunk_len, s, n);
    rd->chunk_len += n;
    return 0;
}

void vb_frame_reader_close(vb_frame_reader *rd)
{
    if (!rd)
        return;
    if (rd->f && rd->own_file)
        fclose(rd->f);
    free(rd->name);
    free(rd->head);
    free(rd->line);
    free(rd->chunk);
    free(rd->text);
    free(rd);
}

/* Reads the head of the stream into rd->head: the first VBI_HEAD_BYTES
 * (binary trajectories and PSF are refused on them), then, when the format
 * is to be detected, on until the detector has seen enough whole lines to
 * decide (however long the header) or the input ends. rd->fmt gets the
 * format. Returns VB_OK or the error (message set). */
static int read_head(vb_ctx *ctx, vb_frame_reader *rd)
{
    size_t cap = VBI_HEAD_BYTES, fed = 0;
    vbi_detector det;
    vbi_detector_init(&det);
    rd->fmt = rd->opt.format;
    for (;;) {
        char *h = realloc(rd->head, cap + 1);
        if (!h)
            return vb_error(ctx, VB_ENOMEM, rd->name, 0, "out of memory");
        rd->head = h;
        rd->head_len += fread(rd->head + rd->head_len, 1, cap - rd->head_len, rd->f);
        rd->head[rd->head_len] = '\0';
        if (ferror(rd->f))
            return vbi_input_read_error(ctx, rd->name);
        int eof = rd->head_len < cap;
        if (fed == 0) {
            int rc = vbi_refuse_nonspheres(ctx, rd->name, rd->head, rd->head_len);
            if (rc != VB_OK)
                return rc;
            rd->head_pos = fed = vbi_bom_length(rd->head, rd->head_len);
        }
        if (rd->fmt != VB_FMT_AUTO)
            return VB_OK;
        /* Whole lines only: up to the last '\n' read, or all at the end. */
        size_t upto = rd->head_len;
        if (!eof)
            while (upto > fed && rd->head[upto - 1] != '\n')
                upto--;
        if (vbi_detector_feed(&det, rd->head + fed, upto - fed) || eof)
            break;
        fed = upto;
        if (cap >= VBI_MAX_FILE_BYTES)
            return vb_error(ctx, VB_EINPUT_TOOLARGE, rd->name, 0, "input is larger than 2 GiB");
        cap *= 2;
    }
    int rc = vbi_detector_result(&det, &rd->fmt);
    return rc == VB_OK ? VB_OK : vbi_detect_error(ctx, rd->name, rc);
}

int vb_frame_reader_open(vb_ctx *ctx, const char *path, const vb_read_options *opt,
                         vb_frame_reader **out)
{
    *out = NULL;
    vb_frame_reader *rd = calloc(1, sizeof *rd);
    if (!rd || !(rd->name = strdup(path))) {
        free(rd);
        return vb_error(ctx, VB_ENOMEM, path, 0, "out of memory");
    }
    if (opt)
        rd->opt = *opt;
    rd->f = vbi_open_input(ctx, path, NULL);
    rd->own_file = 1;
    if (!rd->f) {
        int rc = vb_errcode(ctx);
        vb_frame_reader_close(rd);
        return rc;
    }
    int rc0 = read_head(ctx, rd);
    if (rc0 != VB_OK) {
        vb_frame_reader_close(rd);
        return rc0;
    }
    if (rd->fmt == VB_FMT_MMCIF || rd->fmt == VB_FMT_XYZR || rd->fmt == VB_FMT_GRO) {
        /* Not streamed: the rest of the text joins the head. */
        const char *s;
        size_t n;
        int got;
        while ((got = next_line(rd, &s, &n)) > 0)
            if (chunk_add(rd, s, n) != 0 || rd->chunk_len > VBI_MAX_FILE_BYTES)
                break;
        int rc = VB_OK;
        if (got < 0)
            rc = vbi_input_read_error(ctx, path);
        else if (got > 0 && rd->chunk_len > VBI_MAX_FILE_BYTES)
            rc = vb_error(ctx, VB_EINPUT_TOOLARGE, path, 0, "input is larger than 2 GiB");
        else if (got > 0)
            rc = vb_error(ctx, VB_ENOMEM, path, 0, "out of memory");
        if (rc != VB_OK) {
            vb_frame_reader_close(rd);
            return rc;
        }
        rd->text = rd->chunk;
        rd->text_len = rd->chunk_len;
        rd->chunk = NULL;
        rd->chunk_len = rd->chunk_cap = 0;
        if (rd->text) {
            vbi_lone_cr_to_lf(rd->text, rd->text_len);
            if ((rc = vbi_check_nul(ctx, path, rd->text, rd->text_len, 1)) != VB_OK) {
                vb_frame_reader_close(rd);
                return rc;
            }
        }
    }
    *out = rd;
    return VB_OK;
}

static int is_atom_line(const char *s, size_t n)
{
    return vbi_pdb_record(s, n, "ATOM") || vbi_pdb_record(s, n, "HETATM");
}

/* Gathers the next MODEL..ENDMDL block (or, without MODEL records, the whole
 * stream) into rd->chunk. Returns 1 with a block, 0 at the end, or a negative
 * status. *first gets the block's first line number, *serial its MODEL
 * number. */
static int gather_block(vb_ctx *ctx, vb_frame_reader *rd, long *first, int *serial)
{
    rd->chunk_len = 0;
    const char *s;
    size_t n;
    int got, in_block = 0;
    size_t loose_atoms = 0; /* atoms gathered before the first MODEL */
    *first = 0;
    rd->open_at_eof = 0;
    while ((got = next_line(rd, &s, &n)) > 0) {
        if (memchr(s, '\0', n))
            return -vbi_check_nul(ctx, rd->name, s, n, rd->lineno);
        if (vbi_pdb_record(s, n, "MODEL")) {
            if (in_block) {
                /* MODEL without ENDMDL: this line opens the next block. */
                rd->unread = 1;
                rd->lineno--;
                return 1;
            }
            /* What came before the first MODEL was header, or atoms outside
             * any model. */
            rd->dr.other_models += loose_atoms;
            rd->chunk_len = 0;
            rd->block_box = rd->has_box;
            rd->has_box = 0;
            rd->seen_model = in_block = 1;
            *first = rd->lineno;
            *serial = vbi_pdb_model_serial(s, n);
        } else if (rd->seen_model && !in_block) {
            if (vbi_pdb_record(s, n, "CRYST1"))
                rd->has_box = vbi_pdb_cryst1_box(s, n, &rd->box);
            if (is_atom_line(s, n))
                rd->dr.other_models++;
            continue;
        } else if (!rd->seen_model) {
            loose_atoms += is_atom_line(s, n);
            if (vbi_pdb_record(s, n, "CRYST1"))
                rd->has_box = vbi_pdb_cryst1_box(s, n, &rd->box);
        }
        if (*first == 0) {
            *first = rd->lineno;
            *serial = 1;
        }
        if (chunk_add(rd, s, n) != 0)
            return -vb_error(ctx, VB_ENOMEM, rd->name, 0, "out of memory");
        if (rd->chunk_len > VBI_MAX_FILE_BYTES)
            return -vb_error(ctx, VB_EINPUT_TOOLARGE, rd->name, *first,
                             "one frame is larger than 2 GiB");
        if (in_block && vbi_pdb_record(s, n, "ENDMDL"))
            return 1;
    }
    if (got < 0)
        return -vbi_input_read_error(ctx, rd->name);
    rd->open_at_eof = in_block;
    return *first != 0 && (in_block || !rd->seen_model);
}

int vb_frame_reader_next(vb_ctx *ctx, vb_frame_reader *rd, vb_sphere_set **out,
                         int *model_number)
{
    *out = NULL;
    if (rd->done)
        return VB_OK;
    vb_read_options one = rd->opt;
    int serial = 1, rc = VB_OK;
    for (;;) {
        if (rd->fmt == VB_FMT_GRO) {
            size_t off = rd->text_off;
            while (off < rd->text_len && strchr(" \t\r\n", rd->text[off]))
                off++;
            if (off >= rd->text_len)
                break;
            size_t used;
            if (rd->text_line == 0)
                rd->text_line = 1;
            for (size_t i = rd->text_off; i < off; i++)
                rd->text_line += rd->text[i] == '\n';
            rc = vbi_gro_parse(ctx, rd->name, rd->text + off, rd->text_len - off, rd->text_line,
                               &one, &rd->dr, out, &used);
            if (rc != VB_OK)
                return rc;
            for (size_t i = off; i < off + used; i++)
                rd->text_line += rd->text[i] == '\n';
            rd->text_off = off + used;
            serial = ++rd->frames;
        } else if (rd->fmt == VB_FMT_MMCIF || rd->fmt == VB_FMT_XYZR) {
            int ordinal = rd->frames + 1;
            if (rd->fmt == VB_FMT_XYZR) {
                if (ordinal > 1)
                    break;
                rc = vbi_read_xyzr(ctx, rd->name, rd->text, rd->text_len, &one, out);
            } else {
                /* Each pass skips the other models, which are frames here,
                 * not dropped atoms: keep them out of the counts. */
                vbi_dropped keep = rd->dr;
                rc = vbi_mmcif_parse(ctx, rd->name, rd->text, rd->text_len, &one, ordinal,
                                     &rd->dr, &serial, out);
                rd->dr.other_models = keep.other_models;
                rd->dr.other_model_count = keep.other_model_count;
                /* Past the last model: the end, not an error. */
                if (rc == VB_EINPUT_MODEL && ordinal > 1) {
                    vb_clear_error(ctx);
                    rc = VB_OK;
                    break;
                }
            }
            if (rc != VB_OK)
                return rc;
            rd->frames++;
        } else {
            long first;
            int got = gather_block(ctx, rd, &first, &serial);
            if (got < 0)
                return -got;
            if (got == 0)
                break;
            /* The block holds one model: take it, whatever its number. */
            one.model = 0;
            rc = rd->fmt == VB_FMT_PQR
                     ? vbi_pqr_parse(ctx, rd->name, rd->chunk, rd->chunk_len, first, &one,
                                     &rd->dr, out)
                     : vbi_pdb_parse(ctx, rd->name, rd->chunk, rd->chunk_len, first, &one,
                                     &rd->dr, out);
            /* A CRYST1 before the block's MODEL is its box. */
            if (rc == VB_OK && *out && !(*out)->box && rd->block_box) {
                if (!((*out)->box = malloc(sizeof *(*out)->box)))
                    rc = vb_error(ctx, VB_ENOMEM, rd->name, 0, "out of memory");
                else
                    *(*out)->box = rd->box;
            }
            if (rc != VB_OK)
                return rc;
            /* A block closed by the next MODEL lacks ENDMDL, yet it is whole. */
            if (!rd->open_at_eof)
                rd->dr.open_model_line = 0;
            rd->frames++;
        }
        /* --model N picks one frame out of the stream. */
        if (rd->opt.model == 0 || rd->opt.model == serial)
            break;
        rd->dr.other_models += (*out)->n;
        rd->dr.other_model_count++;
        vb_spheres_free(*out);
        *out = NULL;
    }
    if (*out) {
        *model_number = serial;
        if (rd->opt.model != 0)
            rd->done = 1;
        return VB_OK;
    }
    rd->done = 1;
    vbi_report_dropped(ctx, rd->name, &rd->dr);
    if (rd->opt.model != 0)
        return vb_error(ctx, VB_EINPUT_MODEL, rd->name, 0, "model %d is not in the input",
                        rd->opt.model);
    return VB_OK;
}
