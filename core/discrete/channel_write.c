/* Writers of the channel analysis: CSV and JSON tables, centreline PDB, the
 * PyMOL script, and the mask volume (MRC or VTK). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vbc_channel.h"
#include "vb_build.h"
#include "vb_json.h"
#include "vb_output.h"
#include "vb_parallel.h"
#include "vb_stage_clock.h"
#include "vbc_pore.h"

static const char *kind_name(int kind)
{
    return kind == VBC_CHANNEL ? "channel" : kind == VBC_PORE ? "pore" : "cavity";
}

/* Axial coordinate of a point on the pore's axis (the pore's s). */
static double axial(const vbc_result *res, const vbc_point *p)
{
    return p->x * res->pore.u[0] + p->y * res->pore.u[1] + p->z * res->pore.u[2];
}

/* "A:GLY12" (chain, residue name, number, insertion code), or "#<index>"
 * when the input has no atom records. */
static void residue_label(const vb_sphere_set *s, int32_t atom, char *buf, size_t len)
{
    if (!s->info) {
        snprintf(buf, len, "#%d", (int)atom);
        return;
    }
    const vb_atom_info *a = &s->info[atom];
    if (a->icode != ' ' && a->icode != '\0')
        snprintf(buf, len, "%s:%s%d%c", a->chain, a->resname, (int)a->resseq, a->icode);
    else
        snprintf(buf, len, "%s:%s%d", a->chain, a->resname, (int)a->resseq);
}

/* Calls emit(label) once per residue lining channel c, in atom order. */
static void each_residue(const vb_sphere_set *s, const vbc_result *res, const vbc_channel *c,
                         void (*emit)(FILE *, const char *, int), FILE *f)
{
    char prev[64] = "", cur[64], seen[64];
    int count = 0;
    for (size_t t = 0; t < c->nlining; t++) {
        residue_label(s, res->lining[c->first_lining + t], cur, sizeof cur);
        if (strcmp(cur, prev) == 0)
            continue;
        /* Residues are nearly always contiguous; the rare repeat is checked in full. */
        int dup = 0;
        for (size_t u = 0; u < t && !dup; u++) {
            residue_label(s, res->lining[c->first_lining + u], seen, sizeof seen);
            dup = strcmp(seen, cur) == 0;
        }
        strcpy(prev, cur);
        if (!dup)
            emit(f, cur, count++);
    }
}

static void emit_csv(FILE *f, const char *label, int index)
{
    fprintf(f, "%s%s", index ? ";" : "", label);
}

static void emit_json(FILE *f, const char *label, int index)
{
    if (index)
        fputc(',', f);
    vb_json_write_string(f, label);
}

/* The table's columns and what they hold: the CSV header, `channels --help`
 * and the README (a test keeps it equal) come from this one list. */
static const struct {
    const char *name, *meaning;
} columns[] = {
    {"frame", "index of the frame in the input, from 0"},
    {"model", "its MODEL serial (PDB), else frame + 1"},
    {"channel", "number in the frame, 1 = the longest"},
    {"kind", "pore (the axis sweep), channel (reaches the surface) or cavity (--cavities)"},
    {"through", "1 when the centreline joins openings on opposite sides (a pore)"},
    {"length_A", "length of the centreline through its points as written, A"},
    {"bottleneck_A", "smallest clearance radius on it (to the nearest atom surface), A"},
    {"bottleneck_x", "where that is, A (and _y, _z)"},
    {"bottleneck_y", NULL},
    {"bottleneck_z", NULL},
    {"start_x", "the centreline's first point, A (and _y, _z)"},
    {"start_y", NULL},
    {"start_z", NULL},
    {"end_x", "its last point, A (and _y, _z)"},
    {"end_y", NULL},
    {"end_z", NULL},
    {"voxels", "channel voxels of the component"},
    {"volume_A3", "voxels times the voxel volume, A^3"},
    {"mouths", "of those voxels, the ones on the molecular surface (a voxel count)"},
    {"points", "points of the centreline (--centerlines, JSON)"},
    {"lining_atoms", "atoms whose surface is within radius + --lining-tol of a point"},
    {"lining_residues", "their residues, chain:NAMEnumber joined by ';' (one field)"},
    {"reason", "why it is listed: pore along the axis, through, branch, tunnel or cavity"},
    {"bottleneck_s_A", "the bottleneck's position along the pore axis, A (empty: no pore)"},
    {"g_macro_pS", "the pore row: its macroscopic conductance estimate, pS"},
};

