/* The pore stage of a frame (vbc_pore_frame.h): axis candidates, the sweep
 * in the molecule's mask, the verdict; the pore's entry in the table and
 * the refined bottlenecks are channel_pore_table.c's. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"
#include "vb_parallel.h"
#include "vbc_pore_frame.h"
#include "vbc_walls.h"

typedef vbc_mask_view mask_view;

int vbc_mask_outside(void *user, const double p[3])
{
    const mask_view *M = user;
    const vbc_grid *g = M->g;
    long idx[3];
    int n[3] = {g->nx, g->ny, g->nz};
    for (int a = 0; a < 3; a++) {
        double f = floor((p[a] - g->origin[a]) / g->h);
        if (!(f >= 0.0) || f >= (double)n[a])
            return 1;
        idx[a] = (long)f;
    }
    size_t v = (size_t)idx[0] + (size_t)g->nx * ((size_t)idx[1] + (size_t)g->ny * (size_t)idx[2]);
    return (M->flags[v] & VBC_F_MOLECULAR) == 0;
}

static int sweep(vb_ctx *ctx, const vbc_cells *cells, const vb_sphere_set *s, const vbc_axis *ax,
                 const vbc_pore_request *req, mask_view *M, vbc_pore *out)
{
    return vbc_pore_sweep(ctx, cells, s, ax, &req->sweep, M->flags ? vbc_mask_outside : NULL, M, out);
}

/* sweep for a pore wider than floor only (vbc_pore_sweep_above). */
static int sweep_above(vb_ctx *ctx, const vbc_cells *cells, const vb_sphere_set *s,
                       const vbc_axis *ax, const vbc_pore_request *req, mask_view *M, double floor,
                       vbc_pore *out)
{
    return vbc_pore_sweep_above(ctx, cells, s, ax, &req->sweep, M->flags ? vbc_mask_outside : NULL, M,
                                floor, out);
}

static int open_pore(const vbc_pore *p)
{
    /* More than the start: a start outside the molecule is no pore. */
    return p->n > 1 && p->pts[p->min_at].r > 0.0 && p->open_lo && p->open_hi;
}

/* The widest through channel's axis: its end-to-end direction through its
 * bottleneck. Returns 0 when there is none. */
static int channel_axis(const vbc_result *res, vbc_axis *ax)
{
    const vbc_channel *best = NULL;
    for (size_t t = 0; t < res->nchannels; t++) {
        const vbc_channel *c = &res->channels[t];
        if (c->kind == VBC_CHANNEL && c->through && (!best || c->bottleneck > best->bottleneck))
            best = c;
    }
    if (!best || best->npoints < 2)
        return 0;
    const vbc_point *a = &res->points[best->first_point], *b = a + best->npoints - 1;
    const vbc_point *m = a + best->bottleneck_at;
    double d[3] = {b->x - a->x, b->y - a->y, b->z - a->z};
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(len > 0.0))
        return 0;
    memset(ax, 0, sizeof *ax);
    for (int k = 0; k < 3; k++)
        ax->u[k] = d[k] / len;
    ax->c[0] = m->x;
    ax->c[1] = m->y;
    ax->c[2] = m->z;
    ax->source = VBC_AXIS_CHANNEL;
    snprintf(ax->why, sizeof ax->why, "the widest through channel of the discrete analysis");
    return 1;
}

/* Sweeps that the choice below takes in any case run at once, each on its
 * own thread (vb_run_jobs), and are then judged in their order: the same
 * pores as one after the other. A job reports no error to the context
 * (which is not shared between threads); the caller does. */
typedef struct {
    const vbc_cells *cells;
    const vb_sphere_set *s;
    vbc_axis ax;
    const vbc_pore_request *req;
    mask_view *M;
    int widest_first; /* a subunit: first its widest place near the centroid */
    double floor;     /* only a pore wider than this is wanted (vbc_pore_sweep_above) */
    vbc_pore pore;
    int rc;
} sweep_job;

static void sweep_job_set(sweep_job *J, const vbc_cells *cells, const vb_sphere_set *s,
                          const vbc_axis *ax, const vbc_pore_request *req, mask_view *M,
                          int widest_first)
{
    memset(J, 0, sizeof *J);
    J->cells = cells;
    J->s = s;
    J->ax = *ax;
    J->req = req;
    J->M = M;
    J->widest_first = widest_first;
    J->floor = -INFINITY;
    J->rc = VB_OK;
}

