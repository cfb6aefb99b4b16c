/* Arc closure (vb_arc.h): the tracing loop over the vertices, the lookup of
 * the next vertex of each arc, and the counts of the certificate. */
#include <stdlib.h>
#include <string.h>

#include "vb_arc.h"
#include "vbx_arc.h"

/* ---- the set of known vertices: members + rounded point -> index -------- */

typedef struct vtable {
    vb_vertex_list *v;
    size_t *slot; /* index + 1, 0 = empty */
    size_t cap;   /* power of two */
} vtable;

static uint64_t mix(uint64_t h, uint64_t x)
{
    h ^= x + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    return h * 0xff51afd7ed558ccdull;
}

static uint64_t vhash(const uint32_t *m, size_t nm, const double p[4])
{
    uint64_t h = nm;
    for (size_t i = 0; i < nm; i++)
        h = mix(h, m[i]);
    for (int k = 0; k < 4; k++) {
        uint64_t b;
        double x = p[k] == 0 ? 0.0 : p[k];
        memcpy(&b, &x, sizeof b);
        h = mix(h, b);
    }
    return h;
}

static int vsame(const vb_vertex_list *v, size_t k, const uint32_t *m, size_t nm,
                 const double p[4])
{
    size_t s = v->start[k], n = v->start[k + 1] - s;
    return n == nm && memcmp(v->ids + s, m, nm * sizeof *m) == 0 && v->x[k] == p[0] &&
           v->y[k] == p[1] && v->z[k] == p[2] && v->t[k] == p[3];
}

static size_t *vfind(vtable *t, const uint32_t *m, size_t nm, const double p[4])
{
    size_t i = (size_t)vhash(m, nm, p) & (t->cap - 1);
    while (t->slot[i] && !vsame(t->v, t->slot[i] - 1, m, nm, p))
        i = (i + 1) & (t->cap - 1);
    return &t->slot[i];
}

static void vpoint(const vb_vertex_list *v, size_t k, double p[4])
{
    p[0] = v->x[k];
    p[1] = v->y[k];
    p[2] = v->z[k];
    p[3] = v->t[k];
}

static int vgrow(vtable *t)
{
    size_t cap = t->cap ? 2 * t->cap : 64;
    while (cap < 2 * (t->v->n + 1))
        cap *= 2;
    size_t *slot = calloc(cap, sizeof *slot);
    if (!slot)
        return VB_ENOMEM;
    free(t->slot);
    t->slot = slot;
    t->cap = cap;
    for (size_t k = 0; k < t->v->n; k++) {
        double p[4];
        vpoint(t->v, k, p);
        size_t s = t->v->start[k];
        *vfind(t, t->v->ids + s, t->v->start[k + 1] - s, p) = k + 1;
    }
    return VB_OK;
}

/* ---- connected components ------------------------------------------------ */

typedef struct uf {
    size_t *p, cap;
} uf;

static int uf_fit(uf *u, size_t n)
{
    if (n <= u->cap)
        return VB_OK;
    size_t cap = u->cap ? u->cap : 64;
    while (cap < n)
        cap *= 2;
    size_t *p = realloc(u->p, cap * sizeof *p);
    if (!p)
        return VB_ENOMEM;
    for (size_t i = u->cap; i < cap; i++)
        p[i] = i;
    u->p = p;
    u->cap = cap;
    return VB_OK;
}

static size_t uf_root(uf *u, size_t i)
{
    while (u->p[i] != i) {
        u->p[i] = u->p[u->p[i]];
        i = u->p[i];
    }
    return i;
}

/* ---- tracing ------------------------------------------------------------- */

typedef struct closure {
    vb_ctx *ctx;
    vbx_arcw w;
    vb_vertex_list all; /* input + added, in tracing order */
    vtable tab;
    uf comp;
    vb_arc_report *r;
} closure;

/* The next vertex of arc tp of triple frame f: certified, looked up, added
 * when new. from is the index of the arc's start. */
