/* A cover worker's arena (vbq_arena, vb_cover_shared.h): its arrays made
 * and freed; a backend closed. */
#include <stdlib.h>
#include <string.h>

#include "vb_cover.h"
#include "vb_cover_shared.h"
#include "vbq_cluster.h"

void vbq_arena_free(vbq_arena *a)
{
    free(a->nb);
    free(a->lab);
    free(a->st);
    free(a->q);
    free(a->hi);
    free(a->memo);
    free(a->memo_tag);
    vbq_cluster_memo_free(a->cmemo);
    memset(a, 0, sizeof *a);
}

int vbq_arena_make(vbq_arena *a, uint32_t nb, uint32_t lab, uint32_t st, uint32_t q)
{
    vbq_arena_free(a);
    a->nb = malloc((size_t)nb * sizeof *a->nb);
    a->lab = malloc((size_t)lab * sizeof *a->lab);
    a->st = malloc((size_t)st * sizeof *a->st);
    a->q = malloc(4 * (size_t)q * sizeof *a->q);
    a->hi = malloc((size_t)lab * sizeof *a->hi);
    a->memo = malloc(VBQ_MEMO * sizeof *a->memo);
    a->memo_tag = calloc(2u * VBQ_MEMO, sizeof *a->memo_tag);
    a->cmemo = vbq_cluster_memo_new();
    a->nb_cap = nb;
    a->lab_cap = lab;
    a->st_cap = st;
    a->q_cap = q;
    int ok = a->nb && a->lab && a->st && a->q && a->hi && a->memo && a->memo_tag && a->cmemo;
    return ok ? VB_OK : VB_ENOMEM;
}

void vb_cover_backend_close(vb_cover_backend *be)
{
    if (be && be->judge_close)
        be->judge_close(be);
    if (be && be->close)
        be->close(be);
}
