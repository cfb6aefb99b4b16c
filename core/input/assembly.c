/* mmCIF biological assemblies (--assembly N): the copies of the asymmetric
 * unit that _pdbx_struct_assembly_gen lists - per row an operator
 * expression and the label_asym_id chains it applies to - with the
 * rotation and translation of _pdbx_struct_oper_list.
 *
 * Expressions: "1,2,5", ranges "1-60", and products "(1-5)(6-10)": every
 * operator of the first group after every one of the second (x' =
 * A (B x + b) + a, the rightmost applied first), as the PDBx dictionary
 * defines them.
 *
 * Exactly: the matrices and vectors are decimals, the coordinates too, and
 * a product or sum of decimals is a decimal with more digits - computed in
 * GMP integers and kept exact, never through a double. A coordinate of a
 * copy that needs more than the 18 significant digits of vb_decimal is
 * refused (E107) naming the operator and the atom, rather than rounded. */
#include "vbi_cif.h"
#include "vbi_input.h"
#include "vb_diag.h"

#include <gmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* An exact decimal of any length: m * 10^e. */
typedef struct {
    mpz_t m;
    long e;
} xdec;

typedef struct {
    char id[16];
    xdec a[3][3], t[3];
} oper;

static void xdec_init(xdec *x)
{
    mpz_init(x->m);
    x->e = 0;
}

static void xdec_set_vb(xdec *x, vb_decimal d)
{
    mpz_set_si(x->m, (long)d.mant);
    x->e = d.exp10;
}

/* r = a * b (r may not alias). */
static void xdec_mul(xdec *r, const xdec *a, const xdec *b)
{
    mpz_mul(r->m, a->m, b->m);
    r->e = a->e + b->e;
}

/* r += a, aligning to the smaller exponent (tmp: scratch). */
static void xdec_add(xdec *r, const xdec *a, mpz_t tmp)
{
    if (mpz_sgn(a->m) == 0)
        return;
    if (mpz_sgn(r->m) == 0) {
        mpz_set(r->m, a->m);
        r->e = a->e;
        return;
    }
    if (a->e < r->e) {
        mpz_ui_pow_ui(tmp, 10, (unsigned long)(r->e - a->e));
        mpz_mul(r->m, r->m, tmp);
        r->e = a->e;
        mpz_add(r->m, r->m, a->m);
    } else {
        mpz_ui_pow_ui(tmp, 10, (unsigned long)(a->e - r->e));
        mpz_addmul(r->m, a->m, tmp);
    }
}

static void oper_init(oper *o)
{
    for (int i = 0; i < 3; i++) {
        xdec_init(&o->t[i]);
        for (int j = 0; j < 3; j++)
            xdec_init(&o->a[i][j]);
    }
}

static void oper_clear(oper *o)
{
    for (int i = 0; i < 3; i++) {
        mpz_clear(o->t[i].m);
        for (int j = 0; j < 3; j++)
            mpz_clear(o->a[i][j].m);
    }
}

/* r = p after q: r.a = p.a q.a, r.t = p.a q.t + p.t. */
static void oper_compose(oper *r, const oper *p, const oper *q)
{
    xdec prod;
    xdec_init(&prod);
    mpz_t tmp;
    mpz_init(tmp);
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            mpz_set_ui(r->a[i][j].m, 0);
            r->a[i][j].e = 0;
            for (int k = 0; k < 3; k++) {
                xdec_mul(&prod, &p->a[i][k], &q->a[k][j]);
                xdec_add(&r->a[i][j], &prod, tmp);
            }
        }
        mpz_set(r->t[i].m, p->t[i].m);
        r->t[i].e = p->t[i].e;
        for (int k = 0; k < 3; k++) {
            xdec_mul(&prod, &p->a[i][k], &q->t[k]);
            xdec_add(&r->t[i], &prod, tmp);
        }
    }
    snprintf(r->id, sizeof r->id, "%.7sx%.7s", p->id, q->id);
    mpz_clear(prod.m);
    mpz_clear(tmp);
}

/* The exact decimal as a vb_decimal and its nearest double; -1 when it
 * needs more than 18 significant digits (*digits gets how many). */
