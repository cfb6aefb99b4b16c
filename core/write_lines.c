/* vb_write_lines: formatting 17 digits is most of the cost of writing a
 * vertex file, so blocks of items are formatted on the threads into plain
 * memory (vb_text: no stdio call per number), and the round formatted
 * before is written meanwhile: copied by every thread into the mapped file
 * where the output is a regular file (vb_write_map.h), else by one thread
 * through stdio. */
#include "vb_write_lines.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "vb.h"
#include "vb_numtext.h"
#include "vb_parallel.h"
#include "vb_write_map.h"

#define WRITE_BLOCK 4096u

int vb_text_grow(vb_text *t, size_t need)
{
    if (t->nomem)
        return -1;
    size_t cap = t->cap ? t->cap : 4096;
    while (cap - t->n < need)
        cap *= 2;
    char *p = realloc(t->p, cap);
    if (!p) {
        t->nomem = 1;
        return -1;
    }
    t->p = p;
    t->cap = cap;
    return 0;
}

void vb_text_put(vb_text *t, const char *s, size_t n)
{
    char *d = vb_text_room(t, n);
    if (!d)
        return;
    memcpy(d, s, n);
    t->n += n;
}

void vb_text_u32(vb_text *t, char sep, uint32_t v)
{
    char *d = vb_text_room(t, 12);
    if (!d)
        return;
    size_t n = 0;
    if (sep)
        d[n++] = sep;
    n += vb_format_u32(v, d + n);
    t->n += n;
}

void vb_text_g17(vb_text *t, char sep, double x)
{
    char *d = vb_text_room(t, VB_G17_MAX + 1);
    if (!d)
        return;
    size_t n = 0;
    if (sep)
        d[n++] = sep;
    n += vb_format_g17(x, d + n);
    t->n += n;
}

/* One round: blocks 0 .. nb-1 of items from k0 formatted into text[0 ..
 * nb), and the round before (prev[0 .. nprev)) written meanwhile. Its jobs
 * are taken in order from one counter by every thread: first the writing
 * (one job through stdio; into the mapped file, job j copies block j to
 * dst + at[j]), then the blocks to format. The thread that writes through
 * stdio formats only once its write is done, so the round lasts the longer
 * of the write and the formatting shared out, never their sum. */
typedef struct round {
    vb_line_fn fn;
    const void *arg;
    size_t n, k0, nb;
    vb_text *text;
    FILE *f;
    vb_text *prev;
    size_t nprev, writes; /* writing jobs: 0, 1 (stdio) or nprev (mapped) */
    char *dst;
    const size_t *at;
    atomic_size_t next;
} round;

static void write_texts(FILE *f, vb_text *t, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (t[i].n)
            fwrite(t[i].p, 1, t[i].n, f);
}

static void format_block(round *r, size_t b)
{
    vb_text *t = r->text + b;
    t->n = 0;
    size_t k0 = r->k0 + b * WRITE_BLOCK, k1 = k0 + WRITE_BLOCK;
    for (size_t k = k0; k < k1 && k < r->n; k++)
        r->fn(t, r->arg, k);
}

static void round_item(void *ctx, size_t i, int tid)
{
    (void)i;
    (void)tid;
    round *r = ctx;
    for (size_t j; (j = atomic_fetch_add(&r->next, 1)) < r->writes + r->nb;) {
        if (j >= r->writes)
            format_block(r, j - r->writes);
        else if (!r->dst)
            write_texts(r->f, r->prev, r->nprev);
        else if (r->prev[j].n)
            memcpy(r->dst + r->at[j], r->prev[j].p, r->prev[j].n);
    }
}

static int any_nomem(const vb_text *t, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (t[i].nomem)
            return 1;
    return 0;
}

/* One block of text at a time, written as it fills (one thread, a file
 * that is not mapped). */
static int write_serial(FILE *f, size_t n, vb_line_fn fn, const void *arg)
{
    vb_text t = {0};
    int rc = VB_OK;
    for (size_t k = 0; k < n && rc == VB_OK; k++) {
        fn(&t, arg, k);
        if (t.nomem)
            rc = VB_ENOMEM;
        else if (t.n >= 65536 || k + 1 == n) {
            fwrite(t.p, 1, t.n, f);
            t.n = 0;
        }
    }
    free(t.p);
    return rc;
}

/* Where the round before goes: a mapping of its bytes at the file's end
 * (at[j]: block j's offset in it), or NULL (stdio; the mapping ended). */
static char *map_prev(vb_map_out *m, FILE *f, const vb_text *prev, size_t nprev, size_t *at)
{
    if (m->fd < 0 || !nprev)
        return NULL;
    size_t len = 0;
    for (size_t j = 0; j < nprev; j++) {
        at[j] = len;
        len += prev[j].n;
    }
    char *dst = vb_map_round(m, len);
    if (!dst && len)
        vb_map_end(f, m);
    return dst;
}

int vb_write_lines(FILE *f, size_t n, vb_line_fn fn, const void *arg)
{
    int nt = vb_threads(0);
    if (n <= WRITE_BLOCK)
        return write_serial(f, n, fn, arg);
    vb_map_out m;
    if (vb_map_begin(f, &m) != 0 && nt == 1)
        return write_serial(f, n, fn, arg);
    /* Two sets of a round's texts: one formatted while the other is
     * written. */
    size_t per = 4u * (size_t)nt;
    vb_text *text = calloc(2 * per, sizeof *text);
    size_t *at = malloc(per * sizeof *at);
    if (!text || !at) {
        free(text);
        free(at);
        return vb_map_end(f, &m) != 0 ? VB_EIO : VB_ENOMEM;
    }
    int rc = VB_OK, cur = 0;
    size_t nprev = 0, k0 = 0;
    while (rc == VB_OK && (k0 < n || nprev)) {
        vb_text *prev = text + (size_t)(1 - cur) * per;
        char *dst = map_prev(&m, f, prev, nprev, at);
        size_t nb = k0 < n ? (n - k0 + WRITE_BLOCK - 1) / WRITE_BLOCK : 0;
        nb = nb < per ? nb : per;
        round r = {fn, arg, n, k0, nb, text + (size_t)cur * per, f, prev, nprev,
                   dst ? nprev : nprev ? 1 : 0, dst, at, 0};
        vb_parallel_for(round_item, &r, (size_t)nt, nt);
        vb_map_round_end(&m);
        if (any_nomem(r.text, nb)) {
            /* What came before the short block is written. */
            size_t i = 0;
            while (!r.text[i].nomem)
                i++;
            rc = vb_map_end(f, &m) != 0 ? VB_EIO : VB_ENOMEM;
            write_texts(f, r.text, i);
        }
        k0 += nb * WRITE_BLOCK;
        nprev = nb;
        cur = 1 - cur;
    }
    if (vb_map_end(f, &m) != 0 && rc == VB_OK)
        rc = VB_EIO;
    for (size_t i = 0; i < 2 * per; i++)
        free(text[i].p);
    free(text);
    free(at);
    return rc;
}
