/* The vertices of each triple of a vertex list, sorted (vbx_closure.h):
 * where the forward arc of a triple is first searched up to. */
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_parallel.h"

#include "vbx_closure.h"

static int tent_cmp(const void *pa, const void *pb)
{
    const vbx_tent *a = pa, *b = pb;
    for (int i = 0; i < 3; i++)
        if (a->t[i] != b->t[i])
            return a->t[i] < b->t[i] ? -1 : 1;
    return (a->k > b->k) - (a->k < b->k);
}

/* tent_cmp's order as one comparison: the entries of a bucket share t[0],
 * so (t[1], t[2]) as one 64-bit key, then k. */
static int tent_less(const vbx_tent *a, const vbx_tent *b)
{
    uint64_t ka = (uint64_t)a->t[1] << 32 | a->t[2], kb = (uint64_t)b->t[1] << 32 | b->t[2];
    return ka < kb || (ka == kb && a->k < b->k);
}

/* e[lo..end) sorted by tent_less, by insertion. */
static void tent_insertion_sort(vbx_tent *e, size_t lo, size_t end)
{
    for (size_t a = lo + 1; a < end; a++) {
        vbx_tent x = e[a];
        size_t c = a;
        while (c > lo && tent_less(&x, &e[c - 1])) {
            e[c] = e[c - 1];
            c--;
        }
        e[c] = x;
    }
}

/* Entries bigger buckets are merge-sorted with on the stack (more go to
 * qsort). */
enum { TENT_MERGE_MAX = 512 };

/* e[0..n) sorted by tent_less, bottom-up merges of runs of 16 that were
 * insertion-sorted, through tmp (n entries). */
static void tent_merge_sort(vbx_tent *e, size_t n, vbx_tent *tmp)
{
    enum { RUN = 16 };
    for (size_t r = 0; r < n; r += RUN)
        tent_insertion_sort(e, r, r + RUN < n ? r + RUN : n);
    vbx_tent *src = e, *dst = tmp;
    for (size_t w = RUN; w < n; w *= 2) {
        for (size_t lo = 0; lo < n; lo += 2 * w) {
            size_t mid = lo + w < n ? lo + w : n, hi = lo + 2 * w < n ? lo + 2 * w : n;
            size_t i = lo, j = mid, o = lo;
            while (i < mid && j < hi)
                dst[o++] = tent_less(&src[j], &src[i]) ? src[j++] : src[i++];
            while (i < mid)
                dst[o++] = src[i++];
            while (j < hi)
                dst[o++] = src[j++];
        }
        vbx_tent *x = src;
        src = dst;
        dst = x;
    }
    if (src != e)
        memcpy(e, src, n * sizeof *e);
}

/* The entries of bucket i ([off[i], off[i + 1]): one first sphere) sorted
 * in tent_cmp's order (a total order: the same array whichever sort):
 * insertion sort for the few of most spheres, merges on the stack up to
 * TENT_MERGE_MAX (qsort's comparator calls were most of this), qsort
 * beyond. */
typedef struct tbuckets {
    vbx_tent *e;
    const size_t *off;
} tbuckets;

static void sort_bucket(void *arg, size_t i, int tid)
{
    (void)tid;
    const tbuckets *b = arg;
    vbx_tent *e = b->e + b->off[i];
    size_t n = b->off[i + 1] - b->off[i];
    if (n > TENT_MERGE_MAX) {
        qsort(e, n, sizeof *e, tent_cmp);
        return;
    }
    if (n > 32) {
        vbx_tent tmp[TENT_MERGE_MAX];
        tent_merge_sort(e, n, tmp);
        return;
    }
    tent_insertion_sort(e, 0, n);
}

/* The map's build: the vertices cut into nchunk runs; hist[c * top + i]
 * counts the entries of run c with first sphere i, then is run c's write
 * cursor in bucket i. */
