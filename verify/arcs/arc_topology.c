/* The exact topology of a closed vertex list (vb_arc_topology): edges the
 * traced arcs, faces the sphere pairs that share a face at a vertex.
 *
 * Faces at a vertex p of tangent radius t. Near p the distance to sphere m
 * is t + u_m . h to first order (u_m the unit vector from p towards c_m
 * reversed: u_m = (p - c_m) / (t + R_m)), so the local cells are the
 * normal fan of the convex hull of the u_m: members i, j share a face at p
 * exactly when u_i u_j is an edge of that hull (the edges of the diagram at
 * p are its facets). The u_m lie on the unit sphere, so all are hull
 * vertices and no three are collinear. The side of u_l of the plane through
 * u_i, u_j, u_k is the sign of det[u_m, 1] over m = i, j, k, l, which is
 * (times the positive prod 1 / (t + R_m)) the sign of det[(p, t) - b_m]
 * with b_m = (c_m, -R_m): multilinear in the rows and with the row (p, t)
 * repeated in no term that survives, it is linear in (p, t), so one number
 * of Z[sqrt(delta)] at the exact vertex decides it. */
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_arc.h"
#include "vbx_arc.h"

typedef struct fwork {
    vbx_arcw w;
    mpz_t b[64][4];  /* -b_m in a's frame: (c_a - c_m, R_m - R_a) scaled */
    mpz_t m[4][4], s[8];
    vbx_zs val;
    vbx_xpt x;
    int8_t *memo;    /* nm^4 signs, 2 = not yet */
    size_t nm;
} fwork;

/* det of the 3x3 minor of m (4x4) without row r and column c. */
static void det3(fwork *fw, int r, int c, mpz_t out)
{
    int R[3], C[3], nr = 0, nc = 0;
    for (int i = 0; i < 4; i++) {
        if (i != r)
            R[nr++] = i;
        if (i != c)
            C[nc++] = i;
    }
    mpz_t *t = fw->s;
    mpz_set_ui(out, 0);
    for (int a = 0; a < 3; a++) {
        int b = (a + 1) % 3, d = (a + 2) % 3;
        mpz_mul(t[0], fw->m[R[1]][C[b]], fw->m[R[2]][C[d]]);
        mpz_submul(t[0], fw->m[R[1]][C[d]], fw->m[R[2]][C[b]]);
        mpz_addmul(out, fw->m[R[0]][C[a]], t[0]);
    }
}

static void det4(fwork *fw, mpz_t out)
{
    mpz_set_ui(out, 0);
    for (int c = 0; c < 4; c++) {
        det3(fw, 0, c, fw->s[1]);
        if (c & 1)
            mpz_submul(out, fw->m[0][c], fw->s[1]);
        else
            mpz_addmul(out, fw->m[0][c], fw->s[1]);
    }
}

/* Side of u_l of the plane through u_i, u_j, u_k (member indices): the sign
 * of den det(M) + sum_col U_col det(M, column col := 1), M the rows -b_m. */
static int side(fwork *fw, size_t i, size_t j, size_t k, size_t l)
{
    size_t n = fw->nm, key = ((i * n + j) * n + k) * n + l;
    if (fw->memo[key] != 2)
        return fw->memo[key];
    const size_t q[4] = {i, j, k, l};
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            mpz_set(fw->m[r][c], fw->b[q[r]][c]);
    det4(fw, fw->s[2]);
    mpz_mul(fw->val.a, fw->s[2], fw->x.den);
    mpz_set_ui(fw->val.b, 0);
    for (int c = 0; c < 4; c++) {
        for (int r = 0; r < 4; r++)
            mpz_set_ui(fw->m[r][c], 1);
        det4(fw, fw->s[2]);
        vbx_zs_addmul_z(&fw->val, &fw->x.U[c], fw->s[2]);
        for (int r = 0; r < 4; r++)
            mpz_set(fw->m[r][c], fw->b[q[r]][c]);
    }
    int s = vbx_zs_sign(&fw->val, fw->x.d, fw->s[3], fw->s[4]);
    fw->memo[key] = (int8_t)s;
    return s;
}

/* 1 when members i, j of the vertex share a face there, 0 when not, -1
 * when a sign cannot place it (three directions on a line). */
