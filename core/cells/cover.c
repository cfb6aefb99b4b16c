/* The direction-cover proposer on the host (vb_cover.h; the argument is in
 * vb_cover_shared.h). Each cell is covered independently: a near list of
 * neighbours from the tree of the centres (cover_tree.c), then a
 * depth-first subdivision of the cube's faces in which every patch keeps
 * the labels its enclosures cannot exclude. Cells run on worker threads; the quadruples are sorted at the
 * end, so the result does not depend on the thread count. */
#include "vb_array.h"
#include "vb_cover.h"

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "vb_cover_shared.h"
#include "vb_parallel.h"
#include "vb_stage_clock.h"
#include "vbq_cluster.h"
#include "vbs_internal.h"

/* ---- the cells on worker threads ---------------------------------------- */

typedef struct job {
    const vb_sphere_set *set;
    vbq_env env;
    const uint32_t *cells;  /* the cells to cover */
    size_t ncells;
    atomic_size_t next;
    atomic_int failed;
    vb_ctx *ctx;            /* where progress goes (vb_progress) */
    size_t base, all;       /* cells of earlier parts, and of every part */
    atomic_size_t covered;  /* cells of this part covered so far */
    size_t batch;           /* cells per device batch (0: the backend's) */
    vb_cover_sink sink;     /* non-NULL: each device batch's quadruples go to it at once, */
    void *user;
    size_t flush;           /* and a host worker's once it holds this many */
    int host_back;          /* 0: host threads cover only the cells a device left */
} job;

/* n more cells covered: the progress of the whole cover, from any thread. */
static void covered(job *jb, size_t n)
{
    size_t d = atomic_fetch_add(&jb->covered, n) + n;
    vb_progress(jb->ctx, "cover", jb->base + d, jb->all);
}

/* A worker's arena (grown when a cell overflows it) and its quadruples. */
typedef struct worker {
    job *jb;
    vbq_arena ar;
    vb_quad_list ql;        /* its quadruples */
    vb_cover_stats st;
    int rc;
} worker;

/* Arena capacities of the first try on the host; a cell that overflows one
 * is covered again with that capacity doubled. */
#define VBQ_NB0 1024u
#define VBQ_LAB0 8192u
#define VBQ_ST0 512u
#define VBQ_Q0 512u

/* Cell i covered from `root` on w's arena, grown until it fits (root
 * VBQ_RESUME: the handed patches resume[0 .. nres) words alone): its
 * quadruples appended to l, its counters to w's. */
static int cover_root(worker *w, uint32_t i, uint32_t root, const uint32_t *resume, size_t nres,
                      vb_quad_list *l)
{
    vbq_cell_out o;
    for (;;) {
        w->ar.resume = resume;
        w->ar.resume_n = (uint32_t)nres;
        vb_cover_cell_host(&w->jb->env, &w->ar, i, root, &o);
        w->ar.resume = NULL;
        w->ar.resume_n = 0;
        if (o.status == VBQ_OK)
            break;
        uint32_t nb = w->ar.nb_cap, lab = w->ar.lab_cap, st = w->ar.st_cap, q = w->ar.q_cap;
        uint32_t *grow = o.status == VBQ_OVER_NB ? &nb : o.status == VBQ_OVER_LAB ? &lab
                         : o.status == VBQ_OVER_ST ? &st : &q;
        if (*grow >= (1u << 30))
            return VB_ENOMEM;
        *grow *= 2u;
        if (vbq_arena_make(&w->ar, nb, lab, st, q) != VB_OK)
            return VB_ENOMEM;
        w->st.retries++;
    }
    vb_cover_stats_cell(&w->st, &o);
    return vb_quad_list_append(l, w->ar.q, o.nq);
}

/* A part of quadruples to the job's sink, counted in w's stats (parts,
 * quadruples, the sink's seconds). The sink takes the array, or keeps
 * nothing of it. */
static int sink_part(worker *w, vb_quad_list *part)
{
    double t0 = vb_now();
    w->st.quads += part->n;
    w->st.stream_parts++;
    int rc = w->jb->sink(w->jb->user, part);
    w->st.steps.sink_s += vb_now() - t0;
    return rc;
}

