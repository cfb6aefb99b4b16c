/* Periodic vertex files read back (tsv as periodic_write.c writes it), and
 * their vertices named by the spheres of an image set, for the verifier. */
#include "vb_periodic.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "vbi_input.h"

void vb_periodic_vertices_free(vb_periodic_vertices *v)
{
    free(v->start);
    free(v->m);
    free(v->x);
    free(v->y);
    free(v->z);
    free(v->t);
    memset(v, 0, sizeof *v);
}

/* Room for one more vertex of m members. */
static int grow(vb_periodic_vertices *v, size_t *cap, size_t *mcap, size_t m)
{
    if (v->n + 1 >= *cap) {
        size_t c = *cap ? 2 * *cap : 64;
        size_t *st = realloc(v->start, (c + 1) * sizeof *st);
        if (st)
            v->start = st;
        double *p[4] = {realloc(v->x, c * sizeof(double)), NULL, NULL, NULL};
        if (p[0])
            v->x = p[0];
        p[1] = realloc(v->y, c * sizeof(double));
        if (p[1])
            v->y = p[1];
        p[2] = realloc(v->z, c * sizeof(double));
        if (p[2])
            v->z = p[2];
        p[3] = realloc(v->t, c * sizeof(double));
        if (p[3])
            v->t = p[3];
        if (!st || !p[0] || !p[1] || !p[2] || !p[3])
            return VB_ENOMEM;
        *cap = c;
    }
    size_t used = v->n ? v->start[v->n] : 0;
    if (used + m > *mcap) {
        size_t c = (used + m) * 2;
        vb_periodic_member *q = realloc(v->m, c * sizeof *q);
        if (!q)
            return VB_ENOMEM;
        v->m = q;
        *mcap = c;
    }
    return VB_OK;
}

/* One member "i@(dx,dy,dz)" at *p; *p moves past it. 0 or -1. */
static int member(const char **p, const char *end, vb_periodic_member *out)
{
    char *e;
    errno = 0;
    unsigned long id = strtoul(*p, &e, 10);
    if (e == *p || errno || id > UINT32_MAX || e + 2 > end || e[0] != '@' || e[1] != '(')
        return -1;
    const char *q = e + 2;
    for (int k = 0; k < 3; k++) {
        long s = strtol(q, &e, 10);
        if (e == q || s < INT16_MIN || s > INT16_MAX || e >= end || *e != (k < 2 ? ',' : ')'))
            return -1;
        out->s[k] = (int16_t)s;
        q = e + 1;
    }
    out->id = (uint32_t)id;
    *p = q;
    return 0;
}

int vb_periodic_read(vb_ctx *ctx, const char *path, vb_periodic_vertices *out, long **lines)
{
    memset(out, 0, sizeof *out);
    *lines = NULL;
    char *buf = NULL;
    size_t len = 0, cap = 0, mcap = 0;
    int rc = vbi_slurp(ctx, path, &buf, &len);
    if (rc != VB_OK)
        return rc;
    long lineno = 0, *ln = NULL;
    const char *p = buf, *end = buf + len;
    while (rc == VB_OK && p < end) {
        const char *eol = memchr(p, '\n', (size_t)(end - p));
        eol = eol ? eol : end;
        lineno++;
        const char *q = p;
        p = eol + (eol < end);
        if (q == eol || *q == '#')
            continue;
        /* Members: as many as '@' before the first tab. */
        const char *tab = memchr(q, '\t', (size_t)(eol - q));
        size_t want = 0;
        for (const char *c = q; tab && c < tab; c++)
            want += *c == '@';
        if (grow(out, &cap, &mcap, want) != VB_OK) {
            rc = vb_error(ctx, VB_ENOMEM, path, 0, "out of memory");
            break;
        }
        size_t used = out->n ? out->start[out->n] : 0, m = 0;
        while (m < want && member(&q, eol, &out->m[used + m]) == 0) {
            m++;
            if (q < eol && *q == ',')
                q++;
            else
                break;
        }
        double d[4];
        int ok = m >= 4 && m == want && q == tab;
        for (int k = 0; ok && k < 4; k++) {
            char *e;
            d[k] = strtod(q, &e);
            ok = e != q && (e == eol || *e == '\t' || *e == '\r');
            q = e;
        }
        if (!ok) {
            rc = vb_error(ctx, VB_EINPUT_MALFORMED, path, lineno,
                          "not a periodic vertex line (i@(dx,dy,dz),... x y z t)");
            break;
        }
        long *l2 = realloc(ln, cap * sizeof *l2);
        if (!l2) {
            rc = vb_error(ctx, VB_ENOMEM, path, 0, "out of memory");
            break;
        }
        ln = l2;
        out->start[0] = 0;
        out->start[out->n + 1] = used + m;
        out->x[out->n] = d[0];
        out->y[out->n] = d[1];
        out->z[out->n] = d[2];
        out->t[out->n] = d[3];
        ln[out->n++] = lineno;
    }
    free(buf);
    if (rc == VB_OK && out->n == 0)
        rc = vb_error(ctx, VB_EINPUT_EMPTY, path, 0, "no periodic vertex lines");
    if (rc != VB_OK) {
        vb_periodic_vertices_free(out);
        free(ln);
        return rc;
    }
    *lines = ln;
    return VB_OK;
}

