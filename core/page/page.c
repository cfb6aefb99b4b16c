/* The results page (vb_page.h): what a command adds is kept as JSON text
 * per frame (memory streams), and written at the end between the page's
 * frame (HTML and style), the embedded viewer and the page's script
 * (page_assets.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_diag.h"
#include "vb_json.h"
#include "vb_output.h"
#include "vb_page.h"
#include "vbp_assets.h"

/* One list of JSON values being written: "[a,b,...]" without the brackets. */
typedef struct jlist {
    FILE *f;
    char *buf;
    size_t len;
    int count;
} jlist;

typedef struct page_frame {
    char *label;
    double *xyz; /* NULL: the set's coordinates */
    jlist paths, profiles, facts, measures, points;
} page_frame;

struct vb_page {
    vb_ctx *ctx;
    char *title;
    char *source;
    size_t n;
    double *xyz, *r;     /* the set's coordinates and radii */
    vb_atom_info *info;  /* NULL for XYZR input */
    page_frame *frames;
    int nframes, cap;
    int full; /* frames were left out (W829 given) */
};

int vb_page_viewer_available(void)
{
    return vbp_viewer_js() != NULL;
}

int vb_page_check(vb_ctx *ctx, const char *path)
{
    if (vbp_viewer_js())
        return VB_OK;
    return vb_error(ctx, VB_EMISUSE, NULL, 0,
                    "%s: this vorball was built without the viewer the results page embeds "
                    "(NGL): run 'bash .ci/viewer' (or pass -DVORBALL_NGL_JS=/path/ngl.js to "
                    "cmake) and rebuild",
                    path);
}

static char *dup_text(const char *s)
{
    size_t k = strlen(s ? s : "") + 1;
    char *d = malloc(k);
    if (d)
        memcpy(d, s ? s : "", k);
    return d;
}

vb_page *vb_page_new(vb_ctx *ctx, const char *title, const vb_sphere_set *s)
{
    vb_page *p = calloc(1, sizeof *p);
    if (!p) {
        vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory for the results page");
        return NULL;
    }
    p->ctx = ctx;
    p->n = s->n;
    p->title = dup_text(title);
    p->source = dup_text(s->source);
    p->xyz = malloc((s->n ? s->n : 1) * 3 * sizeof *p->xyz);
    p->r = malloc((s->n ? s->n : 1) * sizeof *p->r);
    if (s->info)
        p->info = malloc((s->n ? s->n : 1) * sizeof *p->info);
    if (!p->title || !p->source || !p->xyz || !p->r || (s->info && !p->info)) {
        vb_page_free(p);
        vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory for the results page (%zu atoms)", s->n);
        return NULL;
    }
    for (size_t i = 0; i < s->n; i++) {
        p->xyz[3 * i] = s->x[i];
        p->xyz[3 * i + 1] = s->y[i];
        p->xyz[3 * i + 2] = s->z[i];
        p->r[i] = s->r[i];
    }
    if (s->info)
        memcpy(p->info, s->info, s->n * sizeof *p->info);
    return p;
}

size_t vb_page_atoms(const vb_page *p)
{
    return p->n;
}

static void jlist_close(jlist *l)
{
    if (l->f)
        fclose(l->f);
    free(l->buf);
    memset(l, 0, sizeof *l);
}

void vb_page_free(vb_page *p)
{
    if (!p)
        return;
    for (int k = 0; k < p->nframes; k++) {
        page_frame *fr = &p->frames[k];
        free(fr->label);
        free(fr->xyz);
        jlist_close(&fr->paths);
        jlist_close(&fr->profiles);
        jlist_close(&fr->facts);
        jlist_close(&fr->measures);
        jlist_close(&fr->points);
    }
    free(p->frames);
    free(p->title);
    free(p->source);
    free(p->xyz);
    free(p->r);
    free(p->info);
    free(p);
}

static int nomem(vb_page *p)
{
    return vb_error(p->ctx, VB_ENOMEM, NULL, 0, "out of memory for the results page");
}