static int cover_one(worker *w, uint32_t i)
{
    w->st.cells++;
    return cover_root(w, i, VBQ_ALL_ROOTS, NULL, 0, &w->ql);
}

/* Records a host worker's error rc and flags its job failed (every worker
 * stops at its next cell). */
static void worker_fail(worker *w, int rc)
{
    w->rc = rc;
    atomic_store(&w->jb->failed, 1);
}

/* Gives a host worker its first arena: 1 when ready, 0 when out of memory
 * (the worker failed, see worker_fail). */
static int worker_ready(worker *w)
{
    if (w->ar.nb || vbq_arena_make(&w->ar, VBQ_NB0, VBQ_LAB0, VBQ_ST0, VBQ_Q0) == VB_OK)
        return 1;
    worker_fail(w, VB_ENOMEM);
    return 0;
}

static void *work(void *arg)
{
    worker *w = arg;
    job *jb = w->jb;
    if (!worker_ready(w))
        return NULL;
    for (;;) {
        size_t k = atomic_fetch_add(&jb->next, 1);
        if (k >= jb->ncells || atomic_load(&jb->failed))
            break;
        int rc = cover_one(w, jb->cells[k]);
        if (rc != VB_OK) {
            worker_fail(w, rc);
            break;
        }
        covered(jb, 1);
    }
    return NULL;
}

/* The first worker's error (VB_OK when none failed). */
static int first_error(const worker *w, int nt)
{
    int bad = vb_jobs_first_error(w, sizeof *w, nt, offsetof(worker, rc), VB_JOBS_UNORDERED);
    return bad < 0 ? VB_OK : w[bad].rc;
}

/* Covers jb->cells on nt host threads, appending to the workers' lists. */
static int cover_host(job *jb, worker *w, int nt)
{
    atomic_store(&jb->next, 0);
    atomic_store(&jb->failed, 0);
    vb_run_jobs(work, w, sizeof *w, nt);
    return first_error(w, nt);
}

/* The device and the host together: the calling thread feeds the backend
 * batches from the front of the cell list, host threads take single cells
 * from its back, and the cells a device batch could not finish (an arena
 * ran out there) go to a queue the host threads serve first. Which side
 * covers a cell changes nothing it proposes. */
typedef struct share {
    pthread_mutex_t mu;
    pthread_cond_t cv;
    size_t front, back;    /* cells [front, back) are still untaken */
    uint32_t *left;        /* cells the device left to the host */
    size_t nleft, lhead;
    struct resume_task **rq; /* cells whose handed patches the host threads resume */
    size_t nrq, rqhead, rqcap;
    int helpers;           /* host threads beside the device's */
    int done;              /* the device takes no more batches */
    vb_quad_list posted;   /* early cells' quadruples for a host thread to sink */
} share;

/* A device cell with handed patches, for a host thread: the kernel's nq
 * quadruples (w[0 .. 4 nq)) and the hand words (w[4 nq .. + nhw)), copied
 * out of the batch's buffers, which the next batch reuses. */
typedef struct resume_task {
    uint32_t cell, nq;
    size_t nhw;
    uint32_t w[];
} resume_task;

/* Resumes task t on w's arena: the cell's quadruples (the kernel's and the
 * resumed patches', made unique) appended to w's list; frees t. */
static int resume_on(worker *w, resume_task *t)
{
    size_t c0 = w->ql.n;
    double c = vb_thread_cpu_now();
    int rc = vb_quad_list_append(&w->ql, t->w, t->nq);
    if (rc == VB_OK)
        rc = cover_root(w, t->cell, VBQ_RESUME, t->w + 4 * (size_t)t->nq, t->nhw, &w->ql);
    w->st.steps.resume_cpu_s += vb_thread_cpu_now() - c;
    if (rc == VB_OK)
        w->ql.n = c0 + vb_quad_cell_unique(w->ql.q + c0, w->ql.n - c0);
    free(t);
    return rc;
}

/* Queues cell's resume (copied here) for the host threads and wakes one.
 * VB_OK or VB_ENOMEM. */
