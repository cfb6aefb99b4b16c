/* Frames in flight: the reader thread and its ring of frames (vbc_ahead.h). */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vbc_ahead.h"

/* A diagnostic of the reader's thread, held until its frame is taken. */
typedef struct said {
    char kind;
    int number;
    long line;
    char *file, *message;
} said;

typedef struct said_list {
    said *v;
    size_t n, cap;
    int failed;             /* a record was lost (out of memory) */
} said_list;

typedef struct slot {
    vbc_ahead_frame f;
    int rc;                 /* VB_OK, or the reader's failure (then end) */
    int end;                /* no frame: the selection ended here */
    said_list said;         /* its warnings and info lines, then its error */
} slot;

struct vbc_ahead {
    vbc_run *r;
    vb_frame_source *src;
    vb_ctx *w;              /* the reader's context */
    pthread_t th;
    pthread_mutex_t lock;
    pthread_cond_t moved;   /* a slot was filled or emptied, or stop */
    slot ring[VBC_AHEAD_MAX];
    int depth, head, count; /* the caller takes ring[head]; count filled */
    int stop;               /* the caller closes */
    said_list pending;      /* what the reader said for the frame it works on */
};

int vbc_ahead_depth(void)
{
    const char *e = getenv("VORBALL_FRAMES_AHEAD");
    if (!e || !*e)
        return 2;
    char *end;
    long v = strtol(e, &end, 10);
    return *end == '\0' && v >= 0 && v <= VBC_AHEAD_MAX ? (int)v : 2;
}

static void said_clear(said_list *L)
{
    for (size_t k = 0; k < L->n; k++) {
        free(L->v[k].file);
        free(L->v[k].message);
    }
    free(L->v);
    memset(L, 0, sizeof *L);
}

static void said_add(said_list *L, char kind, int number, const char *file, long line,
                     const char *message)
{
    if (VB_ARRAY_FIT(L->v, L->cap, L->n + 1, 8) != VB_OK) {
        L->failed = 1;
        return;
    }
    said *d = &L->v[L->n];
    d->kind = kind;
    d->number = number;
    d->line = line;
    d->file = file ? strdup(file) : NULL;
    d->message = strdup(message ? message : "");
    if ((file && !d->file) || !d->message) {
        free(d->file);
        free(d->message);
        L->failed = 1;
        return;
    }
    L->n++;
}

/* The reader context's log callback: only the reader's thread calls it. */
static void hold(void *arg, const vb_diag_record *rec)
{
    vbc_ahead *a = arg;
    said_add(&a->pending, rec->kind, rec->number, rec->file, rec->line, rec->message);
}

/* Publishes the reader's frame (or its end, or failure) into the ring;
 * returns 0, or -1 when the caller has stopped (the frame is dropped). */
static int publish(vbc_ahead *a, const slot *s)
{
    pthread_mutex_lock(&a->lock);
    while (a->count == a->depth && !a->stop)
        pthread_cond_wait(&a->moved, &a->lock);
    if (a->stop) {
        pthread_mutex_unlock(&a->lock);
        return -1;
    }
    slot *d = &a->ring[(a->head + a->count) % VBC_AHEAD_MAX];
    *d = *s;
    d->said = a->pending;
    memset(&a->pending, 0, sizeof a->pending);
    a->count++;
    pthread_cond_broadcast(&a->moved);
    pthread_mutex_unlock(&a->lock);
    return 0;
}

/* The reader's loop: the selection as the sequential loop makes it. */
static void *reader(void *arg)
{
    vbc_ahead *a = arg;
    const vbc_channels_config *c = a->r->cfg;
    long index = 0, j = 0;
    for (;;) {
        slot s;
        memset(&s, 0, sizeof s);
        if (c->f1 >= 0 && index >= c->f1) {
            s.end = 1;
            publish(a, &s);
            break;
        }
        int model = 0;
        vb_sphere_set *set = NULL;
        s.rc = vb_frame_source_next(a->w, a->src, &set, &model);
        if (s.rc == VB_OK && !set) {
            s.end = 1;
            publish(a, &s);
            break;
        }
        if (s.rc == VB_OK && index >= c->f0 && (index - c->f0) % c->fstep == 0) {
            s.rc = vbc_run_front(a->w, a->r, set, index, model, j == 0, 1, &s.f.o);
            s.f.s0 = set;
            s.f.index = index;
            s.f.j = j++;
            set = NULL;
        } else if (s.rc == VB_OK) {
            vb_spheres_free(set);
            index++;
            continue;
        }
        if (s.rc != VB_OK) {
            vb_diag_record e;
            vb_error_record(a->w, &e);
            said_add(&a->pending, 'E', e.number, e.file, e.line, e.message);
            vb_spheres_free(s.f.s0);
            vb_spheres_free(set);
            s.f.s0 = NULL;
            s.end = 1;
            publish(a, &s);
            break;
        }
        if (publish(a, &s) != 0) {
            vbc_run_front_drop(&s.f.o);
            vb_spheres_free(s.f.s0);
            break;
        }
        index++;
    }
    return NULL;
}

