/* The cover backend's launches (gpu/cover_ocl.c is its host side): one
 * launch of a tier's kernel over a run of tasks, its arguments, its clock,
 * and the read-back of the per-task results and the quadruples. */

#include "vb_array.h"
#include "vb_parallel.h"
#include "vbg_buffer.h"
#include "vbg_cover_state.h"

static int set_arg(vb_ctx *ctx, cl_kernel k, cl_uint i, size_t size, const void *v)
{
    return vbg_check(ctx, clSetKernelArg(k, i, size, v), "clSetKernelArg");
}

/* Appends room for n more quadruples to host_q. */
int vbg_cov_host_q_room(vb_ctx *ctx, cov_state *s, size_t n)
{
    s->host_q = vb_array_grow(s->host_q, &s->host_q_cap, s->host_nq + n, 4 * sizeof *s->host_q,
                              4096);
    if (s->host_q_cap < s->host_nq + n)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (quadruples)");
    return VB_OK;
}

/* The step of the clocks a launch of tier t counts in: the tier's, or the
 * reruns' while rerun_hand_short runs the first tier again. */
static size_t clock_step(const cov_state *s, const cov_tier *t)
{
    return s->rerun ? VB_COVER_RERUN : (size_t)(t - s->tier);
}

/* The kernel's run time of one launch of tier t (event profiling; the
 * queue is made with it) into its step's clocks (vbg_cover_state.h); a
 * device that gives no times adds none. Its tasks' work from their
 * results out[0 .. ntasks) (vb_cover_clocks): a task that ran out of room
 * (neither finished nor past the group kernel's budget, whose patches the
 * host resumes) is covered again from its roots elsewhere. */
static void tier_clock(cov_state *s, const cov_tier *t, cl_event done, const vbq_cell_out *out,
                       size_t ntasks)
{
    size_t i = clock_step(s, t);
    vb_cover_clocks *c = s->clocks;
    c->launches[i]++;
    c->tasks[i] += ntasks;
    c->kernel_s[i] += vbg_event_seconds(done);
    for (size_t k = 0; k < ntasks; k++) {
        uint64_t p = out[k].patches;
        c->patches[i] += p;
        c->task_max[i] = p > c->task_max[i] ? p : c->task_max[i];
        if (out[k].status != VBQ_OK && out[k].status != VBQ_BUDGET) {
            c->wasted_patches[i] += p;
            c->wasted_tasks[i]++;
        } else if (i == COV_FIRST) {
            const vbq_cell_out *o = &out[k];
            c->first_nb_max = o->nnb > c->first_nb_max ? o->nnb : c->first_nb_max;
            c->first_lab_max = o->lab_hw > c->first_lab_max ? o->lab_hw : c->first_lab_max;
            c->first_q_max = o->nq > c->first_q_max ? o->nq : c->first_q_max;
            c->first_past_half += 2 * (uint64_t)o->nnb > t->nb_cap ||
                                  2 * (uint64_t)o->lab_hw > t->lab_cap;
        }
    }
}

/* The launch's handed patches (the first `words` words of s->hand, whole
 * entries) appended to s->host_hand: those of cells that finished
 * (VBQ_OK), each frame's off made the cell's sphere; the others' cells are
 * covered whole on the host. */
static int read_hand(vb_ctx *ctx, cov_state *s, const uint32_t *cells, size_t ncells,
                     const vbq_cell_out *out, size_t words)
{
    s->host_hand = vb_array_grow(s->host_hand, &s->host_hand_cap, s->host_hand_n + words,
                                 sizeof *s->host_hand, 4096);
    if (s->host_hand_cap < s->host_hand_n + words)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory (handed patches)");
    uint32_t *h = s->host_hand + s->host_hand_n;
    int rc = vbg_check(ctx,
                       clEnqueueReadBuffer(vbg_runtime_queue(s->rt), s->hand.mem, CL_TRUE, 0,
                                           words * sizeof *h, h, 0, NULL, NULL),
                       "read handed patches");
    size_t kept = 0;
    if (rc == VB_OK && vb_hand_keep_finished(h, words, cells, ncells, out, &kept) != VB_OK)
        return vb_error(ctx, VB_EINTERNAL, NULL, 0, "bad handed patch");
    s->host_hand_n += kept;
    return rc;
}

