/* A sample of an input's cells covered on the host in fixed arenas: how
 * many of them run out (vb_cover.h, vb_cover_sample_over). A device sizes
 * its arenas from it before its first launch (gpu/cover_plan.c,
 * vbg_cov_fit); nothing of the output depends on it. */
#include <string.h>

#include "vb_cover.h"
#include "vb_parallel.h"

/* One job: the sample's cells j, j + step, ... below `count`, in arenas of
 * its own. */
typedef struct sample_job {
    const vbq_env *env;
    uint32_t nb, lab;
    size_t first, step, count;
    size_t over, covered;
    int rc;
} sample_job;

/* Stacks and quadruples of the sample's arenas: what the host's first try
 * takes (core/cells/cover.c); a cell past them is neither over nor counted. */
#define SAMPLE_ST 512u
#define SAMPLE_Q 512u

static void *sample_run(void *arg)
{
    sample_job *j = arg;
    vbq_arena ar;
    memset(&ar, 0, sizeof ar);
    if (vbq_arena_make(&ar, j->nb, j->lab, SAMPLE_ST, SAMPLE_Q) != VB_OK) {
        vbq_arena_free(&ar);
        j->rc = VB_ENOMEM;
        return NULL;
    }
    for (size_t k = j->first; k < j->count; k += j->step) {
        /* the k-th of `count` cells spread evenly over the tree's order */
        uint32_t i = j->env->ids[(size_t)((double)k * (double)j->env->m / (double)j->count)];
        vbq_cell_out o;
        vb_cover_cell_host(j->env, &ar, i, VBQ_ALL_ROOTS, &o);
        if (o.status == VBQ_OK || o.status == VBQ_OVER_NB || o.status == VBQ_OVER_LAB) {
            j->covered++;
            j->over += o.status != VBQ_OK;
        }
    }
    vbq_arena_free(&ar);
    return NULL;
}

int vb_cover_sample_over(const vbq_env *env, size_t want, uint32_t nb, uint32_t lab, int threads,
                         size_t *covered, size_t *over)
{
    *covered = *over = 0;
    size_t count = want < env->m ? want : env->m;
    if (count == 0 || nb == 0 || lab == 0)
        return VB_OK;
    sample_job jobs[VB_MAX_THREADS];
    int nt = threads < 1 ? 1 : threads > VB_MAX_THREADS ? VB_MAX_THREADS : threads;
    nt = (size_t)nt < count ? nt : (int)count;
    for (int t = 0; t < nt; t++)
        jobs[t] = (sample_job){env, nb, lab, (size_t)t, (size_t)nt, count, 0, 0, VB_OK};
    vb_run_jobs(sample_run, jobs, sizeof jobs[0], nt);
    int rc = VB_OK;
    for (int t = 0; t < nt; t++) {
        *covered += jobs[t].covered;
        *over += jobs[t].over;
        rc = rc != VB_OK ? rc : jobs[t].rc;
    }
    return rc;
}