static void *sweep_job_run(void *arg)
{
    sweep_job *J = arg;
    if (J->widest_first) {
        int32_t atom;
        vbc_plane_widest(J->cells, J->ax.u, VBC_SUBUNIT_REACH, J->M->flags ? vbc_mask_outside : NULL,
                         J->M, J->ax.c, &atom);
    }
    J->rc = sweep_above(NULL, J->cells, J->s, &J->ax, J->req, J->M, J->floor, &J->pore);
    return NULL;
}

/* Runs the n jobs (at once when there are threads to spare); returns the
 * first failure, reported to ctx, with every pore freed, else VB_OK. */
static int sweep_jobs(vb_ctx *ctx, sweep_job *J, int n)
{
    if (n > 1 && vb_threads(0) > 1)
        vb_run_jobs(sweep_job_run, J, sizeof *J, n);
    else
        for (int k = 0; k < n; k++)
            sweep_job_run(&J[k]);
    int bad = vb_jobs_first_error(J, sizeof *J, n, offsetof(sweep_job, rc), VB_JOBS_UNORDERED);
    if (bad < 0)
        return VB_OK;
    int rc = J[bad].rc;
    for (int j = 0; j < n; j++)
        vbc_pore_free(&J[j].pore);
    return vb_error(ctx, rc, NULL, 0, "pore sweep (%s)",
                    rc == VB_ENOMEM ? "out of memory" : vb_errstr(rc));
}

/* The subunits' search: the widest open path of sub[0..n) wider than
 * need (ties to the earlier chain) in *best (*have), each sweep giving up
 * where it cannot beat the need so far (it would not be taken); with
 * judge_each, only a path that is a pore by the verdict counts (its
 * verdict kept in *best). Returns VB_OK or the first failure, reported. */
static int subunit_search(vb_ctx *ctx, const vbc_cells *cells, const vb_sphere_set *s,
                          const vbc_pore_request *req, mask_view *M, const vbc_axis *sub, int n,
                          double need, int judge_each, vbc_pore *best, int *have)
{
    *have = 0;
    for (int k = 0; k < n; k++) {
        sweep_job J;
        sweep_job_set(&J, cells, s, &sub[k], req, M, 1);
        J.floor = need;
        int rc = sweep_jobs(ctx, &J, 1);
        vbc_pore *p = &J.pore;
        double r = rc == VB_OK && p->n ? p->pts[p->min_at].r : 0.0;
        vbc_pore_verdict v = {0, 0.0, 0, 0, 1};
        if (rc == VB_OK && judge_each && open_pore(p) && r > need &&
            vbc_pore_judge(cells, p, VBC_PORE_MIN_BURIED, &v) != 0)
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "pore verdict");
        if (rc != VB_OK) {
            vbc_pore_free(p);
            if (*have)
                vbc_pore_free(best);
            *have = 0;
            return rc;
        }
        if (open_pore(p) && r > need && v.is_pore) {
            if (*have)
                vbc_pore_free(best);
            *best = *p;
            best->judged = judge_each;
            best->is_pore = v.is_pore;
            best->buried = v.buried;
            *have = 1;
            need = r;
        } else {
            vbc_pore_free(p);
        }
    }
    return VB_OK;
}

/* The widest open pore of one subunit replaces the nearly closed central
 * one *out when it is clearly wider and a pore by the verdict (the rule in
 * vbc_pore.h; a path beside a tetrameric channel's closed gate, through a
 * voltage sensor's crevice or along the outside, is none, and the closed
 * gate stays the pore); ties go to the earlier chain. The search runs
 * without the verdict first and judges its winner: when that is a pore it
 * is also the widest path that is one (the answer of judging each), else
 * the search runs again judging each path. */
static int subunit_pore(vb_ctx *ctx, const vbc_cells *cells, const vb_sphere_set *s,
                        const vbc_pore_request *req, mask_view *M, vbc_pore *out)
{
    vbc_axis sub[16];
    int n = vbc_axis_subunits(s, &out->axis, sub, 16), have;
    double need = fmax(VBC_SUBUNIT_MIN_RADIUS, 2.0 * out->pts[out->min_at].r);
    vbc_pore best;
    for (int judge_each = 0; judge_each < 2; judge_each++) {
        int rc = subunit_search(ctx, cells, s, req, M, sub, n, need, judge_each, &best, &have);
        if (rc != VB_OK) {
            vbc_pore_free(out);
            return rc;
        }
        if (!have)
            return VB_OK;
        if (!judge_each) {
            vbc_pore_verdict v;
            if (vbc_pore_judge(cells, &best, VBC_PORE_MIN_BURIED, &v) != 0) {
                vbc_pore_free(&best);
                vbc_pore_free(out);
                return vb_error(ctx, VB_ENOMEM, NULL, 0, "pore verdict");
            }
            best.judged = 1; /* the stage's verdict, not taken twice */
            best.is_pore = v.is_pore;
            best.buried = v.buried;
            if (!v.is_pore) {
                vbc_pore_free(&best);
                continue;
            }
        }
        vbc_pore_free(out);
        *out = best;
        return VB_OK;
    }
    return VB_OK;
}