static int resume_queue(share *sh, uint32_t cell, const uint32_t *q, uint32_t nq,
                        const uint32_t *hw, size_t nhw)
{
    resume_task *t = malloc(sizeof *t + (4 * (size_t)nq + nhw) * sizeof *t->w);
    if (!t)
        return VB_ENOMEM;
    t->cell = cell;
    t->nq = nq;
    t->nhw = nhw;
    memcpy(t->w, q, 4 * (size_t)nq * sizeof *t->w);
    memcpy(t->w + 4 * (size_t)nq, hw, nhw * sizeof *t->w);
    pthread_mutex_lock(&sh->mu);
    int rc = VB_ARRAY_FIT(sh->rq, sh->rqcap, sh->nrq + 1, 64);
    if (rc == VB_OK) {
        sh->rq[sh->nrq++] = t;
        pthread_cond_signal(&sh->cv);
    }
    pthread_mutex_unlock(&sh->mu);
    if (rc != VB_OK)
        free(t);
    return rc == VB_OK ? VB_OK : VB_ENOMEM;
}

typedef struct hybrid_arg {
    worker *w;
    share *sh;
} hybrid_arg;

static void *hybrid_host(void *arg)
{
    hybrid_arg *ha = arg;
    worker *w = ha->w;
    share *sh = ha->sh;
    job *jb = w->jb;
    if (!worker_ready(w))
        return NULL;
    for (;;) {
        pthread_mutex_lock(&sh->mu);
        uint32_t cell = 0;
        int have = 0;
        resume_task *task = NULL;
        vb_quad_list part = {0};
        while (!have && !atomic_load(&jb->failed)) {
            if (sh->posted.n) {
                part = sh->posted;
                memset(&sh->posted, 0, sizeof part);
                have = 1;
            } else if (sh->rqhead < sh->nrq) {
                task = sh->rq[sh->rqhead];
                sh->rq[sh->rqhead++] = NULL;
                have = 1;
            } else if (sh->lhead < sh->nleft) {
                cell = sh->left[sh->lhead++];
                have = 1;
            } else if (sh->front < sh->back && jb->host_back) {
                cell = jb->cells[--sh->back];
                have = 1;
            } else if (sh->done) {
                break;
            } else {
                double t0 = vb_now(); /* no work yet: the device has it */
                pthread_cond_wait(&sh->cv, &sh->mu);
                w->st.steps.host_wait_s += vb_now() - t0;
            }
        }
        pthread_mutex_unlock(&sh->mu);
        if (!have)
            return NULL;
        int rc;
        if (part.n) { /* the device's early cells (take_early) */
            rc = sink_part(w, &part);
            vb_quad_list_free(&part);
        } else {
            /* a resume's cell was counted covered by the device's thread */
            double c = vb_thread_cpu_now();
            rc = task ? resume_on(w, task) : cover_one(w, cell);
            if (!task)
                w->st.steps.host_cells_cpu_s += vb_thread_cpu_now() - c;
            if (rc == VB_OK && !task)
                covered(jb, 1);
        }
        /* Streamed: a host worker's cells go to the sink as the device's
         * batches do, so that what the host covers is not all certified
         * after the cover. */
        if (rc == VB_OK && jb->sink && w->ql.n >= jb->flush) {
            rc = sink_part(w, &w->ql);
            w->ql.n = 0;
        }
        if (rc != VB_OK) {
            worker_fail(w, rc);
            pthread_mutex_lock(&sh->mu);
            pthread_cond_broadcast(&sh->cv);
            pthread_mutex_unlock(&sh->mu);
            return NULL;
        }
    }
}

/* A device batch's cells being taken (take_cells, take_early). */
typedef struct taking {
    job *jb;
    vb_cover_backend *be;
    worker *w0;             /* the device thread's worker */
    share *sh;
    vb_hand_index hx;
    const uint32_t *cells;  /* the batch's cells */
    uint8_t *done;          /* cells taken early */
    uint32_t *left;         /* cells the device did not finish */
    double tres;            /* CPU s of resumes on this thread */
} taking;