/* (atom, shift) -> sphere of the image set: a sorted index. */
typedef struct key {
    vb_periodic_member m;
    uint32_t sphere;
} key;

static int cmp_key(const void *pa, const void *pb)
{
    return vb_periodic_member_cmp(&((const key *)pa)->m, &((const key *)pb)->m);
}

int vb_periodic_to_images(vb_ctx *ctx, const vb_periodic_images *img,
                          const vb_periodic_vertices *v, vb_vertex_list *out, size_t *row,
                          uint8_t *flags)
{
    size_t n = img->set->n;
    key *k = malloc((n ? n : 1) * sizeof *k);
    if (!k)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    for (size_t i = 0; i < n; i++) {
        k[i].m.id = img->atom[i];
        memcpy(k[i].m.s, img->shift[i], sizeof k[i].m.s);
        k[i].sphere = (uint32_t)i;
    }
    qsort(k, n, sizeof *k, cmp_key);
    size_t widest = 4;
    for (size_t a = 0; a < v->n; a++)
        if (v->start[a + 1] - v->start[a] > widest)
            widest = v->start[a + 1] - v->start[a];
    uint32_t *ids = malloc(widest * sizeof *ids);
    vb_periodic_member *scratch = malloc(2 * widest * sizeof *scratch);
    int rc = ids && scratch ? VB_OK : vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    for (size_t a = 0; rc == VB_OK && a < v->n; a++) {
        size_t m = v->start[a + 1] - v->start[a];
        const vb_periodic_member *mem = v->m + v->start[a];
        flags[a] = 0;
        /* The file's list must be its canonical translate, sorted. */
        for (size_t j = 1; j < m; j++)
            if (vb_periodic_member_cmp(&mem[j - 1], &mem[j]) >= 0)
                flags[a] |= VB_PERIODIC_NOT_CANONICAL;
        if (!flags[a] && !vb_periodic_is_canonical(mem, m, scratch))
            flags[a] |= VB_PERIODIC_NOT_CANONICAL;
        for (size_t j = 0; j < m && !(flags[a] & VB_PERIODIC_BEYOND); j++) {
            key *hit = bsearch(&(key){mem[j], 0}, k, n, sizeof *k, cmp_key);
            if (!hit)
                flags[a] |= VB_PERIODIC_BEYOND;
            else
                ids[j] = hit->sphere;
        }
        /* reach.c: no periodic vertex has t above the bound at its point
         * (less the slack: the file's t and point may be off by it). */
        if (v->t[a] > vb_periodic_bound_at(img, v->x[a], v->y[a], v->z[a]) - img->slack)
            flags[a] |= VB_PERIODIC_BEYOND;
        if (flags[a] & VB_PERIODIC_BEYOND)
            continue;
        row[out->n] = a;
        if (vb_vertex_list_push(out, ids, m, v->x[a], v->y[a], v->z[a], v->t[a], 0.0,
                                VB_VERTEX_CANDIDATE) != VB_OK)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory");
    }
    free(ids);
    free(scratch);
    free(k);
    return rc;
}