/* One launch of tier t over the tasks (cells[k], roots[k]) for k <
 * ncells: out[k] and the quadruples appended to host_q (out[k].qoff made
 * relative to host_q). ncells * vbg_cov_task_bytes(t) fits the launch room. */
static int launch_tier(vb_ctx *ctx, cov_state *s, cov_tier *t, const uint32_t *cells,
                       const uint32_t *roots, size_t ncells, vbq_cell_out *out)
{
    cl_command_queue q = vbg_runtime_queue(s->rt);
    size_t qroom, hwords;
    vbg_cov_launch_sizes(s, t, ncells, &qroom, &hwords);
    int hand = s->k_hand && t == &s->tier[COV_FIRST];
    int rc = vbg_cov_tier_bind(ctx, s, t);
    if (rc == VB_OK)
        rc = vbg_cov_upload(ctx, s, &s->cells, cells, ncells * sizeof(uint32_t));
    if (rc == VB_OK)
        rc = vbg_cov_upload(ctx, s, &s->roots, roots, ncells * sizeof(uint32_t));
    if (rc == VB_OK)
        rc = vbg_cov_ensure(ctx, s, &s->outs, ncells * sizeof(vbq_cell_out), CL_MEM_READ_WRITE);
    if (rc == VB_OK)
        rc = vbg_cov_ensure(ctx, s, &s->qout, 4 * qroom * sizeof(uint32_t), CL_MEM_READ_WRITE);
    if (rc == VB_OK && hand && hwords)
        rc = vbg_cov_ensure(ctx, s, &s->hand, hwords * sizeof(uint32_t), CL_MEM_READ_WRITE);
    cl_uint zero[4] = {0, 0, 0, 0};
    if (rc == VB_OK)
        rc = vbg_check(ctx,
                       clEnqueueWriteBuffer(q, s->counters.mem, CL_TRUE, 0, sizeof zero, zero, 0,
                                            NULL, NULL),
                       "clEnqueueWriteBuffer");
    const vbq_env *e = &s->env;
    cl_uint nc = (cl_uint)ncells, qcap = (cl_uint)qroom, hcap = (cl_uint)hwords;
    cl_uint nbc = t->nb_cap, labc = t->lab_cap, stc = t->st_cap, qc = t->q_cap;
    cl_uint a = 0;
    cl_kernel k = t->k;
    if (rc == VB_OK)
        rc = set_arg(ctx, k, a++, sizeof(cl_mem), &s->x.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->y.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->z.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->r.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->box.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->rmax.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->ids.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->first) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->m) ||
             set_arg(ctx, k, a++, sizeof(cl_double), &e->rmax_all) ||
             set_arg(ctx, k, a++, sizeof(cl_double), &e->near) ||
             set_arg(ctx, k, a++, sizeof(cl_double), &e->tmax) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->T) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->min_level) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->max_level) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &e->enum_max) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->cells.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->roots.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &nc) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &t->nb.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &t->lab.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &t->st.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &t->q.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &nbc) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &labc) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &stc) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &qc) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->outs.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->qout.mem) ||
             set_arg(ctx, k, a++, sizeof(cl_uint), &qcap) ||
             set_arg(ctx, k, a++, sizeof(cl_mem), &s->counters.mem) ||
             (t->wg && set_arg(ctx, k, a++, sizeof(cl_uint), &t->budget)) ||
             (s->k_caches && k == s->k &&
              (set_arg(ctx, k, a++, sizeof(cl_mem), t->caches ? &t->hi.mem : NULL) ||
               set_arg(ctx, k, a++, sizeof(cl_mem), t->caches ? &t->memo.mem : NULL) ||
               set_arg(ctx, k, a++, sizeof(cl_mem), t->caches ? &t->memo_tag.mem : NULL))) ||
             (s->k_hand && k == s->k &&
              (set_arg(ctx, k, a++, sizeof(cl_mem), hand && hwords ? &s->hand.mem : NULL) ||
               set_arg(ctx, k, a++, sizeof(cl_uint), &hcap)))
                 ? VB_EDEVICE
                 : VB_OK;
    size_t local, global;
    if (t->wg) {
        local = COV_WG;
        global = (t->slices < ncells ? t->slices : ncells) * COV_WG;
    } else if (t->solo) {
        local = 1;
        global = t->slices < ncells ? t->slices : ncells;
    } else {
        local = t->slices < 64 ? t->slices : 64;
        global = t->slices < ncells ? t->slices : ncells;
        global = (global + local - 1) / local * local;
        if (global > t->slices)
            global = t->slices; /* a multiple of local by construction */
    }
    cl_event done = NULL;
    if (rc == VB_OK)
        rc = vbg_check(ctx,
                       clEnqueueNDRangeKernel(q, k, 1, NULL, &global, &local, 0, NULL, &done),
                       "cover kernel");
    if (rc == VB_OK)
        rc = vbg_check(ctx,
                       clEnqueueReadBuffer(q, s->outs.mem, CL_TRUE, 0,
                                           ncells * sizeof(vbq_cell_out), out, 0, NULL, NULL),
                       "cover kernel");
    if (done) {
        if (rc == VB_OK)
            tier_clock(s, t, done, out, ncells);
        clReleaseEvent(done);
    }
    cl_uint counters[4] = {0, 0, 0, 0};
    if (rc == VB_OK)
        rc = vbg_check(ctx,
                       clEnqueueReadBuffer(q, s->counters.mem, CL_TRUE, 0, sizeof counters,
                                           counters, 0, NULL, NULL),
                       "read counters");
    size_t nq = counters[1] < qroom ? counters[1] : qroom;
    if (rc == VB_OK)
        rc = vbg_cov_host_q_room(ctx, s, nq);
    if (rc == VB_OK && nq)
        rc = vbg_check(ctx,
                       clEnqueueReadBuffer(q, s->qout.mem, CL_TRUE, 0, 4 * nq * sizeof(uint32_t),
                                           s->host_q + 4 * s->host_nq, 0, NULL, NULL),
                       "read quadruples");
    if (rc == VB_OK && hand && counters[3])
        rc = read_hand(ctx, s, cells, ncells, out, counters[3]);
    if (rc != VB_OK) {
        clFinish(q); /* nothing half-done may reach the caller */
        return rc;
    }
    if (hand && counters[2] > hwords) {
        s->hand_want = (size_t)counters[2] + counters[2] / 4;
        s->hand_short = 1;
    }
    for (size_t c = 0; c < ncells; c++)
        if (out[c].status == VBQ_OK)
            out[c].qoff += (uint32_t)s->host_nq;
    s->host_nq += nq;
    /* The next batch gets room for what this one needed. */
    if (counters[1] > qroom)
        s->qout_cap = counters[1] + counters[1] / 4;
    return VB_OK;
}

/* Tier t over the tasks (cells[k], roots[k]) for k < ncells, in as many
 * launches as the launch room needs (launch_tier). */
int vbg_cov_run_tier(vb_ctx *ctx, cov_state *s, cov_tier *t, const uint32_t *cells,
                    const uint32_t *roots, size_t ncells, vbq_cell_out *out)
{
    size_t chunk = s->launch_room / vbg_cov_task_bytes(t);
    chunk = chunk ? chunk : 1;
    int rc = VB_OK;
    for (size_t k0 = 0; rc == VB_OK && k0 < ncells; k0 += chunk) {
        size_t nk = ncells - k0 < chunk ? ncells - k0 : chunk;
        double t0 = vb_now();
        rc = launch_tier(ctx, s, t, cells + k0, roots + k0, nk, out + k0);
        s->clocks->launch_s[clock_step(s, t)] += vb_now() - t0;
    }
    return rc;
}