static int arrive(closure *cl, vbx_tframe *f, const vbx_touch *tp, size_t from)
{
    double p[4];
    int ok = vbx_touch_certify(&cl->w, f, tp, p);
    if (ok < 0)
        return vb_errcode(cl->ctx);
    if (ok == 0) {
        /* A sphere cuts the first touching point: the arc was not an edge
         * there; the local test and the search disagree (degenerate). */
        cl->r->undecided++;
        return VB_OK;
    }
    vb_certifier *c = cl->w.c;
    size_t *s = vfind(&cl->tab, c->members, c->nmembers, p);
    size_t k;
    if (*s) {
        k = *s - 1;
    } else {
        k = cl->all.n;
        int rc = vb_vertex_list_push(&cl->all, c->members, c->nmembers, p[0], p[1], p[2], p[3],
                                     0, VB_VERTEX_CERTIFIED);
        if (rc == VB_OK)
            rc = vb_vertex_list_push(&cl->r->added, c->members, c->nmembers, p[0], p[1], p[2],
                                     p[3], 0, VB_VERTEX_CERTIFIED);
        if (rc != VB_OK)
            return rc;
        if (2 * (cl->all.n + 1) > cl->tab.cap) {
            if (vgrow(&cl->tab) != VB_OK)
                return VB_ENOMEM;
        } else {
            *s = k + 1;
        }
    }
    cl->r->closed++;
    if (uf_fit(&cl->comp, cl->all.n) != VB_OK)
        return VB_ENOMEM;
    size_t a = uf_root(&cl->comp, from), b = uf_root(&cl->comp, k);
    if (a != b)
        cl->comp.p[a > b ? a : b] = a < b ? a : b;
    return VB_OK;
}

/* Both arcs of triple t at vertex k. */
static int trace_triple(closure *cl, size_t k, const uint32_t *m, size_t nm, const double p[4],
                        const vbx_ia box[4], const uint32_t t[3])
{
    vbx_arcw *w = &cl->w;
    vbx_tframe f;
    vbx_tframe_init(&f);
    int rc = vbx_tframe_setup(w, &f, t);
    if (rc != VB_OK) {
        vbx_tframe_clear(&f);
        return rc;
    }
    vbx_xpt x;
    vbx_xpt_init(&x);
    int have = 0, fwd = 0, bwd = 0;
    uint64_t extra = 0;
    vbx_touch tp;
    memset(&tp, 0, sizeof tp);
    vbx_xpt_init(&tp.x);
    if (f.kind == VBX_TRI_NONE) {
        goto done;
    }
    rc = vbx_local_arcs(w, &f, m, nm, p, box, &x, &have, &fwd, &bwd, &extra);
    if (rc == VB_EDEGENERATE) {
        cl->r->half_arcs++;
        cl->r->undecided++;
        rc = VB_OK;
        goto done;
    }
    if (rc != VB_OK)
        goto done;
    if (extra) {
        /* Spheres beyond T carry the same curve: trace it for the triple of
         * the three smallest ids only. */
        size_t ix = 0;
        for (size_t i = 0; i < nm; i++) {
            if (m[i] == t[0] || m[i] == t[1] || m[i] == t[2])
                continue;
            if (ix < 64 && (extra >> ix & 1) && m[i] < t[2])
                goto done;
            ix++;
        }
    }
    vbx_arc_end ev = {0}, einf = {0};
    ev.m = m;
    ev.nm = nm;
    ev.xyzt = p;
    ev.x = &x;
    ev.have = &have;
    vbx_key_of_box(w, &f, box, &ev.key);
    einf.inf = 1;
    int open = f.kind == VBX_TRI_OPEN;
    for (int dir = 0; dir < 2 && rc == VB_OK; dir++) {
        if (!(dir == 0 ? fwd : bwd))
            continue;
        cl->r->half_arcs++;
        tp.found = 0;
        tp.have = 0;
        if (dir == 0)
            rc = vbx_arc_search(w, &f, &ev, open ? &einf : &ev, &tp, NULL);
        else
            rc = vbx_arc_search(w, &f, open ? &einf : &ev, &ev, NULL, &tp);
        if (rc == VB_EDEGENERATE) {
            cl->r->undecided++;
            rc = VB_OK;
            continue;
        }
        if (rc != VB_OK)
            break;
        if (!tp.found) {
            if (open)
                cl->r->infinite++;
            else
                cl->r->loops++;
            continue;
        }
        rc = arrive(cl, &f, &tp, k);
    }
done:
    vbx_xpt_clear(&tp.x);
    vbx_xpt_clear(&x);
    vbx_tframe_clear(&f);
    return rc;
}