int vbc_ahead_open(vb_ctx *ctx, vbc_run *r, vb_frame_source *src, int depth, vbc_ahead **out)
{
    *out = NULL;
    vbc_ahead *a = calloc(1, sizeof *a);
    vb_config cfg = {2, NULL}; /* every line held: the caller's verbosity decides */
    if (!a || vb_open(&a->w, &cfg) != VB_OK) {
        free(a);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (frames in flight)");
    }
    vb_set_log(a->w, hold, a);
    a->r = r;
    a->src = src;
    a->depth = depth < 1 ? 1 : depth > VBC_AHEAD_MAX ? VBC_AHEAD_MAX : depth;
    pthread_mutex_init(&a->lock, NULL);
    pthread_cond_init(&a->moved, NULL);
    if (pthread_create(&a->th, NULL, reader, a) != 0) {
        pthread_cond_destroy(&a->moved);
        pthread_mutex_destroy(&a->lock);
        vb_close(a->w);
        free(a);
        return vb_error(ctx, VB_EINTERNAL, NULL, 0, "the frame reader's thread did not start");
    }
    *out = a;
    return VB_OK;
}

/* Says the held lines on ctx, the error last (its status returned). */
static int replay(vb_ctx *ctx, said_list *L, int rc)
{
    for (size_t k = 0; k < L->n; k++) {
        const said *d = &L->v[k];
        if (d->kind == 'W')
            vb_warn(ctx, d->number, d->file, d->line, "%s", d->message);
        else if (d->kind == 'I')
            vb_info(ctx, "%s", d->message);
        else if (d->kind == 'E' && rc != VB_OK)
            vb_error(ctx, rc, d->file, d->line, "%s", d->message);
    }
    if (L->failed && rc == VB_OK)
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (frames in flight)");
    said_clear(L);
    return rc;
}

int vbc_ahead_next(vb_ctx *ctx, vbc_ahead *a, vbc_ahead_frame *f, int *have)
{
    *have = 0;
    memset(f, 0, sizeof *f);
    pthread_mutex_lock(&a->lock);
    while (a->count == 0)
        pthread_cond_wait(&a->moved, &a->lock);
    slot s = a->ring[a->head];
    if (!s.end) { /* the end stays in the ring: later calls see it again */
        a->head = (a->head + 1) % VBC_AHEAD_MAX;
        a->count--;
    } else
        memset(&a->ring[a->head].said, 0, sizeof s.said);
    pthread_cond_broadcast(&a->moved);
    pthread_mutex_unlock(&a->lock);
    int rc = replay(ctx, &s.said, s.rc);
    if (s.end || rc != VB_OK) {
        if (!s.end) {
            vbc_run_front_drop(&s.f.o);
            vb_spheres_free(s.f.s0);
        }
        return rc;
    }
    *f = s.f;
    *have = 1;
    return VB_OK;
}

void vbc_ahead_close(vb_ctx *ctx, vbc_ahead *a)
{
    if (!a)
        return;
    pthread_mutex_lock(&a->lock);
    a->stop = 1;
    pthread_cond_broadcast(&a->moved);
    pthread_mutex_unlock(&a->lock);
    pthread_join(a->th, NULL);
    for (int k = 0; k < a->count; k++) {
        slot *s = &a->ring[(a->head + k) % VBC_AHEAD_MAX];
        if (!s->end) {
            vbc_run_front_drop(&s->f.o);
            vb_spheres_free(s->f.s0);
        }
        said_clear(&s->said);
    }
    said_clear(&a->pending);
    vb_stats_add(vb_ctx_stats(ctx), vb_ctx_stats(a->w));
    pthread_cond_destroy(&a->moved);
    pthread_mutex_destroy(&a->lock);
    vb_close(a->w);
    free(a);
}