const char *vbc_table_columns_help(void)
{
    static char text[4096];
    if (text[0])
        return text;
    size_t off = 0;
    for (size_t k = 0; k < sizeof columns / sizeof columns[0] && off < sizeof text; k++)
        if (columns[k].meaning)
            off += (size_t)snprintf(text + off, sizeof text - off, "  %-19s %s\n", columns[k].name,
                                    columns[k].meaning);
    return text;
}

void vbc_write_csv_header(FILE *f)
{
    for (size_t k = 0; k < sizeof columns / sizeof columns[0]; k++)
        fprintf(f, "%s%s", k ? "," : "", columns[k].name);
    fputc('\n', f);
}

void vbc_write_csv_rows(FILE *f, const vbc_frame_info *fi, const vbc_grid *g,
                        const vb_sphere_set *s, const vbc_result *res)
{
    double v1 = g->h * g->h * (g->dim == 3 ? g->h : 1.0);
    for (size_t t = 0; t < res->nchannels; t++) {
        const vbc_channel *c = &res->channels[t];
        const vbc_point *p = res->points + c->first_point, *b = p + c->bottleneck_at;
        const vbc_point *e = p + c->npoints - 1;
        fprintf(f, "%ld,%d,%zu,%s,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%zu,%.3f,%zu,%zu,%zu,",
                fi->frame, fi->model, t + 1, kind_name(c->kind), c->through, c->length, c->bottleneck, b->x, b->y,
                b->z, p->x, p->y, p->z, e->x, e->y, e->z, c->voxels, (double)c->voxels * v1, c->mouths,
                c->npoints, c->nlining);
        /* The residues are one field: names may hold commas or quotes. */
        char *field = NULL;
        size_t len = 0;
        FILE *m = open_memstream(&field, &len);
        if (m) {
            each_residue(s, res, c, emit_csv, m);
            fclose(m);
        }
        if (field)
            vb_csv_write_field(f, field);
        else /* no memory for the field: the names as they are */
            each_residue(s, res, c, emit_csv, f);
        free(field);
        fputc(',', f);
        vb_csv_write_field(f, vbc_why_text(c->why));
        if (res->pore.present)
            fprintf(f, ",%.3f", axial(res, b));
        else
            fputc(',', f);
        if (c->kind == VBC_PORE && isfinite(res->pore.F))
            fprintf(f, ",%.1f", res->pore.g_macro_pS);
        else if (c->kind == VBC_PORE)
            fprintf(f, ",0.0");
        else
            fputc(',', f);
        fputc('\n', f);
    }
}

void vbc_write_stats_header(FILE *f)
{
    fprintf(f, "frame,model,atoms,grid,voxel_A,channel_voxels,components,pruned,channels,cavities,"
               "longest_A,widest_bottleneck_A,ms_upload,ms_jfa,ms_masks,ms_analysis,ms_total,pore_rmin_A,"
               "pore_rmin_s_A,pore_rmin_x,pore_rmin_y,pore_rmin_z,pore_g_macro_pS,pore_open,ms_pore\n");
}