typedef struct tbuild {
    const vb_vertex_list *all;
    size_t nchunk, top;
    size_t *hist;
    vbx_tent *out;
} tbuild;

/* Run c of the build: its counts (fill 0: C(nm - 1 - a, 2) triples of
 * vertex k start with its a-th member), or its entries at its cursors in
 * vertex order (fill 1). */
static void build_run(const tbuild *b, size_t c, int fill)
{
    const vb_vertex_list *all = b->all;
    size_t *h = b->hist + c * b->top;
    size_t k0 = all->n * c / b->nchunk, k1 = all->n * (c + 1) / b->nchunk;
    for (size_t k = k0; k < k1; k++) {
        size_t s = all->start[k], nm = all->start[k + 1] - s;
        const uint32_t *id = all->ids + s;
        for (size_t a = 0; a + 2 < nm && !fill; a++)
            h[id[a]] += (nm - 1 - a) * (nm - 2 - a) / 2;
        for (size_t a = 0; a < nm && fill; a++)
            for (size_t bb = a + 1; bb < nm; bb++)
                for (size_t cc = bb + 1; cc < nm; cc++) {
                    vbx_tent *e = &b->out[h[id[a]]++];
                    e->t[0] = id[a];
                    e->t[1] = id[bb];
                    e->t[2] = id[cc];
                    e->k = (uint32_t)k;
                }
    }
}

static void count_run(void *arg, size_t c, int tid)
{
    (void)tid;
    build_run(arg, c, 0);
}

static void fill_run(void *arg, size_t c, int tid)
{
    (void)tid;
    build_run(arg, c, 1);
}

/* Every triple of every vertex of all, bucketed by first sphere (counting
 * runs in parallel, then each run filling its own cursors), each bucket
 * then sorted on its own: tent_cmp is a total order, so the array is the
 * one sorted array on any number of threads. */
int vbx_tmap_update(vbx_tmap *m, const vb_vertex_list *all, unsigned nt)
{
    size_t top = 0, n = 0;
    for (size_t k = 0; k < all->n; k++) {
        size_t s = all->start[k], nm = all->start[k + 1] - s;
        if (nm && all->ids[s + nm - 1] >= top)
            top = (size_t)all->ids[s + nm - 1] + 1;
        n += nm * (nm - 1) * (nm - 2) / 6;
    }
    /* runs: one per thread, fewer where the counts would outweigh the
     * entries (nchunk * top <= n) */
    size_t nchunk = nt ? nt : 1;
    if (top && nchunk > n / top)
        nchunk = n / top ? n / top : 1;
    size_t *off = calloc(top + 1, sizeof *off);
    size_t *hist = calloc(nchunk * (top ? top : 1), sizeof *hist);
    vbx_tent *out = malloc((n ? n : 1) * sizeof *out);
    if (!off || !hist || !out) {
        free(off);
        free(hist);
        free(out);
        m->n = 0;
        m->noff = 0;
        return VB_ENOMEM;
    }
    tbuild b = {all, nchunk, top, hist, out};
    vb_parallel_for(count_run, &b, nchunk, (int)nt);
    size_t at = 0;
    for (size_t i = 0; i < top; i++) {
        off[i] = at;
        for (size_t c = 0; c < nchunk; c++) {
            size_t h = hist[c * top + i];
            hist[c * top + i] = at;
            at += h;
        }
    }
    off[top] = at;
    vb_parallel_for(fill_run, &b, nchunk, (int)nt);
    free(hist);
    tbuckets tb = {out, off};
    vb_parallel_for(sort_bucket, &tb, top, (int)nt);
    free(m->off);
    m->off = off;
    m->noff = top;
    free(m->e);
    m->e = out;
    m->n = n;
    m->cap = n ? n : 1;
    return VB_OK;
}

/* Items of the map: entries cut into runs, each run's triples that start
 * in it (a triple starts at its first entry) counted, then written at the
 * run's offset. */
