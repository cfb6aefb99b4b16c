/* Frames in analysis at once (vbc_flight.h). */
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "vb_diag.h"
#include "vb_parallel.h"
#include "vbc_flight.h"

/* One frame in the window: its analysis runs on th with context w, whose
 * lines `said` holds after the frame's own (f.held); seq: its place in the
 * window's order (the gate's turn). */
typedef struct job {
    vbc_ahead_frame f;
    vbc_run *r;
    struct vbc_flight *fl;
    long seq;
    vb_ctx *w;
    vbc_held *said;
    int rc;
    vb_jobs th;
} job;

struct vbc_flight {
    vbc_run *r;
    job *ring[VBC_FLIGHT_MAX];
    int width, head, count;
    vb_stats stats;         /* the analyses' counters, for ctx at close */
    /* The gate (vbc_run_gate): frames pushed and popped so far (a frame
     * popped has every frame before it backed: the caller backs each
     * before the next pop), and the window closing; moved: either moved. */
    pthread_mutex_t lock;
    pthread_cond_t moved;
    long pushed, popped;
    int stop;
};

/* A positive integer from the environment variable `name` (at most max),
 * or 0. */
static long env_count(const char *name, long max)
{
    const char *e = getenv(name);
    if (!e || !*e)
        return 0;
    char *end;
    long v = strtol(e, &end, 10);
    return *end == '\0' && v >= 1 && v <= max ? v : 0;
}

int vbc_flight_width(int *given)
{
    long v = env_count("VORBALL_FRAMES_IN_FLIGHT", VBC_FLIGHT_MAX);
    *given = v > 0;
    if (v > 0)
        return (int)v;
    int t = vb_threads(0) / 2;
    return t < 1 ? 1 : t > 8 ? 8 : t;
}

size_t vbc_flight_budget(int *given)
{
    long mib = env_count("VORBALL_FRAMES_MEMORY", 1L << 30);
    *given = mib > 0;
    if (mib > 0)
        return (size_t)mib << 20;
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    return pages > 0 && page > 0 ? (size_t)pages * (size_t)page / 4 : (size_t)1 << 30;
}

static size_t sphere_bytes(const vb_sphere_set *s)
{
    if (!s)
        return 0;
    size_t per = 4 * sizeof(double) + sizeof(long) + 1;
    if (s->ex)
        per += 4 * sizeof(vb_decimal);
    if (s->info)
        per += sizeof(vb_atom_info);
    return s->n * per;
}

size_t vbc_flight_frame_bytes(const vbc_run_out *o, const vb_sphere_set *s0)
{
    const vbc_frame_out *x = &o->F.out;
    size_t voxels = vbc_grid_voxels(&o->g), n = x->nvoxels;
    size_t b = sphere_bytes(s0) + sphere_bytes(o->kept) + 4 * sizeof(float) * o->F.atoms_cap;
    b += (x->flags ? voxels : 0) + (x->labels ? 4 * voxels : 0);
    b += n * (sizeof(uint32_t) + (x->clearance ? sizeof(float) : 0) + (x->comp ? sizeof(uint32_t) : 0));
    /* The analysis' scratch and result: union-find, clearances, distances,
     * predecessors and points, under 64 bytes a channel voxel. */
    b += 64 * n;
    return b + b / 2;
}

int vbc_flight_fit(vb_ctx *ctx, int width, int width_given, size_t budget, size_t per,
                   int ahead, int *out)
{
    size_t most = (size_t)(VBC_FLIGHT_MAX + ahead), fit = per ? budget / per : most;
    long room = (long)(fit > most ? most : fit) - ahead;
    *out = width;
    if (room >= width)
        return VB_OK;
    if (!width_given && room >= 1) {
        *out = (int)room;
        return VB_OK;
    }
    return vb_error(ctx, VB_EINPUT_FRAMES_MEMORY, NULL, 0,
                    "frames in flight: %d in analysis and %d held by the reader need %.1f MiB "
                    "(%.1f MiB a frame of this trajectory), over the budget of %.1f MiB "
                    "(VORBALL_FRAMES_MEMORY, MiB; fewer frames: VORBALL_FRAMES_IN_FLIGHT, "
                    "VORBALL_FRAMES_AHEAD)",
                    width_given || room < 1 ? width : 1, ahead,
                    (double)per * (double)((width_given ? width : 1) + ahead) / 1048576.0,
                    (double)per / 1048576.0, (double)budget / 1048576.0);
}

int vbc_flight_open(vb_ctx *ctx, vbc_run *r, int width, vbc_flight **out)
{
    vbc_flight *w = calloc(1, sizeof *w);
    *out = w;
    if (!w)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (frames in flight)");
    w->r = r;
    w->width = width < 1 ? 1 : width > VBC_FLIGHT_MAX ? VBC_FLIGHT_MAX : width;
    pthread_mutex_init(&w->lock, NULL);
    pthread_cond_init(&w->moved, NULL);
    return VB_OK;
}