void vbc_write_stats_row(FILE *f, const vbc_frame_info *fi, const vbc_grid *g,
                         const vbc_result *res)
{
    size_t nch = 0, ncav = 0;
    double longest = 0.0, widest = 0.0;
    for (size_t t = 0; t < res->nchannels; t++) {
        const vbc_channel *c = &res->channels[t];
        if (c->kind != VBC_CAVITY) {
            nch++;
            widest = fmax(widest, c->bottleneck);
        } else {
            ncav++;
        }
        longest = fmax(longest, c->length);
    }
    fprintf(f, "%ld,%d,%zu,%d,%.4f,%zu,%zu,%zu,%zu,%zu,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f", fi->frame,
            fi->model, fi->atoms, g->nx, g->h, fi->channel_voxels, res->components, res->pruned, nch,
            ncav, longest, widest, fi->ms_upload, fi->ms_jfa, fi->ms_masks, fi->ms_analysis,
            fi->ms_total);
    if (res->pore.present) {
        const vbc_channel *c = &res->channels[0];
        const vbc_point *b = res->points + c->first_point + c->bottleneck_at;
        fprintf(f, ",%.3f,%.3f,%.3f,%.3f,%.3f,%.1f,%d", c->bottleneck, axial(res, b), b->x, b->y, b->z,
                isfinite(res->pore.F) ? res->pore.g_macro_pS : 0.0,
                res->pore.open_lo && res->pore.open_hi);
    } else {
        fprintf(f, ",,,,,,,");
    }
    fprintf(f, ",%.3f\n", fi->ms_pore);
}

void vbc_write_json_begin(FILE *f, const char *input, double probe, int n, const char *device)
{
    vbc_write_json_begin_prov(f, NULL, input, probe, n, device);
}

void vbc_write_json_begin_prov(FILE *f, const char *options, const char *input, double probe,
                               int n, const char *device)
{
    fputs("{\n", f);
    if (options) {
        char tool[160];
        snprintf(tool, sizeof tool, "vorball %s (commit %s)", vb_build_version(),
                 vb_build_commit());
        fputs("  \"tool\": ", f);
        vb_json_write_string(f, tool);
        fputs(",\n  \"options\": ", f);
        vb_json_write_string(f, options);
        fputs(",\n", f);
    }
    fprintf(f, "  \"input\": ");
    vb_json_write_string(f, input);
    fprintf(f, ",\n  \"probe_A\": %.3f,\n  \"grid\": %d,\n  \"device\": ", probe, n);
    vb_json_write_string(f, device);
    fprintf(f, ",\n  \"frames\": [");
}

/* A flat JSON object: lead, then "key": value for each space-separated
 * name of keys and its value (ms, 3 decimals), then '}'. */
static void json_clock(FILE *f, const char *lead, const char *keys, const double *v)
{
    fputs(lead, f);
    for (size_t k = 0; *keys; k++) {
        size_t n = strcspn(keys, " ");
        fprintf(f, "%s\"%.*s\": %.3f", k ? ", " : "", (int)n, keys, v[k]);
        keys += n + (keys[n] == ' ');
    }
    fputc('}', f);
}