static int xdec_to_vb(xdec *x, vb_decimal *out, double *d, size_t *digits, mpz_t tmp)
{
    if (mpz_sgn(x->m) == 0) {
        out->mant = 0;
        out->exp10 = 0;
        *d = 0.0;
        return 0;
    }
    mpz_set_ui(tmp, 10);
    x->e += (long)mpz_remove(x->m, x->m, tmp);
    *digits = mpz_sizeinbase(x->m, 10);
    /* sizeinbase may be one too large: 10^18 - 1 has 18 digits. */
    mpz_ui_pow_ui(tmp, 10, 18);
    if (mpz_cmpabs(x->m, tmp) >= 0)
        return -1;
    if (x->e > 340 || x->e < -360)
        return -1;
    out->mant = (int64_t)mpz_get_si(x->m);
    out->exp10 = (int32_t)x->e;
    char buf[64];
    snprintf(buf, sizeof buf, "%lldE%d", (long long)out->mant, (int)out->exp10);
    *d = strtod(buf, NULL);
    return 0;
}

static const char *const oper_items[] = {
    "id",           "matrix[1][1]", "matrix[1][2]", "matrix[1][3]", "vector[1]",
    "matrix[2][1]", "matrix[2][2]", "matrix[2][3]", "vector[2]",    "matrix[3][1]",
    "matrix[3][2]", "matrix[3][3]", "vector[3]"};
static const char *const gen_items[] = {"assembly_id", "oper_expression", "asym_id_list"};

typedef struct {
    vb_ctx *ctx;
    const char *name;
    oper *ops;  /* the file's operators */
    size_t nops;
} assembly;

static int cell_is(const vbi_cif_token *t, const char *s)
{
    return t->kind == VBI_CIF_VALUE && t->len == strlen(s) && memcmp(t->text, s, t->len) == 0;
}

static int read_operators(assembly *A, const char *buf, size_t len)
{
    vbi_cif_table tab;
    int r = vbi_cif_table_read(buf, len, "_pdbx_struct_oper_list", oper_items, 13, &tab);
    int rc = VB_OK;
    if (r == -2)
        rc = vb_error(A->ctx, VB_ENOMEM, A->name, 0, "out of memory");
    else if (r != 0)
        rc = vb_error(A->ctx, VB_EINPUT_ASSEMBLY, A->name, r < 0 ? tab.error_line : 0,
                      r < 0 ? "malformed _pdbx_struct_oper_list" : "no _pdbx_struct_oper_list");
    if (rc == VB_OK && !(A->ops = calloc(tab.rows, sizeof *A->ops)))
        rc = vb_error(A->ctx, VB_ENOMEM, A->name, 0, "out of memory");
    for (size_t row = 0; rc == VB_OK && row < tab.rows; row++) {
        const vbi_cif_token *c = &tab.cell[row * 13];
        oper *o = &A->ops[A->nops++];
        oper_init(o);
        if (c[0].kind != VBI_CIF_VALUE || c[0].len >= sizeof o->id) {
            rc = vb_error(A->ctx, VB_EINPUT_ASSEMBLY, A->name, c[0].line,
                          "_pdbx_struct_oper_list row without a usable id");
            break;
        }
        memcpy(o->id, c[0].text, c[0].len);
        for (int k = 1; k < 13 && rc == VB_OK; k++) {
            int i = (k - 1) / 4, j = (k - 1) % 4;
            vb_decimal d;
            double dd;
            if (c[k].kind != VBI_CIF_VALUE) {
                rc = vb_error(A->ctx, VB_EINPUT_ASSEMBLY, A->name, c[0].line,
                              "operator %s has no %s", o->id, oper_items[k]);
                break;
            }
            rc = vbi_parse_number(A->ctx, A->name, c[k].line, oper_items[k], c[k].text, c[k].len,
                                  &d, &dd);
            if (rc == VB_OK)
                xdec_set_vb(j == 3 ? &o->t[i] : &o->a[i][j], d);
        }
    }
    vbi_cif_table_free(&tab);
    return rc;
}

static const oper *find_oper(const assembly *A, const char *id, size_t n)
{
    for (size_t k = 0; k < A->nops; k++)
        if (strlen(A->ops[k].id) == n && memcmp(A->ops[k].id, id, n) == 0)
            return &A->ops[k];
    return NULL;
}

/* One group's list "1,3-5,P" into ops (at most cap); returns the count, or
 * -1 when an id is unknown or a range is not numeric (message set). */