/* The pore of a barrel: its fitted axis only approximates the pore's (a
 * porin's cross-section is no circle, its loops not symmetric), and a plane
 * a few degrees off the pore cuts its constriction obliquely (maltoporin:
 * 3.4 degrees off takes the bottleneck from 2.04 to 1.47 A). So the fitted
 * direction and VBC_BARREL_CONE directions around it at VBC_BARREL_TILT
 * degrees are swept, each from the widest place near the barrel's centre
 * (a loop may fill the centre), and the open one with the widest
 * bottleneck is the pore (ties to the fitted axis, then ring order). */
static int barrel_pore(vb_ctx *ctx, const vbc_cells *cells, const vb_sphere_set *s,
                       const vbc_axis *ax, const vbc_pore_request *req, mask_view *M, vbc_pore *out)
{
    sweep_job J[1 + VBC_BARREL_CONE];
    double e1[3], e2[3], t = VBC_BARREL_TILT * acos(-1.0) / 180.0;
    int best = 0;
    /* A basis of the plane normal to the axis, as vbc_axis_barrel's. */
    double a[3] = {0.0, 0.0, 0.0};
    a[fabs(ax->u[0]) < 0.6 ? 0 : fabs(ax->u[1]) < 0.6 ? 1 : 2] = 1.0;
    double d = a[0] * ax->u[0] + a[1] * ax->u[1] + a[2] * ax->u[2], n = 0.0;
    for (int k = 0; k < 3; k++) {
        e1[k] = a[k] - d * ax->u[k];
        n += e1[k] * e1[k];
    }
    for (int k = 0; k < 3; k++)
        e1[k] /= sqrt(n);
    e2[0] = ax->u[1] * e1[2] - ax->u[2] * e1[1];
    e2[1] = ax->u[2] * e1[0] - ax->u[0] * e1[2];
    e2[2] = ax->u[0] * e1[1] - ax->u[1] * e1[0];
    for (int j = 0; j <= VBC_BARREL_CONE; j++) {
        vbc_axis b = *ax;
        if (j > 0) {
            double phi = 2.0 * acos(-1.0) * (j - 1) / VBC_BARREL_CONE;
            for (int k = 0; k < 3; k++)
                b.u[k] = cos(t) * ax->u[k] + sin(t) * (cos(phi) * e1[k] + sin(phi) * e2[k]);
            size_t w = strlen(b.why);
            snprintf(b.why + w, sizeof b.why - w, ", tilted %.0f deg to its widest pore",
                     VBC_BARREL_TILT);
        }
        sweep_job_set(&J[j], cells, s, &b, req, M, 1);
        /* One after the other: once the best so far is open, a direction
         * gives up where it cannot be wider (it would not be taken). */
        const vbc_pore *q = &J[best].pore;
        if (j > 0 && open_pore(q))
            J[j].floor = q->pts[q->min_at].r;
        int rc = sweep_jobs(ctx, &J[j], 1);
        if (rc != VB_OK) {
            for (int k = 0; k < j; k++)
                vbc_pore_free(&J[k].pore);
            return rc;
        }
        const vbc_pore *p = &J[j].pore;
        if (j > 0 && open_pore(p) && (!open_pore(q) || p->pts[p->min_at].r > q->pts[q->min_at].r)) {
            vbc_pore_free(&J[best].pore);
            best = j;
        } else if (j > 0) {
            vbc_pore_free(&J[j].pore);
        }
    }
    *out = J[best].pore;
    return VB_OK;
}

/* The membrane's normal (cand[0]) gives way to a symmetry axis (three or
 * more chains) or a barrel axis within VBC_MEMBRANE_AGREE degrees of it:
 * the same direction, fitted to the channel itself, with its own pore
 * search (the subunits, the barrel's cone). Returns the candidates left. */