void vbc_write_json_frame(FILE *f, int first, const vbc_frame_info *fi, const vbc_grid *g,
                          const vb_sphere_set *s, const vbc_result *res)
{
    double t_write = vb_now();
    double v1 = g->h * g->h * (g->dim == 3 ? g->h : 1.0);
    fprintf(f, "%s\n    {\"frame\": %ld, \"model\": %d, \"atoms\": %zu, \"voxel_A\": %.5f,"
               " \"origin\": [%.4f, %.4f, %.4f], \"channel_voxels\": %zu, \"components\": %zu,"
               " \"pruned\": %zu,\n",
            first ? "" : ",", fi->frame, fi->model, fi->atoms, g->h, g->origin[0], g->origin[1],
            g->origin[2], fi->channel_voxels, res->components, res->pruned);
    /* In the order of VBC_JSON_MS_KEYS. */
    const double ms[] = {fi->ms_read,     fi->ms_prepare, fi->ms_upload, fi->ms_jfa,
                         fi->ms_masks,    fi->ms_analysis, fi->ms_graph, fi->ms_voxels,
                         fi->ms_clear,    fi->ms_trace,   fi->ms_cells,  fi->ms_refine,
                         fi->ms_sweep,    fi->ms_verdict, fi->ms_lining, fi->ms_pore,
                         fi->ms_beside,   fi->ms_total};
    json_clock(f, "     \"ms\": {", VBC_JSON_MS_KEYS, ms);
    fputs(",\n", f);
    const vbc_pore_summary *P = &res->pore;
    if (P->present) {
        fprintf(f, "     \"pore\": {\"axis\": [%.5f, %.5f, %.5f], \"start\": [%.3f, %.3f, %.3f],"
                   " \"axis_from\": \"%s\", \"chains\": %d, \"axis_why\": ",
                P->u[0], P->u[1], P->u[2], P->c[0], P->c[1], P->c[2], vbc_axis_source_name(P->source),
                P->chains);
        vb_json_write_string(f, P->why);
        fprintf(f, ", \"step_A\": %.4f, \"open_low\": %s, \"open_high\": %s, \"F_per_A\": %.5f,"
                   " \"g_macro_pS\": %.2f, \"rho_ohm_m\": %.5f},\n",
                P->step, P->open_lo ? "true" : "false", P->open_hi ? "true" : "false",
                isfinite(P->F) ? P->F : -1.0, isfinite(P->F) ? P->g_macro_pS : 0.0, 1.0 / 12.0);
    }
    fprintf(f, "     \"channels\": [");
    for (size_t t = 0; t < res->nchannels; t++) {
        const vbc_channel *c = &res->channels[t];
        const vbc_point *p = res->points + c->first_point, *b = p + c->bottleneck_at;
        fprintf(f, "%s\n       {\"id\": %zu, \"kind\": \"%s\", \"through\": %s, \"length_A\": %.3f, \"bottleneck_A\": %.3f,"
                   " \"bottleneck_at\": [%.3f, %.3f, %.3f], \"voxels\": %zu, \"volume_A3\": %.3f,"
                   " \"mouths\": %zu,\n        \"lining_residues\": [",
                t ? "," : "", t + 1, kind_name(c->kind), c->through ? "true" : "false", c->length, c->bottleneck, b->x, b->y, b->z,
                c->voxels, (double)c->voxels * v1, c->mouths);
        each_residue(s, res, c, emit_json, f);
        fprintf(f, "],\n        \"reason\": ");
        vb_json_write_string(f, vbc_why_text(c->why));
        if (P->present)
            fprintf(f, ", \"bottleneck_s_A\": %.3f", axial(res, b));
        fprintf(f, ", \"nearest_atoms\": [");
        for (size_t u = 0; u < c->npoints; u++)
            fprintf(f, "%s%d", u ? ", " : "", (int)p[u].atom);
        fprintf(f, "],\n        \"centreline\": [");
        for (size_t u = 0; u < c->npoints; u++)
            fprintf(f, "%s[%.3f, %.3f, %.3f, %.3f]", u ? ", " : "", p[u].x, p[u].y, p[u].z, p[u].r);
        fprintf(f, "]}");
    }
    fprintf(f, "],\n");
    /* Last, so that it counts the writing of everything above. */
    double now = vb_now(), w = 1e3 * (now - t_write);
    double frame = fi->t_start > 0.0 ? 1e3 * (now - fi->t_start)
                                     : fi->ms_read + fi->ms_prepare + fi->ms_total + w;
    const double clock[] = {w, frame, frame > 0.0 ? 1e3 / frame : 0.0,
                            fi->t_start > 0.0 ? 1e3 * (vb_cpu_now() - fi->cpu_start) : 0.0};
    json_clock(f, "     \"clock\": {", VBC_JSON_CLOCK_KEYS, clock);
    fputc('}', f);
}

void vbc_write_json_end(FILE *f)
{
    fprintf(f, "\n  ]\n}\n");
}

void vbc_write_json_end_clock(FILE *f, long frames, double wall_ms, double cpu_ms)
{
    const double clock[] = {(double)frames, wall_ms, wall_ms > 0.0 ? 1e3 * (double)frames / wall_ms : 0.0,
                            cpu_ms, frames > 0 ? cpu_ms / (double)frames : 0.0};
    fputs("\n  ],\n", f);
    json_clock(f, "  \"clock\": {", VBC_JSON_RUN_CLOCK_KEYS, clock);
    fputs("\n}\n", f);
}

/* Atom name of point u of a residue: "Q" (HOLE's letter for its sphere
 * centres) and three base-36 digits (unique for 46,656 points), so every
 * point has its own name in the residue as strict PDB readers demand. The
 * letter is no element's: a reader that guesses the element from the name
 * when it does not know the file's "X" (Biopython) finds none, where "P"
 * made every point phosphorus. */