static long parse_list(assembly *A, long line, const char *s, size_t n, const oper **ops,
                       size_t cap)
{
    size_t count = 0, i = 0;
    while (i < n) {
        size_t j = i;
        while (j < n && s[j] != ',')
            j++;
        const char *dash = memchr(s + i, '-', j - i);
        if (dash) {
            char a[16], b[16];
            size_t la = (size_t)(dash - s - (long)i), lb = j - (size_t)(dash - s) - 1;
            long lo, hi;
            char *end;
            if (la == 0 || lb == 0 || la >= sizeof a || lb >= sizeof b) {
                vb_error(A->ctx, VB_EINPUT_ASSEMBLY, A->name, line, "bad operator range '%.*s'",
                         (int)(j - i), s + i);
                return -1;
            }
            memcpy(a, s + i, la), a[la] = '\0';
            memcpy(b, dash + 1, lb), b[lb] = '\0';
            lo = strtol(a, &end, 10);
            int bad = *end != '\0';
            hi = strtol(b, &end, 10);
            if (bad || *end != '\0' || hi < lo || hi - lo > 100000) {
                vb_error(A->ctx, VB_EINPUT_ASSEMBLY, A->name, line,
                         "operator range '%.*s' is not numeric and increasing", (int)(j - i),
                         s + i);
                return -1;
            }
            for (long v = lo; v <= hi; v++) {
                char id[24];
                int k = snprintf(id, sizeof id, "%ld", v);
                const oper *o = find_oper(A, id, (size_t)k);
                if (!o) {
                    vb_error(A->ctx, VB_EINPUT_ASSEMBLY, A->name, line,
                             "operator %s is not in _pdbx_struct_oper_list", id);
                    return -1;
                }
                if (count == cap) {
                    vb_error(A->ctx, VB_EINPUT_ASSEMBLY, A->name, line, "too many operators");
                    return -1;
                }
                ops[count++] = o;
            }
        } else {
            const oper *o = find_oper(A, s + i, j - i);
            if (!o) {
                vb_error(A->ctx, VB_EINPUT_ASSEMBLY, A->name, line,
                         "operator '%.*s' is not in _pdbx_struct_oper_list", (int)(j - i), s + i);
                return -1;
            }
            if (count == cap) {
                vb_error(A->ctx, VB_EINPUT_ASSEMBLY, A->name, line, "too many operators");
                return -1;
            }
            ops[count++] = o;
        }
        i = j + 1;
    }
    return (long)count;
}

/* Operators at most in one expression (a capsid has 60; products more). */
#define VBI_MAX_OPERS 100000

/* The operators of an expression, composed: *out (caller frees with
 * oper_clear each, then free). Returns the count, or -1 (message set). */
