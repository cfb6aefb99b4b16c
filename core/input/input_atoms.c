/* Atom-level rules shared by the PDB, PQR and mmCIF readers: which records
 * and models are read, which residues are water, which atoms are hydrogens,
 * and the one-line reports of what was left out (element inference is
 * element_infer.c). */
#include "vbi_input.h"
#include "vb_array.h"
#include "vb_diag.h"

#include <ctype.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int vbi_is_water(const char *resname)
{
    static const char *const water[] = {"HOH", "WAT", "DOD", "H2O", "TIP", "TIP3", "TIP4",
                                        "TIP5", "SOL", "T3P", "T4P", "T5P", "SPC", "OPC"};
    for (size_t k = 0; k < sizeof water / sizeof water[0]; k++)
        if (strcmp(resname, water[k]) == 0)
            return 1;
    return 0;
}

int vbi_is_virtual_site(const char *resname, const char *name)
{
    static const char *const site[] = {"MW", "OM", "EPW", "EP", "EP1", "EP2", "LP1", "LP2", "M"};
    if (!vbi_is_water(resname))
        return 0;
    for (size_t k = 0; k < sizeof site / sizeof site[0]; k++)
        if (strcmp(name, site[k]) == 0)
            return 1;
    return 0;
}

int vbi_is_hydrogen(const char *element)
{
    return strcmp(element, "H") == 0 || strcmp(element, "D") == 0;
}

int32_t vbi_pdb_model_serial(const char *line, size_t n)
{
    const char *p = line + (n < 5 ? n : 5), *tok;
    size_t k = vbi_token(&p, line + n, &tok);
    int32_t serial = 0;
    if (k > 0)
        vbi_parse_int(tok, k, &serial);
    return serial;
}

int vbi_zero_radius_policy(const vb_read_options *opt, vb_format fmt)
{
    if (opt->zero_radius != VB_ZERO_RADIUS_AUTO)
        return opt->zero_radius;
    return fmt == VB_FMT_PQR ? VB_ZERO_RADIUS_POINT : VB_ZERO_RADIUS_ERROR;
}

int vbi_zero_radius_skip(int policy, vb_decimal r, vbi_dropped *dr)
{
    if (r.mant != 0)
        return 0;
    if (policy == VB_ZERO_RADIUS_DROP) {
        dr->zero_dropped++;
        return 1;
    }
    if (policy == VB_ZERO_RADIUS_POINT)
        dr->zero_points++;
    return 0;
}

void vbi_report_dropped(vb_ctx *ctx, const char *name, const vbi_dropped *dr)
{
    if (dr->water)
        vb_warn(ctx, VB_W_WATER_DROPPED, name, 0, "%zu water atom%s dropped (--water keeps them)", dr->water,
                dr->water == 1 ? "" : "s");
    if (dr->virtual_sites)
        vb_warn(ctx, VB_W_VIRTUAL_SITES_DROPPED, name, 0,
                "%zu massless virtual site%s of a water model (MW, OM, EPW, LP1, ...) left out: "
                "a point charge, not an atom", dr->virtual_sites, dr->virtual_sites == 1 ? "" : "s");
    if (dr->altloc)
        vb_warn(ctx, VB_W_ALTLOC_DROPPED, name, 0,
                "%zu atom%s of other alternate locations dropped (first location kept)",
                dr->altloc, dr->altloc == 1 ? "" : "s");
    if (dr->other_models)
        vb_warn(ctx, VB_W_MODELS_IGNORED, name, 0, "%zu atom%s of %zu other model%s ignored (--model N)",
                dr->other_models, dr->other_models == 1 ? "" : "s", dr->other_model_count,
                dr->other_model_count == 1 ? "" : "s");
    if (dr->hydrogens)
        vb_warn(ctx, VB_W_HYDROGENS_DROPPED, name, 0, "%zu hydrogen atom%s dropped (--no-hydrogens)", dr->hydrogens,
                dr->hydrogens == 1 ? "" : "s");
    if (dr->after_end)
        vb_warn(ctx, VB_W_AFTER_END, name, 0, "%zu atom record%s after the END record ignored", dr->after_end,
                dr->after_end == 1 ? "" : "s");
    if (dr->zero_dropped)
        vb_warn(ctx, VB_W_ZERO_DROPPED, name, 0, "%zu sphere%s of radius 0 dropped (--zero-radius drop)",
                dr->zero_dropped, dr->zero_dropped == 1 ? "" : "s");
    if (dr->zero_points)
        vb_warn(ctx, VB_W_ZERO_POINTS, name, 0,
                "%zu sphere%s of radius 0 kept as point sites (--zero-radius error|drop to change)",
                dr->zero_points, dr->zero_points == 1 ? "" : "s");
    if (dr->open_model_line)
        vb_warn(ctx, VB_W_MODEL_OPEN_AT_END, name, dr->open_model_line,
                "the input ends inside this MODEL (no ENDMDL, no END): the file may be "
                "truncated; the model's atoms were read as they stand");
    vbi_report_inferred(ctx, name, dr);
    if (dr->unknown_elements > 1)
        vb_warn(ctx, VB_W_ELEMENT_UNKNOWN_COUNT, name, 0, "%zu atoms in all had an unknown element and radius 1.70",
                dr->unknown_elements);
}