static void point_name(size_t u, char name[5])
{
    static const char digits[] = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ";
    name[0] = 'Q';
    name[1] = digits[(u / 1296) % 36];
    name[2] = digits[(u / 36) % 36];
    name[3] = digits[u % 36];
    name[4] = '\0';
}

/* Points written for channel t: a residue holds at most 46,656 points and a
 * file at most 99,999 atoms (the PDB's fixed columns). */
static size_t points_written(size_t npoints, size_t before)
{
    size_t n = npoints < 46656 ? npoints : 46656;
    return before >= 99999 ? 0 : n < 99999 - before ? n : 99999 - before;
}

void vbc_write_centrelines_pdb(FILE *f, int model, const vbc_result *res)
{
    fprintf(f, "MODEL     %4d\n", model);
    size_t serial = 1;
    for (size_t t = 0; t < res->nchannels; t++) {
        const vbc_channel *c = &res->channels[t];
        const vbc_point *p = res->points + c->first_point;
        size_t n = points_written(c->npoints, serial - 1);
        for (size_t u = 0; u < n; u++, serial++) {
            char name[5];
            point_name(u, name);
            fprintf(f, "HETATM%5zu %-4s %3s %c%4d    %8.3f%8.3f%8.3f  1.00%6.2f           X\n", serial,
                    name, c->kind == VBC_CHANNEL ? "CHN" : c->kind == VBC_PORE ? "POR" : "CAV",
                    (char)('A' + (int)(t % 26)), (int)((t + 1) % 10000), p[u].x, p[u].y, p[u].z,
                    fmax(fmin(p[u].r, 999.99), -99.99));
        }
    }
    fprintf(f, "ENDMDL\n");
}

void vbc_write_centrelines_conect(FILE *f, const vbc_result *first)
{
    size_t serial = 1;
    for (size_t t = 0; first && t < first->nchannels; t++) {
        size_t n = points_written(first->channels[t].npoints, serial - 1);
        for (size_t u = 0; u + 1 < n; u++)
            fprintf(f, "CONECT%5zu%5zu\n", serial + u, serial + u + 1);
        serial += n;
    }
    fprintf(f, "END\n");
}

static int ends_with(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    return a >= b && strcmp(s + a - b, suffix) == 0;
}

/* The value of voxel v of a volume being written: a mask bit or a float. */
typedef struct {
    const uint8_t *flags;
    unsigned bit;
    const float *values;
    double scale;
} volume_src;

static double volume_at(const volume_src *V, size_t v)
{
    return V->values ? V->values[v] * V->scale : (V->flags[v] & V->bit) ? 1.0 : 0.0;
}

/* MRC 2014 header: 256 little-endian words; mode 0 (signed bytes) for a
 * mask, mode 2 (float32) for values; dmin, dmax, dmean and rms from the data
 * and nversion 20140, as mrcfile.validate asks. */