static int hull_edge(fwork *fw, size_t i, size_t j)
{
    size_t n = fw->nm;
    for (size_t k = 0; k < n; k++) {
        if (k == i || k == j)
            continue;
        int pos = 0, neg = 0;
        size_t off = SIZE_MAX;
        for (size_t l = 0; l < n && !(pos && neg); l++) {
            if (l == i || l == j || l == k)
                continue;
            int s = side(fw, i, j, k, l);
            pos += s > 0;
            neg += s < 0;
            if (s && off == SIZE_MAX)
                off = l;
        }
        if ((pos && neg) || off == SIZE_MAX)
            continue;
        /* The plane of i, j, k supports the hull: the facet holds i, j and
         * the members on it; i j is one of its edges exactly when they all
         * lie on k's side of the line i j (seen from the point off it). */
        int sk = side(fw, i, j, k, off);
        for (size_t l = 0; l < n; l++) {
            if (l == i || l == j || l == k || side(fw, i, j, k, l) != 0)
                continue;
            int sl = side(fw, i, j, l, off);
            if (sl == 0)
                return -1;
            if (sl != sk)
                return 0;
        }
        return 1;
    }
    return 0;
}

static int push_pair(uint32_t **v, size_t *n, size_t *cap, uint32_t a, uint32_t b)
{
    *v = vb_array_grow(*v, cap, *n + 1, 2 * sizeof **v, 1024);
    if (*cap < *n + 1)
        return VB_ENOMEM;
    (*v)[2 * *n] = a < b ? a : b;
    (*v)[2 * *n + 1] = a < b ? b : a;
    (*n)++;
    return VB_OK;
}

static int pair_cmp(const void *pa, const void *pb)
{
    const uint32_t *a = pa, *b = pb;
    if (a[0] != b[0])
        return a[0] < b[0] ? -1 : 1;
    return (a[1] > b[1]) - (a[1] < b[1]);
}

/* The exact point of vertex k (members m, nm) in the frame of one of its
 * triples: 1, or 0 when no triple identifies it. */
static int vertex_point(fwork *fw, vbx_tframe *f, const uint32_t *m, size_t nm,
                        const double p[4])
{
    for (size_t a = 0; a < nm; a++)
        for (size_t b = a + 1; b < nm; b++)
            for (size_t c = b + 1; c < nm; c++) {
                const uint32_t t[3] = {m[a], m[b], m[c]};
                vbx_tframe_clear(f);
                vbx_tframe_init(f);
                if (vbx_tframe_setup(&fw->w, f, t) != VB_OK)
                    return -1;
                if (f->kind == VBX_TRI_NONE)
                    continue;
                if (vbx_xpt_of_vertex(&fw->w, f, m, nm, p, &fw->x))
                    return 1;
            }
    return 0;
}

/* The face pairs of vertex k into pairs; *bad when its point or a sign
 * could not be had (then nothing is added). */
static int vertex_faces(fwork *fw, const vb_vertex_list *v, size_t k, uint32_t **pairs,
                        size_t *np, size_t *cap, int *bad)
{
    const uint32_t *m = v->ids + v->start[k];
    size_t nm = v->start[k + 1] - v->start[k];
    int rc = VB_OK;
    *bad = 0;
    if (nm == 4) {
        for (size_t a = 0; a < 4 && rc == VB_OK; a++)
            for (size_t b = a + 1; b < 4 && rc == VB_OK; b++)
                rc = push_pair(pairs, np, cap, m[a], m[b]);
        return rc;
    }
    if (nm < 4 || nm > 64) {
        *bad = 1;
        return VB_OK;
    }
    const double p[4] = {v->x[k], v->y[k], v->z[k], v->t[k]};
    vbx_tframe f;
    vbx_tframe_init(&f);
    int got = vertex_point(fw, &f, m, nm, p);
    if (got <= 0) {
        vbx_tframe_clear(&f);
        *bad = 1;
        return got < 0 ? VB_ENOMEM : VB_OK;
    }
    const vbx_data *d = &fw->w.c->d;
    uint32_t base = f.t[0];
    for (size_t i = 0; i < nm; i++) {
        for (int c = 0; c < 3; c++)
            mpz_sub(fw->b[i][c], d->c[4 * (size_t)base + c], d->c[4 * (size_t)m[i] + c]);
        mpz_sub(fw->b[i][3], d->c[4 * (size_t)m[i] + 3], d->c[4 * (size_t)base + 3]);
    }
    vbx_tframe_clear(&f);
    size_t n4 = nm * nm * nm * nm;
    fw->memo = malloc(n4);
    if (!fw->memo)
        return VB_ENOMEM;
    memset(fw->memo, 2, n4);
    fw->nm = nm;
    size_t np0 = *np;
    for (size_t i = 0; i < nm && rc == VB_OK && !*bad; i++)
        for (size_t j = i + 1; j < nm && rc == VB_OK && !*bad; j++) {
            int e = hull_edge(fw, i, j);
            if (e < 0)
                *bad = 1;
            else if (e)
                rc = push_pair(pairs, np, cap, m[i], m[j]);
        }
    if (*bad)
        *np = np0;
    free(fw->memo);
    fw->memo = NULL;
    return rc;
}

