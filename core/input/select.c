/* Atom selections (vb_select.h): a recursive-descent parser into a small
 * tree, matched atom by atom. */
#include "vb_select.h"
#include "vbi_input.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

enum { N_OR, N_AND, N_NOT, N_ALL, N_PROTEIN, N_WATER, N_CHAIN, N_SEGID, N_RESNAME, N_RESID,
       N_NAME, N_ELEMENT };

typedef struct sel_node {
    int kind;
    struct sel_node *a, *b;      /* operands of or, and, not */
    char (*val)[16];             /* keyword values */
    long (*range)[2];            /* resid ranges */
    size_t nval;
} sel_node;

struct vb_select {
    sel_node *root;
};

typedef struct {
    vb_ctx *ctx;
    const char *text;
    size_t at;         /* where the current token starts */
    char tok[64];
    size_t tok_at, tok_len;
    int rc;
} parser;

static const char *const keywords[] = {"chain", "segid", "resname", "resid", "name", "element"};

static void node_free(sel_node *n)
{
    if (!n)
        return;
    node_free(n->a);
    node_free(n->b);
    free(n->val);
    free(n->range);
    free(n);
}

static int fail(parser *P, size_t at, const char *what)
{
    if (P->rc == VB_OK)
        P->rc = vb_error(P->ctx, VB_EINPUT_SELECT, NULL, 0,
                         "--select: %s at character %zu of \"%s\"", what, at + 1, P->text);
    return P->rc;
}

/* The next token: "(", ")" or a run of other non-blank characters. */
static void next(parser *P)
{
    const char *t = P->text;
    while (t[P->at] && isspace((unsigned char)t[P->at]))
        P->at++;
    P->tok_at = P->at;
    size_t n = 0;
    if (t[P->at] == '(' || t[P->at] == ')') {
        n = 1;
    } else {
        while (t[P->at + n] && !isspace((unsigned char)t[P->at + n]) && t[P->at + n] != '(' &&
               t[P->at + n] != ')')
            n++;
    }
    P->tok_len = n;
    size_t c = n < sizeof P->tok - 1 ? n : sizeof P->tok - 1;
    memcpy(P->tok, t + P->at, c);
    P->tok[c] = '\0';
    P->at += n;
}

static int is(const parser *P, const char *word)
{
    return P->tok_len > 0 && strcasecmp(P->tok, word) == 0;
}

static int keyword_of(const parser *P)
{
    for (size_t k = 0; k < sizeof keywords / sizeof keywords[0]; k++)
        if (is(P, keywords[k]))
            return N_CHAIN + (int)k;
    return -1;
}

/* A value may follow: not the end, a parenthesis, an operator or a keyword. */
static int value_next(const parser *P)
{
    return P->tok_len > 0 && !is(P, "(") && !is(P, ")") && !is(P, "and") && !is(P, "or") &&
           !is(P, "not") && keyword_of(P) < 0;
}

static sel_node *node(parser *P, int kind, sel_node *a, sel_node *b)
{
    sel_node *n = calloc(1, sizeof *n);
    if (!n) {
        node_free(a);
        node_free(b);
        if (P->rc == VB_OK)
            P->rc = vb_error(P->ctx, VB_ENOMEM, NULL, 0, "out of memory parsing --select");
        return NULL;
    }
    n->kind = kind;
    n->a = a;
    n->b = b;
    return n;
}

/* "12", "-3", "5:20" into r; 0 when malformed. */
static int parse_range(const char *s, long r[2])
{
    char *end;
    r[0] = strtol(s, &end, 10);
    if (end == s)
        return 0;
    if (*end == '\0') {
        r[1] = r[0];
        return 1;
    }
    if (*end != ':')
        return 0;
    const char *s2 = end + 1;
    r[1] = strtol(s2, &end, 10);
    return end != s2 && *end == '\0' && r[0] <= r[1];
}

static sel_node *parse_values(parser *P, int kind)
{
    size_t kw_at = P->tok_at;
    next(P);
    sel_node *n = node(P, kind, NULL, NULL);
    if (!n)
        return NULL;
    while (value_next(P)) {
        if (P->tok_len >= 16) {
            fail(P, P->tok_at, "value longer than 15 characters");
            break;
        }
        void *v = realloc(n->val, (n->nval + 1) * sizeof *n->val);
        void *r = v ? realloc(n->range, (n->nval + 1) * sizeof *n->range) : NULL;
        if (v)
            n->val = v;
        if (r)
            n->range = r;
        if (!v || !r) {
            if (P->rc == VB_OK)
                P->rc = vb_error(P->ctx, VB_ENOMEM, NULL, 0, "out of memory parsing --select");
            break;
        }
        memcpy(n->val[n->nval], P->tok, P->tok_len + 1);
        if (kind == N_RESID && !parse_range(P->tok, n->range[n->nval])) {
            fail(P, P->tok_at, "resid needs a number or a range a:b with a <= b");
            break;
        }
        n->nval++;
        next(P);
    }
    if (P->rc == VB_OK && n->nval == 0)
        fail(P, kw_at, "keyword without a value");
    if (P->rc != VB_OK) {
        node_free(n);
        return NULL;
    }
    return n;
}