static int write_mrc(FILE *f, const vbc_grid *g, const volume_src *V)
{
    int32_t w[256];
    memset(w, 0, sizeof w);
    float fl;
    w[0] = g->nx;
    w[1] = g->ny;
    w[2] = g->nz;
    w[3] = V->values ? 2 : 0;
    w[7] = g->nx;
    w[8] = g->ny;
    w[9] = g->nz;
    float cell[6] = {(float)(g->nx * g->h), (float)(g->ny * g->h), (float)(g->nz * g->h), 90, 90, 90};
    memcpy(&w[10], cell, sizeof cell);
    w[16] = 1;
    w[17] = 2;
    w[18] = 3;
    size_t nv = vbc_grid_voxels(g);
    double lo = INFINITY, hi = -INFINITY, sum = 0.0, sum2 = 0.0;
    for (size_t v = 0; v < nv; v++) {
        double x = (float)volume_at(V, v);
        lo = fmin(lo, x);
        hi = fmax(hi, x);
        sum += x;
    }
    double mean = sum / (double)nv;
    for (size_t v = 0; v < nv; v++) {
        double d = (float)volume_at(V, v) - mean;
        sum2 += d * d;
    }
    float stats[3] = {(float)lo, (float)hi, (float)mean};
    memcpy(&w[19], stats, sizeof stats);
    w[22] = 1; /* space group P1 */
    w[27] = 20140; /* nversion: MRC 2014 */
    /* Origin of the map in A: the centre of voxel (0,0,0). */
    for (int a = 0; a < 3; a++) {
        fl = (float)(g->origin[a] + 0.5 * g->h);
        memcpy(&w[49 + a], &fl, 4);
    }
    memcpy(&w[52], "MAP ", 4);
    unsigned char stamp[4] = {0x44, 0x44, 0, 0};
    memcpy(&w[53], stamp, 4);
    fl = (float)sqrt(sum2 / (double)nv);
    memcpy(&w[54], &fl, 4);
    w[55] = 1;
    char label[80];
    memset(label, ' ', sizeof label);
    memcpy(label, "vorball channels", 16);
    memcpy(&w[56], label, sizeof label);
    if (fwrite(w, 4, 256, f) != 256)
        return -1;
    for (size_t v = 0; v < nv; v++) {
        if (V->values) {
            float x = (float)volume_at(V, v);
            if (fwrite(&x, 4, 1, f) != 1)
                return -1;
        } else if (fputc(volume_at(V, v) != 0.0 ? 1 : 0, f) == EOF) {
            return -1;
        }
    }
    return 0;
}

static int write_vtk(FILE *f, const vbc_grid *g, const volume_src *V)
{
    size_t nv = vbc_grid_voxels(g);
    fprintf(f, "# vtk DataFile Version 3.0\nvorball channels\nBINARY\n"
               "DATASET STRUCTURED_POINTS\nDIMENSIONS %d %d %d\nORIGIN %.6f %.6f %.6f\n"
               "SPACING %.6f %.6f %.6f\nPOINT_DATA %zu\nSCALARS %s %s 1\n"
               "LOOKUP_TABLE default\n",
            g->nx, g->ny, g->nz, g->origin[0] + 0.5 * g->h, g->origin[1] + 0.5 * g->h,
            g->origin[2] + 0.5 * g->h, g->h, g->h, g->h, nv, V->values ? "occupancy" : "mask",
            V->values ? "float" : "unsigned_char");
    for (size_t v = 0; v < nv; v++) {
        if (V->values) {
            /* Legacy VTK binary data is big-endian. */
            float x = (float)volume_at(V, v);
            unsigned char b[4], o[4];
            memcpy(b, &x, 4);
            o[0] = b[3];
            o[1] = b[2];
            o[2] = b[1];
            o[3] = b[0];
            if (fwrite(o, 1, 4, f) != 4)
                return -1;
        } else if (fputc(volume_at(V, v) != 0.0 ? 1 : 0, f) == EOF) {
            return -1;
        }
    }
    /* VTK's own writers end a binary block with a newline, and readers
     * (meshio) check for it before the next section. */
    return fputc('\n', f) == EOF ? -1 : 0;
}

static int write_volume(vb_ctx *ctx, const char *path, const vbc_grid *g, const volume_src *V)
{
    int vtk = ends_with(path, ".vtk");
    if (!vtk && !ends_with(path, ".mrc") && !ends_with(path, ".map"))
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "volume %s: use a .mrc, .map or .vtk name", path);
    FILE *f = vb_output_open(ctx, path);
    if (!f)
        return vb_errcode(ctx);
    if (vtk ? write_vtk(f, g, V) : write_mrc(f, g, V)) {
        vb_output_discard(f);
        return vb_error(ctx, VB_EIO, path, 0, "cannot write volume file");
    }
    return vb_output_commit(ctx, f);
}

int vbc_write_volume(vb_ctx *ctx, const char *path, const vbc_grid *g, const uint8_t *flags,
                     unsigned bit)
{
    volume_src V = {flags, bit, NULL, 1.0};
    return write_volume(ctx, path, g, &V);
}

int vbc_write_volume_f32(vb_ctx *ctx, const char *path, const vbc_grid *g, const float *values,
                         double scale)
{
    volume_src V = {NULL, 0, values, scale};
    return write_volume(ctx, path, g, &V);
}