/* Takes cells[k] for k < n with out[k] (quadruples at quads + 4 qoff,
 * handed patches in tk->hx): each finished cell's quadruples, made unique
 * with its resumed patches', appended to l; its handed patches queued for
 * a host thread, or resumed here when none is beside this one. Early (the
 * backend's later tiers still to run): only finished cells, and of those
 * with handed patches only the ones a host thread can take; done[k] marks
 * them. Else every cell not done, and the unfinished ones listed in
 * tk->left[0 .. *nl). VB_OK or VB_ENOMEM. */
static int take_cells(taking *tk, const vbq_cell_out *out, size_t n, const uint32_t *quads,
                      int early, vb_quad_list *l, size_t *nl)
{
    job *jb = tk->jb;
    worker *w0 = tk->w0;
    int spread = tk->sh->helpers > 0 && tk->be->resume_spread;
    int rc = VB_OK;
    for (size_t k = 0; rc == VB_OK && k < n; k++) {
        if (tk->done[k])
            continue;
        if (out[k].status != VBQ_OK) {
            if (!early)
                tk->left[(*nl)++] = tk->cells[k];
            continue;
        }
        const uint32_t *cq = quads + 4 * (size_t)out[k].qoff, *hw;
        size_t c0 = l->n, nhw, np;
        rc = vb_hand_index_cell(&tk->hx, tk->cells[k], &hw, &nhw, &np);
        int queued = rc == VB_OK && nhw && spread;
        if (rc != VB_OK || (early && nhw && !queued))
            continue;
        w0->st.cells++;
        vb_cover_stats_cell(&w0->st, &out[k]);
        tk->done[k] = 1;
        if (queued) {
            rc = resume_queue(tk->sh, tk->cells[k], cq, out[k].nq, hw, nhw);
            w0->st.steps.resume_queued++;
        } else {
            rc = vb_quad_list_append(l, cq, out[k].nq);
        }
        if (rc == VB_OK && nhw) {
            w0->st.resumed_patches += np;
            w0->st.resumed_cells++;
            if (!queued) {
                double c = vb_thread_cpu_now();
                rc = cover_root(w0, tk->cells[k], VBQ_RESUME, hw, nhw, l);
                tk->tres += vb_thread_cpu_now() - c;
            }
        }
        if (rc == VB_OK && !queued && (jb->sink || nhw))
            l->n = c0 + vb_quad_cell_unique(l->q + c0, l->n - c0);
    }
    return rc;
}

/* be->early (vb_cover.h): the batch's cells finished by the first tier
 * taken while the later tiers run, their quadruples posted for a host
 * thread to sink (certified meanwhile), or sunk here when no host thread
 * is beside this one; be->running says whether those tiers are long. */
static int take_early(void *user, const vbq_cell_out *out, size_t ncells, const uint32_t *quads,
                      const uint32_t *hand, size_t hand_words)
{
    taking *tk = user;
    if (vb_hand_index_make(&tk->hx, hand, hand_words) != VB_OK)
        return VB_ENOMEM;
    size_t later = 0; /* cells left to the later tiers: 1 in 64 keeps them long */
    for (size_t k = 0; k < ncells; k++)
        later += out[k].status != VBQ_OK;
    atomic_store(&tk->be->running, 64 * later >= ncells && later > 0);
    vb_quad_list chunk = {0};
    int rc = take_cells(tk, out, ncells, quads, 1, &chunk, NULL);
    pthread_mutex_lock(&tk->sh->mu);
    if (rc == VB_OK && chunk.n && tk->sh->helpers > 0 && tk->sh->posted.n == 0) {
        tk->sh->posted = chunk; /* the slot is free */
        memset(&chunk, 0, sizeof chunk);
        pthread_cond_signal(&tk->sh->cv);
    }
    pthread_mutex_unlock(&tk->sh->mu);
    if (rc == VB_OK && chunk.n)
        rc = sink_part(tk->w0, &chunk);
    vb_quad_list_free(&chunk);
    return rc;
}

/* Feeds the device; returns its status (VB_EDEVICE: the caller covers
 * everything on the host again). */