int vbc_flight_count(const vbc_flight *w)
{
    return w->count;
}

int vbc_flight_room(const vbc_flight *w)
{
    return w->count < w->width;
}

void vbc_flight_shrink(vbc_flight *w, int width)
{
    if (width >= 1 && width < w->width)
        w->width = width;
}

/* The gate of job J's frame: returns 1 once the run's pore request is
 * fixed or J's frame has been popped (its turn: the frames before it are
 * backed), 0 when the window closes first. */
static int gate_wait(void *arg)
{
    job *J = arg;
    vbc_flight *w = J->fl;
    pthread_mutex_lock(&w->lock);
    while (!atomic_load(&J->r->pore_fixed) && w->popped <= J->seq && !w->stop)
        pthread_cond_wait(&w->moved, &w->lock);
    int go = atomic_load(&J->r->pore_fixed) || w->popped > J->seq;
    pthread_mutex_unlock(&w->lock);
    return go;
}

/* Wakes the gates (a pop or the close moved them). */
static void gate_move(vbc_flight *w, int popped, int stop)
{
    pthread_mutex_lock(&w->lock);
    w->popped += popped;
    w->stop |= stop;
    pthread_cond_broadcast(&w->moved);
    pthread_mutex_unlock(&w->lock);
}

static void *analyse(void *arg)
{
    job *J = arg;
    vbc_run_gate gate = {gate_wait, J};
    J->rc = vbc_run_analyse(J->w, J->r, &J->f.o, &gate);
    if (J->rc != VB_OK)
        vbc_held_error(J->said, J->w);
    return NULL;
}

static void job_free(vbc_flight *w, job *J)
{
    if (J->w) {
        vb_stats_add(&w->stats, vb_ctx_stats(J->w));
        vb_close(J->w);
    }
    vbc_held_free(J->said);
    vbc_held_free(J->f.held);
    free(J);
}

int vbc_flight_push(vb_ctx *ctx, vbc_flight *w, vbc_ahead_frame *f)
{
    job *J = calloc(1, sizeof *J);
    if (!J || !(J->said = vbc_held_new()) || vbc_held_open(&J->w, J->said) != VB_OK) {
        if (J)
            vbc_held_free(J->said);
        free(J);
        int rc = vbc_held_replay(ctx, f->held, VB_OK);
        vbc_held_free(f->held);
        vbc_run_front_drop(&f->o);
        vb_spheres_free(f->s0);
        memset(f, 0, sizeof *f);
        return rc != VB_OK ? rc : vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (frames in flight)");
    }
    J->f = *f;
    J->r = w->r;
    J->fl = w;
    J->seq = w->pushed++;
    memset(f, 0, sizeof *f);
    w->ring[(w->head + w->count) % VBC_FLIGHT_MAX] = J;
    w->count++;
    vb_jobs_start(&J->th, analyse, J, sizeof *J, 1);
    return VB_OK;
}

int vbc_flight_pop(vb_ctx *ctx, vbc_flight *w, vbc_ahead_frame *f)
{
    job *J = w->ring[w->head];
    w->head = (w->head + 1) % VBC_FLIGHT_MAX;
    w->count--;
    /* Its turn (and, the pore request fixed by the back halves before,
     * the later frames' gates open). */
    gate_move(w, 1, 0);
    vb_jobs_join(&J->th);
    memset(f, 0, sizeof *f);
    int rc = vbc_held_replay(ctx, J->f.held, VB_OK);
    rc = vbc_held_replay(ctx, J->said, rc != VB_OK ? rc : J->rc);
    if (rc == VB_OK) {
        *f = J->f;
        f->held = NULL;
    } else {
        vbc_run_front_drop(&J->f.o);
        vb_spheres_free(J->f.s0);
    }
    job_free(w, J); /* and the emptied lists */
    return rc;
}

void vbc_flight_close(vb_ctx *ctx, vbc_flight *w)
{
    if (!w)
        return;
    gate_move(w, 0, 1);
    while (w->count > 0) {
        job *J = w->ring[w->head];
        w->head = (w->head + 1) % VBC_FLIGHT_MAX;
        w->count--;
        vb_jobs_join(&J->th);
        vbc_run_front_drop(&J->f.o);
        vb_spheres_free(J->f.s0);
        job_free(w, J);
    }
    vb_stats_add(vb_ctx_stats(ctx), &w->stats);
    pthread_cond_destroy(&w->moved);
    pthread_mutex_destroy(&w->lock);
    free(w);
}