void vbi_models_init(vbi_models *m, int want)
{
    memset(m, 0, sizeof *m);
    m->want = want;
    m->taken_serial = 1;
}

void vbi_models_begin(vbi_models *m, int serial, vbi_dropped *dr)
{
    m->seen_model = m->in_model = 1;
    m->blocks++;
    m->taking = !m->found && (m->by_ordinal ? m->blocks == m->want
                                            : m->want == 0 || serial == m->want);
    if (m->taking) {
        m->found = 1;
        m->taken_serial = serial;
    } else {
        dr->other_model_count++;
    }
}

void vbi_models_end(vbi_models *m)
{
    m->in_model = 0;
}

int vbi_models_takes(const vbi_models *m)
{
    if (m->in_model)
        return m->taking;
    /* Atoms outside MODEL blocks form the implicit model 1. */
    return !m->seen_model && (m->want == 0 || m->want == 1);
}

int vbi_models_check(vb_ctx *ctx, const char *name, const vbi_models *m)
{
    if (m->want == 0 || m->found || (m->want == 1 && !m->seen_model))
        return VB_OK;
    return vb_error(ctx, VB_EINPUT_MODEL, name, 0, "model %d is not in the input%s", m->want,
                    m->seen_model ? "" : " (it has a single model, number 1)");
}

int vbi_builder_close(vbi_builder *b, const vbi_models *m, int rc, vb_sphere_set **out)
{
    if (rc == VB_OK)
        rc = vbi_models_check(b->ctx, b->name, m);
    if (rc != VB_OK) {
        vbi_builder_discard(b);
        return rc;
    }
    vbi_builder_finish(b, 1, out);
    return VB_OK;
}

vbi_record vbi_record_kind(int (*is)(const char *, size_t, const char *), const char *s,
                           size_t n)
{
    if (is(s, n, "MODEL"))
        return VBI_REC_MODEL;
    if (is(s, n, "ENDMDL"))
        return VBI_REC_ENDMDL;
    if (is(s, n, "END"))
        return VBI_REC_END;
    if (is(s, n, "ATOM") || is(s, n, "HETATM"))
        return VBI_REC_ATOM;
    return VBI_REC_OTHER;
}

void vbi_atom_scan_init(vbi_atom_scan *s, int want)
{
    vbi_models_init(&s->models, want);
    s->ended = 0;
    s->model_line = 0;
}

int vbi_atom_scan_takes(vbi_atom_scan *s, vbi_record rec, int32_t model_serial, long lineno,
                        vbi_dropped *dr)
{
    switch (rec) {
    case VBI_REC_MODEL:
        s->model_line = lineno;
        vbi_models_begin(&s->models, model_serial, dr);
        return 0;
    case VBI_REC_ENDMDL: vbi_models_end(&s->models); return 0;
    case VBI_REC_END: s->ended = 1; return 0;
    case VBI_REC_OTHER: return 0;
    case VBI_REC_ATOM: break;
    }
    if (s->ended) {
        dr->after_end++;
        return 0;
    }
    if (!vbi_models_takes(&s->models)) {
        dr->other_models++;
        return 0;
    }
    return 1;
}

int vbi_atom_parse_begin(vb_ctx *ctx, const char *name, const vb_read_options *opt,
                         vbi_builder *b, vbi_atom_scan *scan, vb_sphere_set **out)
{
    *out = NULL;
    int rc = vbi_builder_init(b, ctx, name, opt->max_spheres, 1);
    if (rc == VB_OK)
        vbi_atom_scan_init(scan, opt->model);
    return rc;
}

int vbi_atom_parse_end(vbi_builder *b, const vbi_atom_scan *scan, vbi_dropped *dr, int rc,
                       vb_sphere_set **out)
{
    if (scan->models.in_model && scan->models.taking && !scan->ended && scan->model_line > 0)
        dr->open_model_line = scan->model_line;
    return vbi_builder_close(b, &scan->models, rc, out);
}