static int membrane_defers(vbc_axis *cand, int *force, int nc)
{
    for (int k = 1; k < nc; k++) {
        int fitted = force[k] || cand[k].source == VBC_AXIS_BARREL;
        double d = fabs(cand[0].u[0] * cand[k].u[0] + cand[0].u[1] * cand[k].u[1] +
                        cand[0].u[2] * cand[k].u[2]);
        if (!fitted || d < cos(VBC_MEMBRANE_AGREE * acos(-1.0) / 180.0))
            continue;
        size_t w = strlen(cand[k].why);
        snprintf(cand[k].why + w, sizeof cand[k].why - w, "; %.0f deg off the membrane normal",
                 acos(fmin(d, 1.0)) * 180.0 / acos(-1.0));
        memmove(cand, cand + 1, (size_t)(nc - 1) * sizeof *cand);
        memmove(force, force + 1, (size_t)(nc - 1) * sizeof *force);
        return nc - 1;
    }
    return nc;
}

/* The refinement of the discrete channels running beside the pore's
 * search (vbc_pore_stage): find waits for it only where it reads the
 * channels, at the candidate of the widest through channel. */
typedef struct {
    vbc_result *res;
    const vbc_cells *cells;
    double h;
    double ms;       /* its wall time */
    int running;     /* started on a thread of its own, not joined yet */
    vb_jobs th;
    const vbc_pore_before *before; /* fills res first (NULL: res is filled) */
    int before_rc;   /* its status; the refinement is skipped after a failure */
} refine_job;

static void *refine_job_run(void *arg)
{
    refine_job *R = arg;
    if (R->before && (R->before_rc = R->before->run(R->before->arg)) != VB_OK)
        return NULL;
    double t0 = vb_now();
    vbc_refine_bottlenecks(R->res, R->cells, R->h);
    R->ms = 1e3 * (vb_now() - t0);
    return NULL;
}

/* The refinement done (joined when it ran beside). NULL: nothing runs.
 * Returns the ms waited for it. */
static double refine_wait(refine_job *R)
{
    double t = vb_now();
    if (R && R->running) {
        vb_jobs_join(&R->th);
        R->running = 0;
    }
    return 1e3 * (vb_now() - t);
}

static int pore_find(vb_ctx *ctx, const vbc_grid *g, const uint8_t *flags, const vbc_cells *cells,
                     const vb_sphere_set *s, const vbc_result *res, const vbc_pore_request *req,
                     refine_job *refine, vbc_pore *out);

int vbc_pore_find(vb_ctx *ctx, const vbc_grid *g, const uint8_t *flags, const vbc_cells *cells,
                  const vb_sphere_set *s, const vbc_result *res, const vbc_pore_request *req,
                  vbc_pore *out)
{
    return pore_find(ctx, g, flags, cells, s, res, req, NULL, out);
}

