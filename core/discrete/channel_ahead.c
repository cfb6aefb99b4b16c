/* Frames in flight: the reader thread and its ring of frames (vbc_ahead.h). */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "vb_parallel.h"
#include "vb_stage_clock.h"
#include "vbc_ahead.h"

typedef struct slot {
    vbc_ahead_frame f;
    int rc;                 /* VB_OK, or the reader's failure (then end) */
    int end;                /* no frame: the selection ended here */
} slot;

/* A selected frame as read (the fetcher's), or the end, or a failure. */
typedef struct raw {
    vb_sphere_set *set;     /* NULL at the end */
    int model, rc, end;
    long index;
    vbc_held *held;         /* what reading said, its error last */
    double t_read, cpu_read, ms_read;
} raw;

struct vbc_ahead {
    vbc_run *r;
    vb_frame_source *src;
    vb_ctx *w, *rw;         /* the front's context and the reading's */
    vbc_held *pending;      /* what the front said for the frame it works on */
    vbc_held *rpending;     /* what reading said for the frame it reads */
    int front;              /* vbc_run_front's mode */
    long index, j;          /* the next frame of the input (fetcher), of the selection (front) */
    pthread_t th, fth;      /* the front's thread and the fetcher's (depth > 0) */
    pthread_mutex_t lock;
    pthread_cond_t moved;   /* a slot or a raw frame was filled or taken, or stop */
    slot ring[VBC_AHEAD_MAX];
    raw raws[VBC_AHEAD_MAX];
    int depth, head, count; /* the caller takes ring[head]; count filled; depth 0: no thread */
    int rhead, rcount;      /* the front takes raws[rhead] */
    int fetching, reading;  /* fth runs, th runs */
    int stop;               /* the caller closes */
    int done;               /* depth 0: the end (or failure) was met, its status in last_rc */
    int last_rc;
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

/* The next selected frame read into *x, or the end of the selection, or
 * a failure (then end), with what reading said. Returns x->end. */
static int fetch(vbc_ahead *a, raw *x)
{
    const vbc_channels_config *c = a->r->cfg;
    memset(x, 0, sizeof *x);
    x->t_read = vb_now();
    x->cpu_read = vb_cpu_now();
    for (;;) {
        if (c->f1 >= 0 && a->index >= c->f1) {
            x->end = 1;
            break;
        }
        vb_sphere_set *set = NULL;
        double t0 = vb_now();
        x->rc = vb_frame_source_next(a->rw, a->src, &set, &x->model);
        x->ms_read += 1e3 * (vb_now() - t0);
        if (x->rc != VB_OK)
            vbc_held_error(a->rpending, a->rw);
        if (x->rc != VB_OK || !set) {
            x->end = 1;
            break;
        }
        long index = a->index++;
        if (index >= c->f0 && (index - c->f0) % c->fstep == 0) {
            x->set = set;
            x->index = index;
            break;
        }
        vb_spheres_free(set);
    }
    if ((x->held = vbc_held_new()))
        vbc_held_move(x->held, a->rpending);
    else if (x->rc == VB_OK) {
        x->rc = VB_ENOMEM;
        vb_spheres_free(x->set);
        x->set = NULL;
        x->end = 1;
    }
    return x->end;
}

static void raw_drop(raw *x)
{
    vb_spheres_free(x->set);
    vbc_held_free(x->held);
    memset(x, 0, sizeof *x);
}

/* The fetcher's loop (depth > 0): frames read up to depth ahead of the front. */
static void *fetcher(void *arg)
{
    vbc_ahead *a = arg;
    for (;;) {
        raw x;
        int end = fetch(a, &x);
        pthread_mutex_lock(&a->lock);
        while (a->rcount == a->depth && !a->stop)
            pthread_cond_wait(&a->moved, &a->lock);
        if (a->stop) {
            pthread_mutex_unlock(&a->lock);
            raw_drop(&x);
            break;
        }
        a->raws[(a->rhead + a->rcount) % VBC_AHEAD_MAX] = x;
        a->rcount++;
        pthread_cond_broadcast(&a->moved);
        pthread_mutex_unlock(&a->lock);
        if (end)
            break;
    }
    return NULL;
}

/* The next frame as read: from the fetcher, or (depth 0) read here. After
 * stop, an end. */
static void take_raw(vbc_ahead *a, raw *x)
{
    if (a->depth == 0) {
        fetch(a, x);
        return;
    }
    pthread_mutex_lock(&a->lock);
    while (a->rcount == 0 && !a->stop)
        pthread_cond_wait(&a->moved, &a->lock);
    if (a->rcount == 0) {
        memset(x, 0, sizeof *x);
        x->end = 1;
    } else {
        *x = a->raws[a->rhead];
        a->rhead = (a->rhead + 1) % VBC_AHEAD_MAX;
        a->rcount--;
    }
    pthread_cond_broadcast(&a->moved);
    pthread_mutex_unlock(&a->lock);
}

/* The reader's next slot: the next selected frame as read with its front
 * run, or the end of the selection, or a failure (then end); the lines of
 * its reading and of its front held with it. Returns s->end. */
static int produce(vbc_ahead *a, slot *s)
{
    raw x;
    memset(s, 0, sizeof *s);
    take_raw(a, &x);
    s->f.t_read = x.t_read;
    s->f.cpu_read = x.cpu_read;
    s->f.ms_read = x.ms_read;
    s->f.held = x.held;
    s->rc = x.rc;
    if (x.end) {
        s->end = 1;
        return 1;
    }
    s->rc = vbc_run_front(a->w, a->r, x.set, x.index, x.model, a->j == 0, a->front, &s->f.o);
    s->f.s0 = x.set;
    s->f.index = x.index;
    s->f.j = a->j++;
    if (s->rc != VB_OK)
        vbc_held_error(a->pending, a->w);
    vbc_held_move(s->f.held, a->pending);
    if (s->rc != VB_OK) {
        vb_spheres_free(s->f.s0);
        s->f.s0 = NULL;
        s->end = 1;
    }
    return s->end;
}

static void slot_drop(slot *s)
{
    if (!s->end) {
        vbc_run_front_drop(&s->f.o);
        vb_spheres_free(s->f.s0);
    }
    vbc_held_free(s->f.held);
    s->f.held = NULL;
}

/* Publishes the reader's slot into the ring; returns 0, or -1 when the
 * caller has stopped (the slot is dropped). */
static int publish(vbc_ahead *a, slot *s)
{
    pthread_mutex_lock(&a->lock);
    while (a->count == a->depth && !a->stop)
        pthread_cond_wait(&a->moved, &a->lock);
    if (a->stop) {
        pthread_mutex_unlock(&a->lock);
        slot_drop(s);
        return -1;
    }
    a->ring[(a->head + a->count) % VBC_AHEAD_MAX] = *s;
    a->count++;
    pthread_cond_broadcast(&a->moved);
    pthread_mutex_unlock(&a->lock);
    return 0;
}

/* The reader's loop: the selection as the sequential loop makes it. */
static void *reader(void *arg)
{
    vbc_ahead *a = arg;
    for (;;) {
        slot s;
        int end = produce(a, &s);
        if (publish(a, &s) != 0 || end)
            break;
    }
    return NULL;
}

int vbc_ahead_open(vb_ctx *ctx, vbc_run *r, vb_frame_source *src, int depth, int front,
                   vbc_ahead **out)
{
    *out = NULL;
    vbc_ahead *a = calloc(1, sizeof *a);
    if (!a || !(a->pending = vbc_held_new()) || !(a->rpending = vbc_held_new()) ||
        vbc_held_open(&a->w, a->pending) != VB_OK || vbc_held_open(&a->rw, a->rpending) != VB_OK) {
        if (a) {
            vb_close(a->w);
            vbc_held_free(a->pending);
            vbc_held_free(a->rpending);
        }
        free(a);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (frames in flight)");
    }
    a->r = r;
    a->src = src;
    a->front = front;
    a->depth = depth < 0 ? 0 : depth > VBC_AHEAD_MAX ? VBC_AHEAD_MAX : depth;
    pthread_mutex_init(&a->lock, NULL);
    pthread_cond_init(&a->moved, NULL);
    if (a->depth > 0 && pthread_create(&a->fth, NULL, fetcher, a) == 0)
        a->fetching = 1;
    if (a->fetching && pthread_create(&a->th, NULL, reader, a) == 0)
        a->reading = 1;
    if (a->depth > 0 && !a->reading) {
        vbc_ahead_close(ctx, a);
        return vb_error(ctx, VB_EINTERNAL, NULL, 0, "the frame reader's thread did not start");
    }
    *out = a;
    return VB_OK;
}

int vbc_ahead_next(vbc_ahead *a, vbc_ahead_frame *f, int *have)
{
    *have = 0;
    memset(f, 0, sizeof *f);
    slot s;
    if (a->depth == 0) { /* on the caller's thread */
        if (a->done)
            return a->last_rc;
        if (produce(a, &s)) {
            a->done = 1;
            a->last_rc = s.rc;
        }
    } else {
        pthread_mutex_lock(&a->lock);
        while (a->count == 0)
            pthread_cond_wait(&a->moved, &a->lock);
        s = a->ring[a->head];
        if (!s.end) { /* the end stays in the ring: later calls see it again */
            a->head = (a->head + 1) % VBC_AHEAD_MAX;
            a->count--;
        } else
            a->ring[a->head].f.held = NULL;
        pthread_cond_broadcast(&a->moved);
        pthread_mutex_unlock(&a->lock);
    }
    *f = s.f;
    *have = !s.end && s.rc == VB_OK;
    return s.rc;
}

void vbc_ahead_close(vb_ctx *ctx, vbc_ahead *a)
{
    if (!a)
        return;
    pthread_mutex_lock(&a->lock);
    a->stop = 1;
    pthread_cond_broadcast(&a->moved);
    pthread_mutex_unlock(&a->lock);
    if (a->reading)
        pthread_join(a->th, NULL);
    if (a->fetching)
        pthread_join(a->fth, NULL);
    for (int k = 0; k < a->count; k++)
        slot_drop(&a->ring[(a->head + k) % VBC_AHEAD_MAX]);
    for (int k = 0; k < a->rcount; k++)
        raw_drop(&a->raws[(a->rhead + k) % VBC_AHEAD_MAX]);
    vbc_held_free(a->pending);
    vbc_held_free(a->rpending);
    vb_stats_add(vb_ctx_stats(ctx), vb_ctx_stats(a->w));
    vb_stats_add(vb_ctx_stats(ctx), vb_ctx_stats(a->rw));
    vb_close(a->rw);
    pthread_cond_destroy(&a->moved);
    pthread_mutex_destroy(&a->lock);
    vb_close(a->w);
    free(a);
}