int vb_page_frame(vb_page *p, const char *label, const double *xyz, int *index)
{
    *index = -1;
    /* Frames with their own coordinates count; the slider writes frame 0's
     * too, so it counts from the start. */
    size_t numbers = 3 * p->n * (size_t)(p->nframes + 1);
    if (p->nframes > 0 && numbers > VB_PAGE_MAX_NUMBERS) {
        if (!p->full)
            vb_warn(p->ctx, VB_W_PAGE_FULL, NULL, 0,
                    "the results page holds %d frames of %zu atoms; later frames are left out "
                    "of it (the tables have them)",
                    p->nframes, p->n);
        p->full = 1;
        return VB_OK;
    }
    if (p->nframes == p->cap) {
        int cap = p->cap ? 2 * p->cap : 4;
        page_frame *f = realloc(p->frames, (size_t)cap * sizeof *f);
        if (!f)
            return nomem(p);
        p->frames = f;
        p->cap = cap;
    }
    page_frame *fr = &p->frames[p->nframes];
    memset(fr, 0, sizeof *fr);
    if (!(fr->label = dup_text(label)))
        return nomem(p);
    if (xyz) {
        if (!(fr->xyz = malloc((p->n ? p->n : 1) * 3 * sizeof *fr->xyz))) {
            free(fr->label);
            return nomem(p);
        }
        memcpy(fr->xyz, xyz, p->n * 3 * sizeof *xyz);
    }
    *index = p->nframes++;
    return VB_OK;
}

int vb_page_frame_set(vb_page *p, const char *label, const vb_sphere_set *s, int *index)
{
    *index = -1;
    if (s->n != p->n)
        return vb_page_frame(p, label, NULL, index);
    double *xyz = malloc((s->n ? s->n : 1) * 3 * sizeof *xyz);
    if (!xyz)
        return nomem(p);
    for (size_t i = 0; i < s->n; i++) {
        xyz[3 * i] = s->x[i];
        xyz[3 * i + 1] = s->y[i];
        xyz[3 * i + 2] = s->z[i];
    }
    int rc = vb_page_frame(p, label, xyz, index);
    free(xyz);
    return rc;
}

/* The list to append to, opened on first use, with the separating comma
 * written; NULL with the error set. */
static FILE *jlist_next(vb_page *p, jlist *l)
{
    if (!l->f && !(l->f = open_memstream(&l->buf, &l->len))) {
        nomem(p);
        return NULL;
    }
    if (l->count++)
        fputc(',', l->f);
    return l->f;
}

/* The frame at `frame`; NULL for -1 (a frame left out of a full page: the
 * caller does nothing) and, with VB_EMISUSE, for an index out of range. */
static page_frame *frame_at(vb_page *p, int frame)
{
    if (frame == -1 && p->full)
        return NULL;
    if (frame < 0 || frame >= p->nframes) {
        vb_error(p->ctx, VB_EMISUSE, NULL, 0, "results page: frame %d of %d", frame, p->nframes);
        return NULL;
    }
    return &p->frames[frame];
}

/* A number for the page: rounded to `digits` significant digits, or null
 * when it is not finite (JSON has no NaN). */
static void put_num(FILE *f, double v, int digits)
{
    if (isfinite(v))
        fprintf(f, "%.*g", digits, v);
    else
        fputs("null", f);
}

static void put_array(FILE *f, size_t n, const double *v, int digits)
{
    fputc('[', f);
    for (size_t k = 0; k < n; k++) {
        if (k)
            fputc(',', f);
        put_num(f, v[k], digits);
    }
    fputc(']', f);
}

/* Coordinates to 0.001 Å, as PDB files give them. */
static void put_coords(FILE *f, size_t n, const double *xyz)
{
    fputc('[', f);
    for (size_t k = 0; k < 3 * n; k++)
        fprintf(f, k ? ",%.3f" : "%.3f", xyz[k]);
    fputc(']', f);
}

enum { LIST_PATHS, LIST_PROFILES, LIST_FACTS, LIST_MEASURES, LIST_POINTS };

/* The stream of list `which` of frame `frame`, ready for the next value;
 * NULL with *rc VB_OK for a frame left out of a full page (nothing to do),
 * VB_EMISUSE for a frame out of range, VB_ENOMEM. */