static int pore_find(vb_ctx *ctx, const vbc_grid *g, const uint8_t *flags, const vbc_cells *cells,
                     const vb_sphere_set *s, const vbc_result *res, const vbc_pore_request *req,
                     refine_job *refine, vbc_pore *out)
{
    memset(out, 0, sizeof *out);
    mask_view M = {g, flags};
    double centroid[3] = {0.0, 0.0, 0.0};
    for (size_t i = 0; i < s->n; i++) {
        centroid[0] += s->x[i];
        centroid[1] += s->y[i];
        centroid[2] += s->z[i];
    }
    for (int k = 0; k < 3; k++)
        centroid[k] /= (double)s->n;
    if (req->have_axis) {
        vbc_axis ax;
        memset(&ax, 0, sizeof ax);
        memcpy(ax.u, req->u, sizeof ax.u);
        memcpy(ax.c, req->have_through ? req->c : centroid, sizeof ax.c);
        ax.source = req->found_source ? req->found_source : VBC_AXIS_GIVEN;
        ax.chains = req->found_chains;
        if (req->found_source)
            snprintf(ax.why, sizeof ax.why, "%s", req->found_why);
        else
            snprintf(ax.why, sizeof ax.why, "given (--axis%s)", req->have_through ? ", --through" : "");
        return sweep(ctx, cells, s, &ax, req, &M, out);
    }
    /* Candidates in the order of vbc_pore.h; the first open one wins. */
    vbc_axis cand[8];
    int force[8] = {0}, nc = 0;
    int membrane = req->have_membrane;
    if (membrane) {
        cand[nc] = req->membrane;
        memcpy(cand[nc++].c, centroid, sizeof centroid);
    }
    if (vbc_axis_symmetry(s, &cand[nc])) {
        force[nc++] = 1;
    } else if (vbc_axis_from_chains(s, &cand[nc])) {
        force[nc] = cand[nc].chains >= 3;
        nc++;
    }
    if (!(nc > membrane && force[membrane]) && vbc_axis_barrel(s, NULL, &cand[nc]))
        nc++;
    /* Across a membrane no channel or principal axis: the normal stays. */
    /* The widest through channel's candidate is made where the loop
     * reaches it (the refinement moves the points it reads): a slot held
     * here, dropped there when there is no such channel. */
    int channel_at = -1;
    if (!membrane) {
        memset(&cand[nc], 0, sizeof cand[nc]);
        cand[nc].source = VBC_AXIS_CHANNEL;
        channel_at = nc++;
    }
    if (!membrane) {
        vbc_axis_principal(s, &cand[nc]);
        nc += 3;
    }
    if (membrane)
        nc = membrane_defers(cand, force, nc);
    if (req->have_through)
        for (int k = 0; k < nc; k++)
            memcpy(cand[k].c, req->c, sizeof req->c);
    int have = 0;
    /* Once the loop reaches the principal axes (the last three) it judges
     * all three (no break among them), so they are swept at once. */
    sweep_job J[3];
    int first_principal = membrane ? nc : nc - 3, swept = 0;
    for (int k = 0; k < nc; k++) {
        vbc_pore p;
        int rc;
        if (k == channel_at) {
            refine_wait(refine);
            if (!channel_axis(res, &cand[k]))
                continue;
            if (req->have_through)
                memcpy(cand[k].c, req->c, sizeof req->c);
        }
        if (k < first_principal && cand[k].source == VBC_AXIS_BARREL && !req->have_through) {
            if ((rc = barrel_pore(ctx, cells, s, &cand[k], req, &M, &p)) != VB_OK) {
                vbc_pore_free(out);
                return rc;
            }
        } else if (k < first_principal) {
            rc = sweep(ctx, cells, s, &cand[k], req, &M, &p);
        } else {
            if (!swept) {
                for (int j = 0; j < 3; j++)
                    sweep_job_set(&J[j], cells, s, &cand[first_principal + j], req, &M, 0);
                rc = sweep_jobs(ctx, J, 3);
                swept = 1;
                if (rc != VB_OK) {
                    vbc_pore_free(out);
                    return rc;
                }
            }
            p = J[k - first_principal].pore;
            rc = VB_OK;
        }
        if (rc != VB_OK) {
            vbc_pore_free(out);
            return rc;
        }
        int better;
        if (!have)
            better = 1;
        else if (cand[k].source == VBC_AXIS_PRINCIPAL && out->axis.source == VBC_AXIS_PRINCIPAL)
            /* Among the principal axes: open first, then the widest constriction. */
            better = (open_pore(&p) && !open_pore(out)) ||
                     (open_pore(&p) == open_pore(out) && p.pts[p.min_at].r > out->pts[out->min_at].r);
        else
            /* A closed membrane normal gives way to the symmetry axis (its subunits). */
            better = (open_pore(&p) && !open_pore(out)) ||
                     (force[k] && out->axis.source == VBC_AXIS_MEMBRANE && !open_pore(out));
        if (better) {
            vbc_pore_free(out);
            *out = p;
            have = 1;
        } else {
            vbc_pore_free(&p);
        }
        if (force[k] || (open_pore(out) && out->axis.source != VBC_AXIS_PRINCIPAL))
            break;
    }
    if (have && !req->have_through &&
        (out->axis.source == VBC_AXIS_CHAINS || out->axis.source == VBC_AXIS_SYMMETRY) &&
        out->axis.chains >= 3 &&
        out->pts[out->min_at].r < VBC_SUBUNIT_CENTRAL_MAX)
        return subunit_pore(ctx, cells, s, req, &M, out);
    return VB_OK;
}

int vbc_pore_stage(vb_ctx *ctx, const vbc_grid *g, const uint8_t *flags, const vb_sphere_set *s,
                   const vbc_pore_request *req, const vbc_walls_engine *walls,
                   double lining_tol, vbc_result *res, vbc_axis *found, vbc_pore_ms *ms)
{
    return vbc_pore_stage_after(ctx, g, flags, s, req, walls, lining_tol, res, found, ms, NULL);
}

