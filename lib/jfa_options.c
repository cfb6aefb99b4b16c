/* The jfa handle's options (lib/vb_jfa.h): the one table of `vorball
 * jfa`'s options (spellings, type, range, default, the Python keyword),
 * setting one by name with the library's one check of the numbers
 * (vbj_setup_check), and the rules between options. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "jfa_handle.h"
#include "vb_numtext.h"

enum {
    O_DIM, O_SIZE, O_SEEDS, O_DIST, O_RNG, O_PROTEIN, O_MARGIN, O_VARIANT, O_M, O_FUSE,
    O_DEVICE, O_CHECK, O_REPEAT, O_JSON, O_PNG, O_SLICE, O_OUT
};

/* The ranges are those vbj_setup_check enforces; help is --help's text
 * (lines broken where --help breaks them). */
static const vb_option OPTIONS[] = {
    {O_DIM, "--dim", "-d", "dim", VB_OPT_COUNT, 2, 3, NULL, "2|3", "2",
     "grid dimension (default 2; 3 with --protein)", 0},
    {O_SIZE, "--size", "-n", "size", VB_OPT_POW2, 2, 16384, NULL, "N", "512",
     "grid side, a power of two (default 512)", 0},
    {O_SEEDS, "--seeds", "-k", "k", VB_OPT_COUNT, 1, 2147483646.0, NULL, "K", "100",
     "generate K seeds (default 100)", 0},
    {O_DIST, "--dist", NULL, "dist", VB_OPT_CHOICE, 0, 0, "uniform,clustered,shell", "D",
     "uniform", "uniform|clustered|shell (default uniform)", 0},
    {O_RNG, "--rng", NULL, "rng", VB_OPT_COUNT, 0, 18446744073709551615.0, NULL, "S", "1",
     "generator seed (default 1)", 0},
    {O_PROTEIN, "--protein", NULL, NULL, VB_OPT_PATH, 0, 0, NULL, "FILE", NULL,
     "seeds at the atom centres of FILE (PDB, mmCIF, PQR, XYZR)\n"
     "fitted into an [n]^3 grid", 0},
    {O_MARGIN, "--margin", NULL, "margin", VB_OPT_REAL, 0, 1e300, NULL, "A", "2",
     "protein: margin around the atoms in Angstrom (default 2)", 0},
    {O_VARIANT, "--variant", "-V", "variant", VB_OPT_NAMES, 1, VBJ_MAX_VARIANTS,
     "jfa,jfa+1,jfa+2,1+jfa,facet,facet-full,exact,exact-boundary,all", "V[,V..]",
     VBJ_VARIANTS_DEFAULT,
     "jfa|jfa+1|jfa+2|1+jfa|facet|facet-full|exact|\n"
     "exact-boundary|all (default jfa+1; all: the first five\n"
     "and exact). exact: the exact diagram by tiles (complete\n"
     "seed lists per tile, exact decisions); exact-boundary:\n"
     "the same and its boundary pixels counted", 0},
    {O_M, "-m", NULL, "m", VB_OPT_COUNT, 1, 16384, NULL, "M", NULL,
     "Facet-JFA start resolution (default: smallest without\n"
     "seed collisions)", 0},
    {O_FUSE, "--fuse-cells", NULL, "fuse_cells", VB_OPT_COUNT, 1, 4294967295.0, NULL, "C",
     NULL,
     "Facet-JFA on OpenCL: the coarse JFA and the levels of at\n"
     "most C cells run in one launch (default 4096 in 2D,\n"
     "1024 in 3D; 1: one launch per phase, as the paper)", 0},
    {O_DEVICE, "--device", NULL, "device", VB_OPT_CHOICE, 0, 0, "auto,gpu,cpu,ref", "D", "auto",
     "auto|gpu|cpu|ref (default auto: GPU, else PoCL, else ref)", 0},
    {O_CHECK, "--check", NULL, "check", VB_OPT_FLAG, 0, 0, NULL, NULL, NULL,
     "compare with the exact diagram (wrong pixels, distance\n"
     "errors, boundary pixels)", 0},
    {O_REPEAT, "--repeat", NULL, "repeat", VB_OPT_COUNT, 1, 100000, NULL, "R", "1",
     "run each variant R times after one warm-up run; times\n"
     "are mean and minimum\n"
     "(time: wall clock of the algorithm on the device; gpu:\n"
     "the summed execution of its commands)", 0},
    {O_JSON, "--json", NULL, NULL, VB_OPT_FLAG, 0, 0, NULL, NULL, NULL,
     "print the figures as JSON", 0},
    {O_PNG, "--png", NULL, NULL, VB_OPT_PATH, 0, 0, NULL, "FILE", NULL,
     "picture: 2D diagram coloured by label, boundaries black;\n"
     "3D: the slices of --slice side by side", 0},
    {O_SLICE, "--slice", NULL, NULL, VB_OPT_NAMES, 1, VBJ_MAX_SLICES, NULL, "Z[,Z..]", NULL,
     "3D slices for --png (default n/2)", 0},
    {O_OUT, "-o", NULL, NULL, VB_OPT_PATH, 0, 0, NULL, "FILE", NULL,
     "output of the figures (default stdout)", 0},
};
#define NOPTIONS (sizeof OPTIONS / sizeof OPTIONS[0])