static FILE *list_next(vb_page *p, int frame, int which, int *rc)
{
    page_frame *fr = frame_at(p, frame);
    *rc = fr ? VB_ENOMEM : frame == -1 && p->full ? VB_OK : VB_EMISUSE;
    if (!fr)
        return NULL;
    jlist *const lists[] = {&fr->paths, &fr->profiles, &fr->facts, &fr->measures, &fr->points};
    jlist *l = lists[which];
    return jlist_next(p, l);
}

/* Writes {"name":..,"<ka>":[a],"r":[r]} for a path or a profile. */
static void put_named(FILE *f, const char *name, const char *ka, size_t n, const double *a, int coords,
                      const double *r)
{
    fputs("{\"name\":", f);
    vb_json_write_string_html(f, name);
    fprintf(f, ",\"%s\":", ka);
    if (coords)
        put_coords(f, n, a);
    else
        put_array(f, n, a, 6);
    fputs(",\"r\":", f);
    put_array(f, n, r, 4);
    fputc('}', f);
}

/* A path or a point set: n points with a radius each, to list `which`. */
static int add_points(vb_page *p, int frame, int which, const char *name, size_t n,
                      const double *xyz, const double *radius)
{
    int rc;
    FILE *f = list_next(p, frame, which, &rc);
    if (!f)
        return rc;
    put_named(f, name, "xyz", n, xyz, 1, radius);
    return VB_OK;
}

int vb_page_path(vb_page *p, int frame, const char *name, size_t n, const double *xyz,
                 const double *radius)
{
    return add_points(p, frame, LIST_PATHS, name, n, xyz, radius);
}

int vb_page_profile(vb_page *p, int frame, const char *name, size_t n, const double *s,
                    const double *r)
{
    int rc;
    FILE *f = list_next(p, frame, LIST_PROFILES, &rc);
    if (!f)
        return rc;
    put_named(f, name, "s", n, s, 0, r);
    return VB_OK;
}

int vb_page_fact(vb_page *p, int frame, const char *key, const char *value)
{
    int rc;
    FILE *f = list_next(p, frame, LIST_FACTS, &rc);
    if (!f)
        return rc;
    fputc('[', f);
    vb_json_write_string_html(f, key);
    fputc(',', f);
    vb_json_write_string_html(f, value);
    fputc(']', f);
    return VB_OK;
}

int vb_page_fact_count(vb_page *p, int frame, const char *key, size_t count)
{
    char v[32];
    snprintf(v, sizeof v, "%zu", count);
    return vb_page_fact(p, frame, key, v);
}

int vb_page_atom_values(vb_page *p, int frame, const char *name, const double *v)
{
    int rc;
    FILE *f = list_next(p, frame, LIST_MEASURES, &rc);
    if (!f)
        return rc;
    fputs("{\"name\":", f);
    vb_json_write_string_html(f, name);
    fputs(",\"v\":", f);
    put_array(f, p->n, v, 6);
    fputc('}', f);
    return VB_OK;
}

int vb_page_points(vb_page *p, int frame, const char *name, size_t n, const double *xyz,
                   const double *radius)
{
    return add_points(p, frame, LIST_POINTS, name, n, xyz, radius);
}

/* The atoms as PDB ATOM/HETATM records (what NGL reads), with the sphere's
 * radius in the B-factor column (the page draws the spheres vorball used),
 * as one JSON string. */