static long expand(assembly *A, const vbi_cif_token *expr, oper **out)
{
    *out = NULL;
    const char *s = expr->text;
    size_t n = expr->len;
    /* Groups: "(...)(...)" or one bare list. */
    const oper **groups[8];
    long sizes[8];
    int ng = 0;
    long total = 1, rc = 0;
    size_t i = 0;
    while (rc >= 0 && i < n) {
        size_t a = i, b;
        if (s[i] == '(') {
            const char *close = memchr(s + i, ')', n - i);
            if (!close) {
                rc = -1;
                vb_error(A->ctx, VB_EINPUT_ASSEMBLY, A->name, expr->line,
                         "unbalanced '(' in operator expression '%.*s'", (int)n, s);
                break;
            }
            a = i + 1;
            b = (size_t)(close - s);
            i = b + 1;
        } else if (ng == 0) {
            b = n;
            i = n;
        } else {
            rc = -1;
            vb_error(A->ctx, VB_EINPUT_ASSEMBLY, A->name, expr->line,
                     "operator expression '%.*s' is not lists in parentheses", (int)n, s);
            break;
        }
        if (ng == 8 || !(groups[ng] = malloc(VBI_MAX_OPERS * sizeof *groups[ng]))) {
            rc = -1;
            vb_error(A->ctx, ng == 8 ? VB_EINPUT_ASSEMBLY : VB_ENOMEM, A->name, expr->line,
                     ng == 8 ? "more than 8 groups in an operator expression" : "out of memory");
            break;
        }
        sizes[ng] = parse_list(A, expr->line, s + a, b - a, groups[ng], VBI_MAX_OPERS);
        if (sizes[ng] <= 0) {
            if (sizes[ng] == 0)
                vb_error(A->ctx, VB_EINPUT_ASSEMBLY, A->name, expr->line,
                         "empty operator list in '%.*s'", (int)n, s);
            rc = -1;
            ng++;
            break;
        }
        total *= sizes[ng];
        ng++;
        if (total > VBI_MAX_OPERS) {
            rc = -1;
            vb_error(A->ctx, VB_EINPUT_ASSEMBLY, A->name, expr->line,
                     "operator expression '%.*s' makes more than %d copies", (int)n, s,
                     VBI_MAX_OPERS);
        }
    }
    oper *ops = NULL;
    if (rc == 0 && ng == 0) {
        rc = -1;
        vb_error(A->ctx, VB_EINPUT_ASSEMBLY, A->name, expr->line, "empty operator expression");
    }
    if (rc == 0 && !(ops = calloc((size_t)total, sizeof *ops))) {
        rc = -1;
        vb_error(A->ctx, VB_ENOMEM, A->name, 0, "out of memory");
    }
    /* Index c in mixed radix over the groups, the last group fastest. */
    for (long c = 0; rc == 0 && c < total; c++) {
        long idx[8], v = c;
        for (int g = ng - 1; g >= 0; g--) {
            idx[g] = v % sizes[g];
            v /= sizes[g];
        }
        /* acc = the last group's operator, then each group's before it. */
        const oper *last = groups[ng - 1][idx[ng - 1]];
        oper acc, tmp;
        oper_init(&acc);
        oper_init(&tmp);
        for (int r = 0; r < 3; r++) {
            mpz_set(acc.t[r].m, last->t[r].m);
            acc.t[r].e = last->t[r].e;
            for (int q = 0; q < 3; q++) {
                mpz_set(acc.a[r][q].m, last->a[r][q].m);
                acc.a[r][q].e = last->a[r][q].e;
            }
        }
        snprintf(acc.id, sizeof acc.id, "%s", last->id);
        for (int g = ng - 2; g >= 0; g--) {
            oper_compose(&tmp, groups[g][idx[g]], &acc);
            oper t = acc;
            acc = tmp;
            tmp = t;
        }
        ops[c] = acc;
        oper_clear(&tmp);
    }
    for (int g = 0; g < ng; g++)
        free(groups[g]);
    if (rc < 0) {
        free(ops);
        return -1;
    }
    *out = ops;
    return total;
}

/* Whether chain `asym` is in the comma-separated list. */
static int in_asym_list(const vbi_cif_token *list, const char *asym)
{
    size_t n = strlen(asym), i = 0;
    while (i < list->len) {
        size_t j = i;
        while (j < list->len && list->text[j] != ',')
            j++;
        size_t a = i, b = j;
        while (a < b && list->text[a] == ' ')
            a++;
        while (b > a && list->text[b - 1] == ' ')
            b--;
        if (b - a == n && memcmp(list->text + a, asym, n) == 0)
            return 1;
        i = j + 1;
    }
    return 0;
}

/* Appends the copy of atom i of src under o to b. */
static int push_copy(assembly *A, vbi_builder *b, const vb_sphere_set *src, size_t i,
                     const oper *o, xdec *x, xdec *prod, xdec *acc, mpz_t tmp)
{
    vb_decimal e[4];
    double d[4];
    for (int k = 0; k < 3; k++) {
        mpz_set(acc->m, o->t[k].m);
        acc->e = o->t[k].e;
        const vb_decimal c[3] = {src->ex[i], src->ey[i], src->ez[i]};
        for (int j = 0; j < 3; j++) {
            if (mpz_sgn(o->a[k][j].m) == 0 || c[j].mant == 0)
                continue;
            xdec_set_vb(x, c[j]);
            xdec_mul(prod, &o->a[k][j], x);
            xdec_add(acc, prod, tmp);
        }
        size_t digits = 0;
        if (xdec_to_vb(acc, &e[k], &d[k], &digits, tmp) != 0)
            return vb_error(A->ctx, VB_EINPUT_MAGNITUDE, A->name, src->line[i],
                            "assembly operator %s moves this atom's %c coordinate to a decimal of "
                            "%zu significant digits: more than the 18 of vorball's exact "
                            "decimals (refused rather than rounded)",
                            o->id, "xyz"[k], digits);
    }
    e[3] = src->er[i];
    d[3] = src->r[i];
    return vbi_builder_push(b, e, d, src->info ? &src->info[i] : NULL, src->line[i]);
}