int vbc_pore_stage_after(vb_ctx *ctx, const vbc_grid *g, const uint8_t *flags, const vb_sphere_set *s,
                         const vbc_pore_request *req, const vbc_walls_engine *walls,
                         double lining_tol, vbc_result *res, vbc_axis *found, vbc_pore_ms *ms,
                         const vbc_pore_before *before)
{
    vbc_pore_ms t = {0.0, 0.0, 0.0, 0.0, 0.0};
    double t0 = vb_now();
    vbc_cells *cells = NULL;
    int rc = vbc_cells_build(ctx, s, 3.0, &cells);
    if (rc != VB_OK) {
        /* What fills res still runs: its status comes first, as when it
         * runs before this stage. */
        int brc = before ? before->run(before->arg) : VB_OK;
        return brc != VB_OK ? brc : rc;
    }
    double t1 = vb_now();
    t.cells = 1e3 * (t1 - t0);
    /* The refinement moves the discrete channels' points, which the pore's
     * search reads only at the through channel's candidate (it waits for
     * it there) and the table's steps after the verdict: with threads to
     * spare (vbc_pore_threads' rule) it runs beside the search. */
    refine_job R = {res, cells, g->h, 0.0, 0, {0}, before, VB_OK};
    int beside = req && req->enabled && vb_threads(0) >= VBC_PORE_MIN_THREADS;
    if (beside) {
        vb_jobs_start(&R.th, refine_job_run, &R, sizeof R, 1);
        R.running = 1;
    } else {
        refine_job_run(&R);
    }
    t0 = vb_now();
    double waited = 0.0;
    if (found)
        memset(found, 0, sizeof *found);
    if (req && req->enabled) {
        vbc_pore p;
        rc = pore_find(ctx, g, flags, cells, s, res, req, &R, &p);
        t1 = vb_now();
        t.sweep = 1e3 * (t1 - t0);
        /* A path along an axis the user gave is reported as it is; a found
         * one only when it is a pore (the verdict, vbc_pore.h). */
        vbc_pore_verdict v = {0, 0.0, 0, 0, 1};
        int judge = !(req->have_axis && !req->found_source);
        /* The verdict alone: a pore's planes past VBC_PORE_MIN_BURIED of
         * walled run are not flooded (their buried length is never shown). */
        if (rc == VB_OK && p.n > 0 && judge && p.judged) {
            v.is_pore = p.is_pore;
            v.buried = p.buried;
        } else if (rc == VB_OK && p.n > 0 && judge &&
                   vbc_pore_judge_on(walls, cells, &p, VBC_PORE_MIN_BURIED, &v) != 0) {
            rc = vb_error(ctx, VB_ENOMEM, NULL, 0, "pore verdict");
        }
        t0 = vb_now();
        t.verdict = 1e3 * (t0 - t1);
        /* The pore's lining reads the cell list only: made before the
         * wait, beside the analysis when that runs longer. */
        int32_t *lining = NULL;
        size_t nlining = 0;
        int lined = rc == VB_OK && p.n > 0 && v.is_pore
                        ? vbc_pore_lining(&p, cells, lining_tol, &lining, &nlining)
                        : VB_ENOMEM;
        waited = refine_wait(&R);
        if (R.before_rc != VB_OK)
            rc = R.before_rc;
        if (rc == VB_OK && p.n > 0 && v.is_pore) {
            rc = lined == VB_OK ? vbc_result_add_pore_lined(ctx, res, &p, lining, nlining)
                                : vb_error(ctx, VB_ENOMEM, NULL, 0, "pore of %zu points", p.n);
            lining = NULL;
            if (found)
                *found = p.axis;
        }
        free(lining);
        if (rc == VB_OK && p.n > 0 && judge) {
            res->pore.judged = 1;
            res->pore.buried = v.buried;
            res->pore.rejected_source = v.is_pore ? 0 : p.axis.source;
        }
        vbc_pore_free(&p);
    }
    waited += refine_wait(&R);
    if (R.before_rc != VB_OK)
        rc = R.before_rc;
    t.refine = R.ms;
    if (rc == VB_OK)
        vbc_rank(res);
    vbc_cells_free(cells);
    /* Less the wait for the refinement (and what fills res before it). */
    t.lining = 1e3 * (vb_now() - t0) - waited;
    if (ms)
        *ms = t;
    return rc;
}