void vbi_altloc_init(vbi_altloc *a)
{
    memset(a, 0, sizeof *a);
    a->last = SIZE_MAX;
}

void vbi_altloc_free(vbi_altloc *a)
{
    free(a->res);
    vb_hash_free(&a->h);
    vbi_altloc_init(a);
}

static int same_residue(const vbi_altloc_res *r, const vb_atom_info *info)
{
    return r->resseq == info->resseq && r->icode == info->icode &&
           strcmp(r->chain, info->chain) == 0;
}

static uint64_t residue_hash(const char *chain, int32_t resseq, char icode)
{
    uint64_t h = 1469598103934665603ull;
    for (const char *c = chain; *c; c++)
        h = (h ^ (unsigned char)*c) * 1099511628211ull;
    h = (h ^ (uint32_t)resseq) * 1099511628211ull;
    h = (h ^ (unsigned char)icode) * 1099511628211ull;
    return h ^ (h >> 29);
}

/* vb_hash's callbacks: the residue sought is key (chain cut as kept). */
typedef struct residue_key {
    const vbi_altloc *a;
    const vbi_altloc_res *key;
} residue_key;

static int residue_same(const void *key, size_t item)
{
    const residue_key *k = key;
    const vbi_altloc_res *r = &k->a->res[item];
    return r->resseq == k->key->resseq && r->icode == k->key->icode &&
           strcmp(r->chain, k->key->chain) == 0;
}

static uint64_t residue_hash_of(const void *arg, size_t item)
{
    const vbi_altloc_res *r = &((const vbi_altloc *)arg)->res[item];
    return residue_hash(r->chain, r->resseq, r->icode);
}

/* The residue of info in the table (a->last), added with info's location
 * and occupancy occ when new. 0, or -1 when out of memory. */
static int residue_of(vbi_altloc *a, const vb_atom_info *info, double occ)
{
    /* Lettered atoms of one residue usually come together: the last
     * residue answers most lookups. */
    if (a->last != SIZE_MAX && same_residue(&a->res[a->last], info))
        return 0;
    vbi_altloc_res key;
    memset(&key, 0, sizeof key);
    memcpy(key.chain, info->chain, sizeof key.chain);
    key.chain[sizeof key.chain - 1] = '\0';
    key.resseq = info->resseq;
    key.icode = info->icode;
    if ((!a->h.cap && vb_hash_fit(&a->h, 1, residue_hash_of, a) != VB_OK) ||
        VB_ARRAY_FIT(a->res, a->cap, a->n + 1, 64) != VB_OK)
        return -1;
    residue_key k = {a, &key};
    size_t *slot = vb_hash_slot(&a->h, residue_hash(key.chain, key.resseq, key.icode),
                                residue_same, &k);
    if (*slot) {
        a->last = *slot - 1;
        return 0;
    }
    key.kept = info->altloc;
    key.occupancy = occ;
    a->res[a->n] = key;
    a->last = a->n++;
    return vb_hash_put(&a->h, slot, a->last, residue_hash_of, a) == VB_OK ? 0 : -1;
}

int vbi_altloc_offer(vbi_altloc *a, const vb_atom_info *info, double occupancy)
{
    if (info->altloc == ' ')
        return 0;
    if (residue_of(a, info, occupancy) != 0)
        return -1;
    /* Strictly higher: ties go to the location met first. */
    vbi_altloc_res *r = &a->res[a->last];
    if (occupancy > r->occupancy) {
        r->kept = info->altloc;
        r->occupancy = occupancy;
    }
    return 0;
}

int vbi_altloc_keeps(vbi_altloc *a, const vb_atom_info *info)
{
    if (info->altloc == ' ')
        return 1;
    if (residue_of(a, info, -1) != 0)
        return -1;
    return info->altloc == a->res[a->last].kept;
}

int vbi_atom_dropped(const vb_read_options *opt, vbi_altloc *alt, const vb_atom_info *info,
                     vbi_dropped *dr)
{
    if (!opt->keep_water && vbi_is_water(info->resname)) {
        dr->water++;
        return 1;
    }
    if (!opt->keep_virtual_sites && vbi_is_virtual_site(info->resname, info->name)) {
        dr->virtual_sites++;
        return 1;
    }
    int keep = alt ? vbi_altloc_keeps(alt, info) : 1;
    if (keep < 0)
        return -1;
    if (!keep) {
        dr->altloc++;
        return 1;
    }
    if (opt->drop_hydrogens && vbi_is_hydrogen(info->element)) {
        dr->hydrogens++;
        return 1;
    }
    return 0;
}