static sel_node *parse_or(parser *P);

static sel_node *parse_factor(parser *P)
{
    if (P->tok_len == 0) {
        fail(P, P->tok_at, "expression ends where a selection was expected");
        return NULL;
    }
    if (is(P, "not")) {
        next(P);
        sel_node *a = parse_factor(P);
        return a ? node(P, N_NOT, a, NULL) : NULL;
    }
    if (is(P, "(")) {
        size_t open = P->tok_at;
        next(P);
        sel_node *a = parse_or(P);
        if (!a)
            return NULL;
        if (!is(P, ")")) {
            node_free(a);
            fail(P, P->tok_len ? P->tok_at : open, P->tok_len ? "')' expected" : "'(' not closed");
            return NULL;
        }
        next(P);
        return a;
    }
    int simple = is(P, "all") ? N_ALL : is(P, "protein") ? N_PROTEIN : is(P, "water") ? N_WATER : -1;
    if (simple >= 0) {
        next(P);
        return node(P, simple, NULL, NULL);
    }
    int kw = keyword_of(P);
    if (kw >= 0)
        return parse_values(P, kw);
    fail(P, P->tok_at, "unknown word (chain, segid, resname, resid, name, element, protein, water, "
                       "all, and, or, not, parentheses)");
    return NULL;
}

/* or-terms of and-factors: level 0 parses "or" over level 1, level 1
 * "and" over factors (so and binds tighter). */
static sel_node *parse_binary(parser *P, int level)
{
    const char *op = level == 0 ? "or" : "and";
    int kind = level == 0 ? N_OR : N_AND;
    sel_node *a = level == 0 ? parse_binary(P, 1) : parse_factor(P);
    while (a && is(P, op)) {
        next(P);
        sel_node *b = level == 0 ? parse_binary(P, 1) : parse_factor(P);
        a = b ? node(P, kind, a, b) : (node_free(a), NULL);
    }
    return a;
}

static sel_node *parse_or(parser *P)
{
    return parse_binary(P, 0);
}

int vb_select_parse(vb_ctx *ctx, const char *expr, vb_select **out)
{
    *out = NULL;
    parser P = {ctx, expr ? expr : "", 0, {0}, 0, 0, VB_OK};
    next(&P);
    sel_node *root = parse_or(&P);
    if (root && P.tok_len > 0) {
        fail(&P, P.tok_at, is(&P, ")") ? "')' without '('" : "'and' or 'or' expected");
        node_free(root);
        root = NULL;
    }
    if (!root)
        return P.rc;
    vb_select *s = malloc(sizeof *s);
    if (!s) {
        node_free(root);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory parsing --select");
    }
    s->root = root;
    *out = s;
    return VB_OK;
}

void vb_select_free(vb_select *sel)
{
    if (!sel)
        return;
    node_free(sel->root);
    free(sel);
}

/* Glob match with '?' and '*', case-insensitive when fold. */
static int glob(const char *p, const char *s, int fold)
{
    for (; *p; p++, s++) {
        if (*p == '*') {
            for (;; s++) {
                if (glob(p + 1, s, fold))
                    return 1;
                if (!*s)
                    return 0;
            }
        }
        if (!*s)
            return 0;
        int a = fold ? toupper((unsigned char)*p) : (unsigned char)*p;
        int b = fold ? toupper((unsigned char)*s) : (unsigned char)*s;
        if (*p != '?' && a != b)
            return 0;
    }
    return *s == '\0';
}

static int is_protein(const char *resname)
{
    static const char *const aa[] = {
        "ALA", "ARG", "ASN", "ASP", "CYS", "GLN", "GLU", "GLY", "HIS", "ILE", "LEU", "LYS",
        "MET", "PHE", "PRO", "SER", "THR", "TRP", "TYR", "VAL", "HID", "HIE", "HIP", "HSD",
        "HSE", "HSP", "CYX", "CYM", "ASH", "GLH", "LYN", "ARN", "MSE", "SEC", "PYL", "DAL",
        "DLE", "DVA", "ACE", "NME", "NMA"};
    for (size_t k = 0; k < sizeof aa / sizeof aa[0]; k++)
        if (strcasecmp(resname, aa[k]) == 0)
            return 1;
    return 0;
}