int vbi_assembly_build(vb_ctx *ctx, const char *name, const char *buf, size_t len, int id,
                       const char (*asym)[8], size_t max, vb_sphere_set **set)
{
    assembly A = {ctx, name, NULL, 0};
    vbi_cif_table gen;
    int r = vbi_cif_table_read(buf, len, "_pdbx_struct_assembly_gen", gen_items, 3, &gen);
    int rc = VB_OK;
    if (r == -2)
        rc = vb_error(ctx, VB_ENOMEM, name, 0, "out of memory");
    else if (r != 0)
        rc = vb_error(ctx, VB_EINPUT_ASSEMBLY, name, r < 0 ? gen.error_line : 0,
                      r < 0 ? "malformed _pdbx_struct_assembly_gen"
                            : "no _pdbx_struct_assembly_gen: the file lists no assembly");
    char want[16];
    snprintf(want, sizeof want, "%d", id);
    size_t rows = 0;
    for (size_t row = 0; rc == VB_OK && row < gen.rows; row++)
        rows += cell_is(&gen.cell[row * 3], want);
    if (rc == VB_OK && rows == 0)
        rc = vb_error(ctx, VB_EINPUT_ASSEMBLY, name, 0,
                      "assembly %d is not in _pdbx_struct_assembly_gen", id);
    if (rc == VB_OK)
        rc = read_operators(&A, buf, len);
    vbi_builder b;
    if (rc == VB_OK)
        rc = vbi_builder_init(&b, ctx, name, max, (*set)->info != NULL);
    int building = rc == VB_OK;
    const vb_sphere_set *src = *set;
    uint8_t *used = rc == VB_OK ? calloc(src->n ? src->n : 1, 1) : NULL;
    if (rc == VB_OK && !used)
        rc = vb_error(ctx, VB_ENOMEM, name, 0, "out of memory");
    xdec x, prod, acc;
    mpz_t tmp;
    xdec_init(&x);
    xdec_init(&prod);
    xdec_init(&acc);
    mpz_init(tmp);
    size_t copies = 0;
    for (size_t row = 0; rc == VB_OK && row < gen.rows; row++) {
        const vbi_cif_token *c = &gen.cell[row * 3];
        if (!cell_is(&c[0], want))
            continue;
        if (c[1].kind != VBI_CIF_VALUE || c[2].kind != VBI_CIF_VALUE) {
            rc = vb_error(ctx, VB_EINPUT_ASSEMBLY, name, c[0].line,
                          "assembly %d: a row without oper_expression or asym_id_list", id);
            break;
        }
        oper *ops = NULL;
        long nops = expand(&A, &c[1], &ops);
        if (nops < 0) {
            rc = vb_errcode(ctx);
            break;
        }
        for (long k = 0; rc == VB_OK && k < nops; k++)
            for (size_t i = 0; rc == VB_OK && i < src->n; i++)
                if (in_asym_list(&c[2], asym[i])) {
                    used[i] = 1;
                    rc = push_copy(&A, &b, src, i, &ops[k], &x, &prod, &acc, tmp);
                }
        copies += (size_t)nops;
        for (long k = 0; k < nops; k++)
            oper_clear(&ops[k]);
        free(ops);
    }
    size_t left = 0;
    for (size_t i = 0; rc == VB_OK && i < src->n; i++)
        left += !used[i];
    mpz_clear(x.m);
    mpz_clear(prod.m);
    mpz_clear(acc.m);
    mpz_clear(tmp);
    free(used);
    for (size_t k = 0; k < A.nops; k++)
        oper_clear(&A.ops[k]);
    free(A.ops);
    vbi_cif_table_free(&gen);
    if (rc != VB_OK) {
        if (building)
            vbi_builder_discard(&b);
        return rc;
    }
    vb_sphere_set *out;
    vbi_builder_finish(&b, 1, &out);
    out->allows_zero_radius = src->allows_zero_radius;
    if (left)
        vb_warn(ctx, VB_W_ASSEMBLY_CHAINS, name, 0,
                "assembly %d: %zu atom%s of chains outside its asym_id_list left out", id, left,
                left == 1 ? "" : "s");
    vb_info(ctx, "assembly %d: %zu operators, %zu atoms from %zu", id, copies, out->n, src->n);
    vb_spheres_free(*set);
    *set = out;
    return VB_OK;
}