static int hybrid_device(vb_ctx *ctx, job *jb, vb_cover_backend *be, worker *w0, share *sh)
{
    size_t batch = jb->batch;
    taking tk;
    memset(&tk, 0, sizeof tk);
    tk.jb = jb;
    tk.be = be;
    tk.w0 = w0;
    tk.sh = sh;
    vbq_cell_out *outs = malloc(batch * sizeof *outs);
    tk.done = malloc(batch);
    tk.left = malloc(batch * sizeof *tk.left);
    be->host_threads = (unsigned)sh->helpers + 1;
    int rc = outs && tk.done && tk.left ? be->begin(ctx, be, &jb->env, jb->set->n)
                                        : vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover)");
    uint64_t handed0 = be->handed_cells;
    /* the handed patches are resumed here, on w0's arena */
    if (rc == VB_OK && !worker_ready(w0))
        rc = w0->rc;
    int early = jb->sink && vb_cover_early_on(be);
    while (rc == VB_OK && !atomic_load(&jb->failed)) {
        pthread_mutex_lock(&sh->mu);
        size_t b0 = sh->front, n = sh->back - sh->front < batch ? sh->back - sh->front : batch;
        sh->front += n;
        pthread_mutex_unlock(&sh->mu);
        if (n == 0)
            break;
        const uint32_t *quads = NULL;
        tk.cells = jb->cells + b0;
        tk.tres = 0.0;
        memset(tk.done, 0, n);
        be->early = early ? take_early : NULL;
        be->early_user = &tk;
        double t0 = vb_now();
        rc = be->run(ctx, be, jb->cells + b0, n, outs, &quads);
        atomic_store(&be->running, 0);
        be->early = NULL;
        double t1 = vb_now();
        w0->st.t_device += t1 - t0;
        w0->st.steps.batches++;
        if (rc == VB_OK && vb_hand_index_make(&tk.hx, be->hand, be->hand_words) != VB_OK)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover)");
        if (rc != VB_OK)
            break;
        size_t nl = 0;
        vb_quad_list chunk = {0};
        rc = take_cells(&tk, outs, n, quads, 0, jb->sink ? &chunk : &w0->ql, &nl);
        if (rc != VB_OK)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover)");
        pthread_mutex_lock(&sh->mu);
        for (size_t k = 0; k < nl; k++)
            sh->left[sh->nleft++] = tk.left[k];
        pthread_cond_broadcast(&sh->cv);
        pthread_mutex_unlock(&sh->mu);
        w0->st.host_cells += nl;
        covered(jb, n - nl);
        w0->st.steps.resume_cpu_s += tk.tres;
        double t2 = vb_now();
        w0->st.steps.dispatch_s += t2 - t1;
        /* Streamed: the batch's cells are disjoint from every other's and
         * each is unique, so the chunk is too; the sink sorts it. */
        if (rc == VB_OK && chunk.n)
            rc = sink_part(w0, &chunk);
        vb_quad_list_free(&chunk);
    }
    be->early = NULL;
    w0->st.handed_cells += be->handed_cells - handed0;
    vb_hand_index_free(&tk.hx);
    free(outs);
    free(tk.done);
    free(tk.left);
    return rc;
}

/* Covers jb->cells with the backend and nt host threads (the calling
 * thread drives the device, then helps the host). */