static int put_pdb(FILE *f, const vb_page *p)
{
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    if (!m)
        return VB_ENOMEM;
    for (size_t i = 0; i < p->n; i++) {
        const vb_atom_info *a = p->info ? &p->info[i] : NULL;
        char name[5], aligned[6];
        snprintf(name, sizeof name, "%.4s", a && a->name[0] ? a->name : "S");
        /* Names of up to 3 characters start in column 14, as PDB writes
         * them, so NGL reads the element from the name where it must. */
        snprintf(aligned, sizeof aligned, strlen(name) < 4 ? " %-3s" : "%-4s", name);
        fprintf(m, "%-6s%5zu %-4.4s%c%3.3s %c%4d%c   %8.3f%8.3f%8.3f%6.2f%6.2f          %2.2s\n",
                a && a->hetatm ? "HETATM" : "ATOM", (i + 1) % 100000, aligned,
                a && a->altloc && a->altloc != ' ' ? a->altloc : ' ',
                a && a->resname[0] ? a->resname : "SPH", a && a->chain[0] ? a->chain[0] : 'A',
                a ? (int)(a->resseq % 10000) : (int)(i % 10000), a && a->icode ? a->icode : ' ',
                p->xyz[3 * i], p->xyz[3 * i + 1], p->xyz[3 * i + 2], 1.0,
                p->r[i] < 999.99 ? p->r[i] : 999.99, a && a->element[0] ? a->element : "");
    }
    if (fclose(m) != 0) {
        free(text);
        return VB_ENOMEM;
    }
    vb_json_write_string_html(f, text);
    free(text);
    return VB_OK;
}

static void put_list(FILE *f, const char *key, jlist *l)
{
    fprintf(f, ",\"%s\":[", key);
    if (l->f) {
        fflush(l->f);
        fwrite(l->buf, 1, l->len, f);
    }
    fputc(']', f);
}

static int put_data(FILE *f, vb_page *p)
{
    fputs("{\"title\":", f);
    vb_json_write_string_html(f, p->title);
    fputs(",\"source\":", f);
    vb_json_write_string_html(f, p->source);
    fprintf(f, ",\"atoms\":%zu,\"annotated\":%s,\"pdb\":", p->n, p->info ? "true" : "false");
    if (put_pdb(f, p) != VB_OK)
        return nomem(p);
    fputs(",\"frames\":[", f);
    for (int k = 0; k < p->nframes; k++) {
        page_frame *fr = &p->frames[k];
        fputs(k ? ",\n{\"label\":" : "\n{\"label\":", f);
        vb_json_write_string_html(f, fr->label);
        fputs(",\"xyz\":", f);
        /* With a slider every frame carries its coordinates (going back to
         * frame 0 moves the atoms back). */
        if (fr->xyz || p->nframes > 1)
            put_coords(f, p->n, fr->xyz ? fr->xyz : p->xyz);
        else
            fputs("null", f);
        put_list(f, "paths", &fr->paths);
        put_list(f, "profiles", &fr->profiles);
        put_list(f, "facts", &fr->facts);
        put_list(f, "measures", &fr->measures);
        put_list(f, "points", &fr->points);
        fputc('}', f);
    }
    fputs("]}", f);
    return VB_OK;
}

static void put_escaped_text(FILE *f, const char *s)
{
    for (; *s; s++) {
        if (*s == '<')
            fputs("&lt;", f);
        else if (*s == '>')
            fputs("&gt;", f);
        else if (*s == '&')
            fputs("&amp;", f);
        else
            fputc(*s, f);
    }
}

int vb_page_write(vb_page *p, const char *path)
{
    const char *viewer = vbp_viewer_js();
    if (!viewer)
        return vb_page_check(p->ctx, path);
    int first;
    if (p->nframes == 0 && vb_page_frame(p, "frame 0", NULL, &first) != VB_OK)
        return vb_errcode(p->ctx);
    FILE *f = vb_output_open(p->ctx, path);
    if (!f)
        return vb_errcode(p->ctx);
    fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>", f);
    put_escaped_text(f, p->title);
    fputs("</title>\n<style>\n", f);
    fputs(vbp_page_css(), f);
    fputs("</style>\n</head>\n<body>\n<header><h1>", f);
    put_escaped_text(f, p->title);
    fputs("</h1></header>\n", f);
    fputs(vbp_page_body(), f);
    fputs("<script type=\"application/json\" id=\"vb-data\">", f);
    if (put_data(f, p) != VB_OK) {
        vb_output_discard(f);
        return vb_errcode(p->ctx);
    }
    fputs("</script>\n<script>\n", f);
    fputs(viewer, f);
    fputs("\n</script>\n<script>\n", f);
    fputs(vbp_page_js(), f);
    fputs("\n</script>\n</body>\n</html>\n", f);
    return vb_output_commit(p->ctx, f);
}