size_t vb_jfa_option_count(void)
{
    return NOPTIONS;
}

int vb_jfa_option_at(size_t k, vb_option *o)
{
    if (k >= NOPTIONS)
        return -1;
    *o = OPTIONS[k];
    return 0;
}

/* The table's row for a command-line spelling or a Python keyword. */
static const vb_option *row_of(const char *name)
{
    for (size_t k = 0; name && k < NOPTIONS; k++) {
        const vb_option *o = &OPTIONS[k];
        if (name[0] == '-' ? strcmp(name, o->name) == 0 || (o->alias && !strcmp(name, o->alias))
                           : o->py && strcmp(name, o->py) == 0)
            return o;
    }
    return NULL;
}

int vb_jfa_option_find(const char *name, vb_option *o)
{
    const vb_option *r = row_of(name);
    if (!r)
        return -1;
    *o = *r;
    return 0;
}

void vb_jfa_help(FILE *f)
{
    for (size_t k = 0; k < NOPTIONS; k++) {
        const vb_option *o = &OPTIONS[k];
        char left[64];
        int n = o->name[1] != '-'  ? snprintf(left, sizeof left, "%s", o->name)
                : o->alias         ? snprintf(left, sizeof left, "%s, %s", o->alias, o->name)
                                   : snprintf(left, sizeof left, "    %s", o->name);
        if (o->value)
            snprintf(left + n, sizeof left - (size_t)n, " %s", o->value);
        fprintf(f, "  %-22s ", left);
        for (const char *h = o->help; *h; h++) {
            fputc(*h, f);
            if (*h == '\n')
                fprintf(f, "%25s", "");
        }
        fputc('\n', f);
    }
}

int vb_jfa_new(vb_ctx *ctx, vb_jfa **out)
{
    vb_jfa *j = calloc(1, sizeof *j);
    *out = j;
    if (!j)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "jfa: out of memory");
    j->ctx = ctx;
    vbj_setup_defaults(&j->set);
    j->device = "auto";
    return vbj_variants_parse(ctx, VBJ_VARIANTS_DEFAULT, j->v, &j->nv);
}

/* -1 with the context's last message in err. */
static int refused(vb_jfa *j, char *err, size_t errlen)
{
    snprintf(err, errlen, "%s", vb_errmsg(j->ctx));
    return -1;
}

/* -1 with err's message recorded as VB_EMISUSE. */
static int misuse(vb_jfa *j, char *err)
{
    vb_error(j->ctx, VB_EMISUSE, NULL, 0, "%s", err);
    return -1;
}

/* The setup's field a numeric option sets (--margin, a double, aside). */
static uint64_t *number_of(vbj_setup *s, int id)
{
    return id == O_DIM ? &s->dim : id == O_SIZE ? &s->n : id == O_SEEDS ? &s->k
           : id == O_M ? &s->m : id == O_FUSE ? &s->fuse_cells : id == O_REPEAT ? &s->repeat
                                                                               : NULL;
}

/* A number of the setup: a value that does not parse, and an explicit 0
 * where 0 means "not given", are stored as one the check refuses; the
 * check's message names the option, with the value as given. */