static int cover_hybrid(vb_ctx *ctx, job *jb, vb_cover_backend *be, worker *w, int nt)
{
    share sh;
    memset(&sh, 0, sizeof sh);
    sh.back = jb->ncells;
    sh.helpers = nt - 1;
    sh.left = malloc((jb->ncells ? jb->ncells : 1) * sizeof *sh.left);
    if (!sh.left || pthread_mutex_init(&sh.mu, NULL)) {
        free(sh.left);
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover)");
    }
    pthread_cond_init(&sh.cv, NULL);
    atomic_store(&jb->failed, 0);
    if (!jb->batch)
        jb->batch = be->batch_cells ? be->batch_cells : 65536;
    jb->flush = 8 * jb->batch; /* about a batch's worth of quadruples (~10 a cell) */
    hybrid_arg *ha = calloc((size_t)nt, sizeof *ha);
    vb_jobs *g = calloc(1, sizeof *g);
    int rc = ha && g ? VB_OK : VB_ENOMEM;
    for (int t = 0; rc == VB_OK && t < nt; t++)
        ha[t] = (hybrid_arg){&w[t], &sh};
    /* One core drives the device; the others cover on the host. */
    if (rc == VB_OK && nt > 1)
        vb_jobs_start(g, hybrid_host, ha + 1, sizeof *ha, nt - 1);
    int drc = rc == VB_OK ? hybrid_device(ctx, jb, be, &w[0], &sh) : rc;
    double t_idle = vb_now(); /* the device's last batch is in */
    pthread_mutex_lock(&sh.mu);
    sh.done = 1;
    /* A failed device: the host threads stop, and the caller covers every
     * cell on the host again (simplest, and it changes nothing in the
     * output). */
    if (drc != VB_OK)
        atomic_store(&jb->failed, 1);
    pthread_cond_broadcast(&sh.cv);
    pthread_mutex_unlock(&sh.mu);
    if (rc == VB_OK) {
        if (drc == VB_OK)
            hybrid_host(&ha[0]);
        if (nt > 1)
            vb_jobs_join(g);
        w[0].st.steps.tail_s += vb_now() - t_idle;
    }
    if (rc == VB_OK)
        rc = first_error(w, nt);
    if (rc == VB_OK)
        rc = drc;
    free(ha);
    free(g);
    free(sh.left);
    for (size_t k = sh.rqhead; k < sh.nrq; k++)
        free(sh.rq[k]); /* left by a failure */
    free(sh.rq);
    vb_quad_list_free(&sh.posted); /* left by a failure */
    pthread_mutex_destroy(&sh.mu);
    pthread_cond_destroy(&sh.cv);
    return rc;
}

/* Workers' quadruples of one run appended to out, sorted and unique.
 * Cells own disjoint quadruples (by their smallest id), but a device may
 * split a cell's root patches into tasks whose lists share some: one sort
 * and one pass of repeats make the list canonical. */
static int gather(worker *w, int nt, vb_quad_list *out)
{
    size_t total = out->n, n0 = out->n;
    for (int t = 0; t < nt; t++)
        total += w[t].ql.n;
    if (total > out->cap) {
        void *p = realloc(out->q, total * sizeof *out->q);
        if (!p)
            return VB_ENOMEM;
        out->q = p;
        out->cap = total;
    }
    for (int t = 0; t < nt; t++) {
        if (w[t].ql.n)
            memcpy(out->q + out->n, w[t].ql.q, w[t].ql.n * sizeof *out->q);
        out->n += w[t].ql.n;
        w[t].ql.n = 0;
    }
    return out->n > n0 ? vb_quad_list_canonical(out, nt) : VB_OK;
}

