/* Frames in flight: the reader thread and its ring of frames (vbc_ahead.h). */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "vb_parallel.h"
#include "vbc_ahead.h"

typedef struct slot {
    vbc_ahead_frame f;
    int rc;                 /* VB_OK, or the reader's failure (then end) */
    int end;                /* no frame: the selection ended here */
} slot;

struct vbc_ahead {
    vbc_run *r;
    vb_frame_source *src;
    vb_ctx *w;              /* the reader's context, its lines held in `pending` */
    int front;              /* vbc_run_front's mode */
    long index, j;          /* the next frame of the input, of the selection */
    pthread_t th;
    pthread_mutex_t lock;
    pthread_cond_t moved;   /* a slot was filled or emptied, or stop */
    slot ring[VBC_AHEAD_MAX];
    int depth, head, count; /* the caller takes ring[head]; count filled; depth 0: no thread */
    int stop;               /* the caller closes */
    int done;               /* depth 0: the end (or failure) was met, its status in last_rc */
    int last_rc;
    vbc_held *pending;      /* what the reader said for the frame it works on */
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

/* The reader's next slot: the next selected frame read and its front run,
 * or the end of the selection, or a failure (then end); its lines held with
 * it. Returns s->end. */
static int produce(vbc_ahead *a, slot *s)
{
    const vbc_channels_config *c = a->r->cfg;
    memset(s, 0, sizeof *s);
    s->f.t_read = vb_now();
    s->f.cpu_read = vbc_cpu_now();
    for (;;) {
        if (c->f1 >= 0 && a->index >= c->f1) {
            s->end = 1;
            break;
        }
        int model = 0;
        vb_sphere_set *set = NULL;
        double t0 = vb_now();
        s->rc = vb_frame_source_next(a->w, a->src, &set, &model);
        s->f.ms_read += 1e3 * (vb_now() - t0);
        if (s->rc == VB_OK && !set) {
            s->end = 1;
            break;
        }
        long index = a->index;
        if (s->rc == VB_OK && index >= c->f0 && (index - c->f0) % c->fstep == 0) {
            s->rc = vbc_run_front(a->w, a->r, set, index, model, a->j == 0, a->front, &s->f.o);
            s->f.s0 = set;
            s->f.index = index;
            s->f.j = a->j++;
            set = NULL;
        } else if (s->rc == VB_OK) {
            vb_spheres_free(set);
            a->index++;
            continue;
        }
        if (s->rc != VB_OK) {
            vbc_held_error(a->pending, a->w);
            vb_spheres_free(s->f.s0);
            vb_spheres_free(set);
            s->f.s0 = NULL;
            s->end = 1;
            break;
        }
        a->index++;
        break;
    }
    /* The lines said so far go with the slot. */
    if ((s->f.held = vbc_held_new()))
        vbc_held_move(s->f.held, a->pending);
    else if (s->rc == VB_OK)
        s->rc = VB_ENOMEM;
    if (s->rc != VB_OK && !s->end) {
        vbc_run_front_drop(&s->f.o);
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
    if (!a || !(a->pending = vbc_held_new()) || vbc_held_open(&a->w, a->pending) != VB_OK) {
        if (a)
            vbc_held_free(a->pending);
        free(a);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (frames in flight)");
    }
    a->r = r;
    a->src = src;
    a->front = front;
    a->depth = depth < 0 ? 0 : depth > VBC_AHEAD_MAX ? VBC_AHEAD_MAX : depth;
    pthread_mutex_init(&a->lock, NULL);
    pthread_cond_init(&a->moved, NULL);
    if (a->depth > 0 && pthread_create(&a->th, NULL, reader, a) != 0) {
        pthread_cond_destroy(&a->moved);
        pthread_mutex_destroy(&a->lock);
        vb_close(a->w);
        vbc_held_free(a->pending);
        free(a);
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
    if (a->depth > 0) {
        pthread_mutex_lock(&a->lock);
        a->stop = 1;
        pthread_cond_broadcast(&a->moved);
        pthread_mutex_unlock(&a->lock);
        pthread_join(a->th, NULL);
    }
    for (int k = 0; k < a->count; k++)
        slot_drop(&a->ring[(a->head + k) % VBC_AHEAD_MAX]);
    vbc_held_free(a->pending);
    vb_stats_add(vb_ctx_stats(ctx), vb_ctx_stats(a->w));
    pthread_cond_destroy(&a->moved);
    pthread_mutex_destroy(&a->lock);
    vb_close(a->w);
    free(a);
}