static int any_value(const sel_node *n, const char *field, int fold, int wild)
{
    for (size_t k = 0; k < n->nval; k++)
        if (wild ? glob(n->val[k], field, fold)
                 : (fold ? strcasecmp(n->val[k], field) : strcmp(n->val[k], field)) == 0)
            return 1;
    return 0;
}

static int match(const sel_node *n, const vb_atom_info *a)
{
    switch (n->kind) {
    case N_OR: return match(n->a, a) || match(n->b, a);
    case N_AND: return match(n->a, a) && match(n->b, a);
    case N_NOT: return !match(n->a, a);
    case N_ALL: return 1;
    default: break;
    }
    if (!a)
        return 0;
    switch (n->kind) {
    case N_PROTEIN: return is_protein(a->resname);
    case N_WATER: return vbi_is_water(a->resname);
    case N_CHAIN: return any_value(n, a->chain, 0, 0);
    case N_SEGID: return any_value(n, a->segid, 0, 0);
    case N_RESNAME: return any_value(n, a->resname, 1, 1);
    case N_NAME: return any_value(n, a->name, 1, 1);
    case N_ELEMENT: return any_value(n, a->element, 1, 0);
    case N_RESID:
        for (size_t k = 0; k < n->nval; k++)
            if (a->resseq >= n->range[k][0] && a->resseq <= n->range[k][1])
                return 1;
        return 0;
    default: return 0;
    }
}

int vb_select_match(const vb_select *sel, const vb_atom_info *a)
{
    return match(sel->root, a);
}

int vb_spheres_subset(vb_ctx *ctx, const vb_sphere_set *s, const uint8_t *keep, vb_sphere_set **out)
{
    *out = NULL;
    size_t n = 0;
    for (size_t i = 0; i < s->n; i++)
        n += keep[i] != 0;
    vb_sphere_set *t;
    int rc = vb_spheres_new(ctx, s->source, n, s->info != NULL, &t);
    int exact = s->ex != NULL;
    if (rc == VB_OK && exact) {
        t->ex = malloc((n ? n : 1) * sizeof *t->ex);
        t->ey = malloc((n ? n : 1) * sizeof *t->ey);
        t->ez = malloc((n ? n : 1) * sizeof *t->ez);
        t->er = malloc((n ? n : 1) * sizeof *t->er);
    }
    if (rc == VB_OK && s->box && (t->box = malloc(sizeof *t->box)))
        *t->box = *s->box;
    if (rc == VB_OK && ((exact && (!t->ex || !t->ey || !t->ez || !t->er)) || (s->box && !t->box))) {
        vb_spheres_free(t);
        rc = vb_error(ctx, VB_ENOMEM, s->source, 0, "out of memory for %zu spheres", n);
    }
    if (rc != VB_OK)
        return rc;
    size_t k = 0;
    for (size_t i = 0; i < s->n; i++) {
        if (!keep[i])
            continue;
        t->x[k] = s->x[i];
        t->y[k] = s->y[i];
        t->z[k] = s->z[i];
        t->r[k] = s->r[i];
        if (exact) {
            t->ex[k] = s->ex[i];
            t->ey[k] = s->ey[i];
            t->ez[k] = s->ez[i];
            t->er[k] = s->er[i];
        }
        t->line[k] = s->line ? s->line[i] : 0;
        if (s->info)
            t->info[k] = s->info[i];
        k++;
    }
    t->allows_zero_radius = s->allows_zero_radius;
    *out = t;
    return VB_OK;
}

int vb_spheres_select(vb_ctx *ctx, const vb_sphere_set *s, const char *expr, vb_sphere_set **out)
{
    *out = NULL;
    vb_select *sel;
    int rc = vb_select_parse(ctx, expr, &sel);
    if (rc != VB_OK)
        return rc;
    uint8_t *keep = malloc(s->n ? s->n : 1);
    if (!keep) {
        vb_select_free(sel);
        return vb_error(ctx, VB_ENOMEM, s->source, 0, "out of memory selecting spheres");
    }
    size_t n = 0;
    for (size_t i = 0; i < s->n; i++)
        n += keep[i] = (uint8_t)vb_select_match(sel, s->info ? &s->info[i] : NULL);
    vb_select_free(sel);
    if (n == 0)
        rc = vb_error(ctx, VB_EINPUT_SELECT, s->source, 0,
                      "--select \"%s\" selects none of the %zu spheres%s", expr, s->n,
                      s->info ? "" : " (the input has no atom records)");
    else
        rc = vb_spheres_subset(ctx, s, keep, out);
    free(keep);
    return rc;
}