int vb_arc_topology(vb_ctx *ctx, const vb_sphere_set *set, const vb_vertex_list *list,
                    vb_topology_edge *edges, size_t nedges, const vb_arc_report *r,
                    vb_topology *out)
{
    vb_topology_init(out);
    out->exact = 1;
    out->edges = edges;
    out->nedges = out->edges_cap = nedges;
    out->undecided = r->undecided;
    fwork fw;
    memset(&fw, 0, sizeof fw);
    vb_certifier *c = NULL;
    uint32_t *pairs = NULL;
    uint8_t *bad = calloc(list->n ? list->n : 1, 1);
    size_t np = 0, cap = 0;
    int rc = bad ? vb_certifier_open(ctx, set, &c) : VB_ENOMEM;
    int have_w = 0;
    if (rc == VB_OK) {
        rc = vbx_arcw_init(&fw.w, ctx, c);
        have_w = 1;
    }
    if (rc == VB_OK) {
        for (int i = 0; i < 64; i++)
            for (int k = 0; k < 4; k++)
                mpz_init(fw.b[i][k]);
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 4; k++)
                mpz_init(fw.m[i][k]);
        for (int i = 0; i < 8; i++)
            mpz_init(fw.s[i]);
        vbx_zs_init(&fw.val);
        vbx_xpt_init(&fw.x);
        for (size_t k = 0; k < list->n && rc == VB_OK; k++) {
            int b = 0;
            rc = vertex_faces(&fw, list, k, &pairs, &np, &cap, &b);
            bad[k] = (uint8_t)b;
            out->unresolved += (size_t)b;
        }
        /* A vertex without an exact answer: the pairs of its edges' triples. */
        for (size_t e = 0; e < nedges && rc == VB_OK; e++) {
            const vb_topology_edge *g = &edges[e];
            if (!bad[g->v[0]] && (g->v[1] < 0 || !bad[g->v[1]]))
                continue;
            const uint32_t *t = g->spheres;
            rc = push_pair(&pairs, &np, &cap, t[0], t[1]);
            if (rc == VB_OK)
                rc = push_pair(&pairs, &np, &cap, t[0], t[2]);
            if (rc == VB_OK)
                rc = push_pair(&pairs, &np, &cap, t[1], t[2]);
        }
        for (int i = 0; i < 64; i++)
            for (int k = 0; k < 4; k++)
                mpz_clear(fw.b[i][k]);
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 4; k++)
                mpz_clear(fw.m[i][k]);
        for (int i = 0; i < 8; i++)
            mpz_clear(fw.s[i]);
        vbx_zs_clear(&fw.val);
        vbx_xpt_clear(&fw.x);
    }
    if (have_w)
        vbx_arcw_free(&fw.w);
    vb_certifier_close(c);
    free(bad);
    if (rc == VB_OK && np) {
        qsort(pairs, np, 2 * sizeof *pairs, pair_cmp);
        size_t u = 0;
        for (size_t i = 0; i < np; i++)
            if (!u || pair_cmp(pairs + 2 * i, pairs + 2 * (u - 1)) != 0) {
                pairs[2 * u] = pairs[2 * i];
                pairs[2 * u + 1] = pairs[2 * i + 1];
                u++;
            }
        np = u;
    }
    out->faces = pairs;
    out->nfaces = np;
    if (rc != VB_OK) {
        vb_topology_free(out);
        if (rc == VB_ENOMEM)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (topology)");
    }
    return rc;
}