typedef struct titems {
    const vbx_tmap *m;
    size_t nrun;
    size_t *cnt; /* per run: triples starting in it, then their first item */
    vbx_item *it;
} titems;

static int starts_triple(const vbx_tmap *m, size_t i)
{
    return i == 0 || memcmp(m->e[i].t, m->e[i - 1].t, sizeof m->e[i].t) != 0;
}

static void count_triples(void *arg, size_t r, int tid)
{
    (void)tid;
    titems *x = arg;
    size_t i0 = x->m->n * r / x->nrun, i1 = x->m->n * (r + 1) / x->nrun, c = 0;
    for (size_t i = i0; i < i1; i++)
        c += (size_t)starts_triple(x->m, i);
    x->cnt[r] = c;
}

static void write_triples(void *arg, size_t r, int tid)
{
    (void)tid;
    titems *x = arg;
    const vbx_tmap *m = x->m;
    size_t i0 = m->n * r / x->nrun, i1 = m->n * (r + 1) / x->nrun, o = x->cnt[r];
    for (size_t i = i0; i < i1; i++) {
        if (!starts_triple(m, i))
            continue;
        size_t j = i + 1;
        while (j < m->n && memcmp(m->e[j].t, m->e[i].t, sizeof m->e[i].t) == 0)
            j++;
        vbx_item *it = &x->it[o++];
        it->k = i;
        memcpy(it->t, m->e[i].t, sizeof it->t);
        it->n = (uint32_t)(j - i);
        it->all = VBX_IT_TRIPLE;
    }
}

int vbx_tmap_items(const vbx_tmap *m, unsigned nt, vbx_item **it, size_t *n, size_t *cap)
{
    size_t nrun = nt ? nt : 1;
    size_t cnt[VB_MAX_THREADS];
    if (nrun > VB_MAX_THREADS)
        nrun = VB_MAX_THREADS;
    titems x = {m, nrun, cnt, NULL};
    vb_parallel_for(count_triples, &x, nrun, (int)nt);
    size_t total = 0;
    for (size_t r = 0; r < nrun; r++) {
        size_t c = cnt[r];
        cnt[r] = total;
        total += c;
    }
    if (VB_ARRAY_FIT(*it, *cap, total ? total : 1, 256) != VB_OK)
        return VB_ENOMEM;
    x.it = *it;
    vb_parallel_for(write_triples, &x, nrun, (int)nt);
    *n = total;
    return VB_OK;
}

size_t vbx_tmap_find(const vbx_tmap *m, const vb_vertex_list *all, const uint32_t t[3],
                     const uint32_t *ids, size_t nm, const double p[4])
{
    size_t lo, hi;
    vbx_tmap_range(m, t, &lo, &hi);
    for (size_t i = lo; i < hi; i++) {
        size_t k = m->e[i].k, s = all->start[k];
        if (all->start[k + 1] - s == nm && memcmp(all->ids + s, ids, nm * sizeof *ids) == 0 &&
            all->x[k] == p[0] && all->y[k] == p[1] && all->z[k] == p[2] && all->t[k] == p[3])
            return k;
    }
    return SIZE_MAX;
}

void vbx_tmap_range(const vbx_tmap *m, const uint32_t t[3], size_t *lo, size_t *hi)
{
    vbx_tent key = {{t[0], t[1], t[2]}, 0};
    size_t a = 0, b = m->n;
    if (m->off) {
        a = t[0] < m->noff ? m->off[t[0]] : m->n;
        b = t[0] < m->noff ? m->off[t[0] + 1] : m->n;
    }
    while (a < b) {
        size_t mid = a + (b - a) / 2;
        if (tent_cmp(&m->e[mid], &key) < 0)
            a = mid + 1;
        else
            b = mid;
    }
    *lo = a;
    while (a < m->n && m->e[a].t[0] == t[0] && m->e[a].t[1] == t[1] && m->e[a].t[2] == t[2])
        a++;
    *hi = a;
}