static int set_number(vb_jfa *j, int id, const char *v, char *err, size_t errlen)
{
    vbj_setup set = j->set;
    uint64_t *num = number_of(&set, id);
    size_t sz;
    if (num) {
        if (vb_parse_size(v, &sz))
            sz = id == O_SEEDS ? 0 : SIZE_MAX;
        else if (sz == 0 && (id == O_M || id == O_FUSE))
            sz = SIZE_MAX;
        *num = sz;
    } else if (vb_parse_double(v, &set.margin))
        set.margin = -1.0;
    if (vbj_setup_check(j->ctx, &set) != VB_OK) {
        if (id == O_DIM)
            return refused(j, err, errlen);
        char msg[128];
        snprintf(msg, sizeof msg, "%s", vb_errmsg(j->ctx));
        snprintf(err, errlen, "%s '%s'", msg, v);
        return misuse(j, err);
    }
    j->set = set;
    j->dim_given |= id == O_DIM;
    return 0;
}

int vb_jfa_set(vb_jfa *j, const char *name, const char *value, char *err, size_t errlen)
{
    const vb_option *o = row_of(name);
    if (!o) {
        snprintf(err, errlen, "unknown jfa option '%s'", name ? name : "");
        return misuse(j, err);
    }
    if (o->type != VB_OPT_FLAG && !value) {
        snprintf(err, errlen, "option %s needs a value", o->name);
        return misuse(j, err);
    }
    size_t sz;
    switch (o->id) {
    case O_DIST:
        return vbj_distribution_parse(j->ctx, value, &j->dist) ? refused(j, err, errlen) : 0;
    case O_VARIANT:
        return vbj_variants_parse(j->ctx, value, j->v, &j->nv) ? refused(j, err, errlen) : 0;
    case O_RNG:
        if (vb_parse_size(value, &sz)) {
            snprintf(err, errlen, "bad --rng '%s'", value);
            return misuse(j, err);
        }
        j->set.rng = sz;
        return 0;
    case O_PROTEIN: j->protein = value; return 0;
    case O_DEVICE: j->device = value; return 0;
    case O_CHECK: j->check = 1; return 0;
    case O_JSON: j->json = 1; return 0;
    case O_PNG: j->png = value; return 0;
    case O_SLICE: j->slices = value; return 0;
    case O_OUT: j->out = value; return 0;
    default: return set_number(j, o->id, value, err, errlen);
    }
}

/* --slice Z[,Z..] into the setup: a value that does not parse is stored
 * as one vbj_setup_check refuses. */
static void parse_slices(const char *text, vbj_setup *set)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", text);
    set->nslices = 0;
    char *save = NULL;
    for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        size_t z;
        if (set->nslices == VBJ_MAX_SLICES) {
            set->nslices++; /* one too many */
            return;
        }
        set->slice[set->nslices++] = vb_parse_size(t, &z) ? UINT64_MAX : z;
    }
    if (set->nslices == 0)
        set->slice[set->nslices++] = UINT64_MAX;
}

int vb_jfa_check(vb_jfa *j, char *err, size_t errlen)
{
    if (j->protein || j->spheres) {
        if (j->path) {
            snprintf(err, errlen, "give either SEEDS or --protein");
            return misuse(j, err);
        }
        if (j->dim_given && j->set.dim != 3) {
            snprintf(err, errlen, "--protein needs --dim 3");
            return misuse(j, err);
        }
        j->set.dim = 3;
    }
    if (j->set.dim == 3 && j->slices) {
        parse_slices(j->slices, &j->set);
        if (vbj_setup_check(j->ctx, &j->set) != VB_OK) {
            snprintf(err, errlen, "bad --slice '%s' (z values below n)", j->slices);
            return misuse(j, err);
        }
    }
    return vb_device_kind_parse(j->ctx, j->device, &j->kind) ? refused(j, err, errlen) : 0;
}

void vb_jfa_request_get(const vb_jfa *j, vb_jfa_request *r)
{
    r->protein = j->protein;
    r->png = j->png;
    r->out = j->out;
    r->json = j->json;
    r->check = j->check;
}