static int trace_vertex(closure *cl, size_t k)
{
    /* Copy: tracing may grow cl->all. */
    size_t s = cl->all.start[k], nm = cl->all.start[k + 1] - s;
    uint32_t mbuf[64];
    uint32_t *m = nm <= 64 ? mbuf : malloc(nm * sizeof *m);
    if (!m)
        return VB_ENOMEM;
    memcpy(m, cl->all.ids + s, nm * sizeof *m);
    double p[4];
    vpoint(&cl->all, k, p);
    vbx_ia box[4];
    vbx_box_of_rounded(p, box);
    int rc = VB_OK;
    for (size_t a = 0; a < nm && rc == VB_OK; a++)
        for (size_t b = a + 1; b < nm && rc == VB_OK; b++)
            for (size_t c = b + 1; c < nm && rc == VB_OK; c++) {
                uint32_t t[3] = {m[a], m[b], m[c]};
                rc = trace_triple(cl, k, m, nm, p, box, t);
            }
    if (m != mbuf)
        free(m);
    return rc;
}

int vb_arc_close(vb_ctx *ctx, const vb_sphere_set *set, const vb_vertex_list *in,
                 vb_arc_report *out)
{
    memset(out, 0, sizeof *out);
    vb_vertex_list_init(&out->added);
    closure cl;
    memset(&cl, 0, sizeof cl);
    cl.ctx = ctx;
    cl.r = out;
    vb_vertex_list_init(&cl.all);
    vb_certifier *c = NULL;
    int rc = vb_certifier_open(ctx, set, &c);
    if (rc == VB_OK)
        rc = vbx_arcw_init(&cl.w, ctx, c);
    for (size_t k = 0; rc == VB_OK && k < in->n; k++) {
        size_t s = in->start[k];
        rc = vb_vertex_list_push(&cl.all, in->ids + s, in->start[k + 1] - s, in->x[k], in->y[k],
                                 in->z[k], in->t[k], 0, VB_VERTEX_CERTIFIED);
    }
    cl.tab.v = &cl.all;
    if (rc == VB_OK)
        rc = vgrow(&cl.tab);
    if (rc == VB_OK)
        rc = uf_fit(&cl.comp, cl.all.n);
    for (size_t k = 0; rc == VB_OK && k < cl.all.n; k++)
        rc = trace_vertex(&cl, k);
    if (rc == VB_OK) {
        out->vertices = cl.all.n;
        for (size_t k = 0; k < cl.all.n; k++)
            out->components += uf_root(&cl.comp, k) == k;
        out->filter_calls = cl.w.cnt.filter_calls;
        out->filter_failures = cl.w.cnt.filter_failures;
        out->exact_evals = cl.w.cnt.exact_evals;
        out->candidates = cl.w.cnt.candidates;
        rc = vb_vertex_list_sort(&out->added);
    }
    if (c)
        vbx_arcw_free(&cl.w);
    vb_certifier_close(c);
    vb_vertex_list_free(&cl.all);
    free(cl.tab.slot);
    free(cl.comp.p);
    return rc;
}

int vb_arc_report_complete(const vb_arc_report *r)
{
    return r->undecided == 0 && r->added.n == 0;
}

void vb_arc_report_free(vb_arc_report *r)
{
    vb_vertex_list_free(&r->added);
    memset(r, 0, sizeof *r);
    vb_vertex_list_init(&r->added);
}
