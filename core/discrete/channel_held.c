/* Diagnostics held for later (vbc_held.h). */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vbc_held.h"

typedef struct said {
    char kind;
    int number;
    long line;
    char *file, *message;
} said;

struct vbc_held {
    pthread_mutex_t lock;
    said *v;
    size_t n, cap;
    int failed;             /* a record was lost (out of memory) */
};

vbc_held *vbc_held_new(void)
{
    vbc_held *h = calloc(1, sizeof *h);
    if (h)
        pthread_mutex_init(&h->lock, NULL);
    return h;
}

static void clear(vbc_held *h)
{
    for (size_t k = 0; k < h->n; k++) {
        free(h->v[k].file);
        free(h->v[k].message);
    }
    free(h->v);
    h->v = NULL;
    h->n = h->cap = 0;
    h->failed = 0;
}

static void add(vbc_held *h, char kind, int number, const char *file, long line, const char *message)
{
    pthread_mutex_lock(&h->lock);
    said d = {kind, number, line, file ? strdup(file) : NULL, strdup(message ? message : "")};
    if ((file && !d.file) || !d.message || VB_ARRAY_FIT(h->v, h->cap, h->n + 1, 8) != VB_OK) {
        free(d.file);
        free(d.message);
        h->failed = 1;
    } else
        h->v[h->n++] = d;
    pthread_mutex_unlock(&h->lock);
}

void vbc_held_log(void *held, const vb_diag_record *rec)
{
    add(held, rec->kind, rec->number, rec->file, rec->line, rec->message);
}

void vbc_held_error(vbc_held *h, vb_ctx *ctx)
{
    vb_diag_record e;
    if (vb_error_record(ctx, &e) == VB_OK)
        add(h, 'E', e.number, e.file, e.line, e.message);
}

void vbc_held_move(vbc_held *h, vbc_held *from)
{
    if (!from)
        return;
    for (size_t k = 0; k < from->n; k++) {
        const said *d = &from->v[k];
        add(h, d->kind, d->number, d->file, d->line, d->message);
    }
    if (from->failed)
        h->failed = 1;
    clear(from);
}

int vbc_held_open(vb_ctx **out, vbc_held *h)
{
    vb_config cfg = {2, NULL};
    if (vb_open(out, &cfg) != VB_OK) {
        *out = NULL;
        return VB_ENOMEM;
    }
    vb_set_log(*out, vbc_held_log, h);
    return VB_OK;
}

int vbc_held_replay(vb_ctx *ctx, vbc_held *h, int rc)
{
    if (!h)
        return rc;
    for (size_t k = 0; k < h->n; k++) {
        const said *d = &h->v[k];
        if (d->kind == 'W')
            vb_warn(ctx, d->number, d->file, d->line, "%s", d->message);
        else if (d->kind == 'I')
            vb_info(ctx, "%s", d->message);
        else if (d->kind == 'E' && rc != VB_OK)
            vb_error(ctx, rc, d->file, d->line, "%s", d->message);
    }
    if (h->failed && rc == VB_OK)
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (frames in flight)");
    clear(h);
    return rc;
}

void vbc_held_free(vbc_held *h)
{
    if (!h)
        return;
    clear(h);
    pthread_mutex_destroy(&h->lock);
    free(h);
}