int vb_cover_run_parts(vb_ctx *ctx, const vb_sphere_set *set, const vb_cover_options *opt,
                       vb_cover_backend *be, unsigned parts, vb_cover_sink sink, void *user,
                       vb_cover_stats *stats)
{
    vb_cover_options o = opt ? *opt : (vb_cover_options){0};
    if (parts < 1 || parts > 64 || !sink)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "cover: %u pipeline parts", parts);
    job jb;
    memset(&jb, 0, sizeof jb);
    jb.set = set;
    jb.ctx = ctx;
    vb_cover_tree *tree = NULL; /* this run's own, when the caller has none */
    int prc = o.env ? VB_OK : vb_cover_prepare(ctx, set, &o, &tree, &jb.env);
    if (o.env)
        jb.env = *o.env;
    if (prc != VB_OK)
        return prc;
    /* Cells in the tree's curve order: neighbouring cells share neighbours
     * (caches, and a device's work-items). */
    const uint32_t *cells = jb.env.ids;
    size_t m = jb.env.m, ncells = m;
    if (o.nparts > 1) {
        if (o.part >= o.nparts) {
            vb_cover_tree_free(tree);
            return vb_error(ctx, VB_EMISUSE, NULL, 0, "cover part %u of %u", o.part, o.nparts);
        }
        size_t b0 = m * (size_t)o.part / o.nparts, b1 = m * ((size_t)o.part + 1) / o.nparts;
        cells += b0;
        ncells = b1 - b0;
    }
    /* Only the cells below base_limit, in the same curve order. */
    uint32_t *kept = NULL;
    if (o.base_limit) {
        kept = malloc((ncells ? ncells : 1) * sizeof *kept);
        if (!kept) {
            vb_cover_tree_free(tree);
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover)");
        }
        size_t k = 0;
        for (size_t c = 0; c < ncells; c++)
            if (cells[c] < o.base_limit)
                kept[k++] = cells[c];
        cells = kept;
        ncells = k;
    }
    int nt = vb_threads(o.threads);
    worker *w = calloc((size_t)nt, sizeof *w);
    int rc = w ? VB_OK : VB_ENOMEM;
    for (int t = 0; rc == VB_OK && t < nt; t++)
        w[t].jb = &jb;
    jb.batch = vb_cover_batch_cells(&o);
    const char *hb = getenv("VORBALL_COVER_HOST_BACK");
    jb.host_back = !(be && hb && strcmp(hb, "0") == 0);
    if (o.stream_batches) {
        jb.sink = sink;
        jb.user = user;
    }
    vb_cover_stats st;
    memset(&st, 0, sizeof st);
    for (unsigned p = 0; rc == VB_OK && p < parts; p++) {
        size_t c0 = ncells * p / parts, c1 = ncells * (p + 1) / parts;
        jb.cells = cells + c0;
        jb.ncells = c1 - c0;
        jb.base = c0;
        jb.all = ncells;
        atomic_store(&jb.covered, 0);
        if (p == 0)
            vb_progress(ctx, "cover", 0, ncells);
        double t0 = vb_now();
        if (be)
            rc = cover_hybrid(ctx, &jb, be, w, nt);
        else if (jb.ncells)
            rc = cover_host(&jb, w, nt);
        st.t_host += vb_now() - t0;
        vb_quad_list part = {0};
        if (rc == VB_OK)
            rc = gather(w, nt, &part);
        st.quads += part.n;
        if (rc == VB_OK && (part.n || !o.stream_batches))
            rc = sink(user, &part);
        vb_quad_list_free(&part);
    }
    if (rc == VB_OK)
        vb_progress(ctx, "cover", ncells, ncells);
    for (int t = 0; w && t < nt; t++) {
        vb_cover_stats_sum(&st, &w[t].st);
        vbq_arena_free(&w[t].ar);
        vb_quad_list_free(&w[t].ql);
    }
    free(w);
    free(kept);
    vb_cover_tree_free(tree);
    if (stats)
        *stats = st;
    if (rc == VB_ENOMEM)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover)");
    return rc;
}

/* vb_cover_run's sink: each part merged into the caller's list. */
static int append_part(void *user, vb_quad_list *part)
{
    vb_quad_list *out = user;
    if (out->n == 0) {
        vb_quad_list_free(out);
        *out = *part;
        memset(part, 0, sizeof *part);
        return VB_OK;
    }
    if (out->n + part->n > out->cap) {
        void *p = realloc(out->q, (out->n + part->n) * sizeof *out->q);
        if (!p)
            return VB_ENOMEM;
        out->q = p;
        out->cap = out->n + part->n;
    }
    memcpy(out->q + out->n, part->q, part->n * sizeof *out->q);
    out->n += part->n;
    return VB_OK;
}

int vb_cover_run(vb_ctx *ctx, const vb_sphere_set *set, const vb_cover_options *opt,
                 vb_cover_backend *be, vb_quad_list *out, vb_cover_stats *stats)
{
    size_t n0 = out->n;
    vb_cover_options o = opt ? *opt : (vb_cover_options){0};
    o.stream_batches = 0; /* one sorted part */
    int rc = vb_cover_run_parts(ctx, set, &o, be, 1, append_part, out, stats);
    /* Appended to earlier quadruples: the whole list made canonical again. */
    if (rc == VB_OK && n0 > 0 && vb_quad_list_canonical(out, vb_threads(o.threads)) != VB_OK)
        rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (cover)");
    return rc;
}
