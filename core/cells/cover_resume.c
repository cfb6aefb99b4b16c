/* The host's side of a CPU device's hand-off (VBQ_HANDOFF,
 * core/cells/vbq_gather_shared.h): the patches the device's kernel did not
 * decide (a tie cluster, an envelope past its double filter), each with
 * the list it had when popped, covered alone on the host (vbq_cover_cell
 * with root VBQ_RESUME), and the entries of a run grouped by cell.
 *
 * Why the union is the host's own cover. The kernel and the host make the
 * same decisions on the same list (the same doubles: tests/gpu/test_cover
 * compares their quadruples), so up to a handed patch the kernel wrote what
 * the host writes; the host then takes the patch from its list as the
 * kernel popped it, and every decision below it is the host's. The cell's
 * quadruples are the kernel's and the resumed patches' together, the set
 * the host alone writes (the driver makes them unique). Measured on
 * EXTREMESET Congruent 300 (papers/degenerate-input/results/
 * twocore-stop47-pocl.md): 941 handed patches in 267 of 300 cells, which
 * the host covered whole again before. */
#include <stdlib.h>
#include <string.h>

#include "vb_array.h"

#include "vb_cover.h"
#include "vb_cover_shared.h"

/* A cell's records by sphere while its entries are pushed: the patches a
 * kernel hands share most of their lists (children of one chain: fcc
 * 10,976 exact hands 15,801 patches of ~330 labels in 2,168 cells), and a
 * record depends on the cell and the sphere alone. Open addressing, slots
 * a power of two at least twice the ids. */
typedef struct rec_map {
    vbs_u32 *id, *at;  /* sphere id + 1 (0: empty), its record's index in nb */
    vbs_u32 mask;
} rec_map;

/* The record of sphere j for cell i in ar->nb (made once): its index, or
 * VBQ_OVER_NB's status set and UINT32_MAX when nb is full. */
static vbs_u32 rec_get(rec_map *m, const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o,
                       vbs_u32 i, vbs_u32 j)
{
    vbs_u32 s = (j * 2654435761u) & m->mask;
    while (m->id[s] && m->id[s] != j + 1u)
        s = (s + 1u) & m->mask;
    if (m->id[s])
        return m->at[s];
    if (o->nnb >= ar->nb_cap) {
        o->status = VBQ_OVER_NB;
        return UINT32_MAX;
    }
    vbq_nb_make(e->x[i], e->y[i], e->z[i], e->r[i], e->x[j], e->y[j], e->z[j], e->r[j], j,
                &ar->nb[o->nnb]);
    m->id[s] = j + 1u;
    m->at[s] = o->nnb;
    return o->nnb++;
}

/* vbq_resume_push's entries, records from m. */
static int resume_entries(rec_map *m, const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o,
                          vbs_u32 i, vbs_u32 *nst, vbs_u32 *len0)
{
    for (size_t at = 0; at + VBQ_HAND_HEAD <= ar->resume_n;) {
        vbq_frame fr;
        memcpy(&fr, ar->resume + at, sizeof fr);
        const vbs_u32 *ids = ar->resume + at + VBQ_HAND_HEAD;
        at += VBQ_HAND_WORDS(fr.len);
        if (*nst >= ar->st_cap) {
            o->status = VBQ_OVER_ST;
            return 0;
        }
        if (fr.len > ar->lab_cap - *len0) {
            o->status = VBQ_OVER_LAB;
            return 0;
        }
        for (vbs_u32 k = 0u; k < fr.len; k++) {
            vbs_u32 r = rec_get(m, e, ar, o, i, ids[k]);
            if (r == UINT32_MAX)
                return 0;
            ar->lab[*len0 + k] = r;
        }
        fr.off = *len0;
        *len0 += fr.len;
        ar->st[(*nst)++] = fr;
    }
    return 1;
}

int vbq_resume_push(const vbq_env *e, const vbq_arena *ar, vbq_cell_out *o, vbs_u32 i,
                    vbs_u32 *nst, vbs_u32 *len0)
{
    vbs_u32 slots = 16u;
    while (slots < 2u * ar->resume_n && slots < (1u << 30))
        slots *= 2u;
    rec_map m = {calloc(slots, sizeof *m.id), malloc(slots * sizeof *m.at), slots - 1u};
    int ok = m.id && m.at && resume_entries(&m, e, ar, o, i, nst, len0);
    if (!m.id || !m.at)
        o->status = VBQ_OVER_NB; /* no memory: the caller grows nb and fails there */
    free(m.id);
    free(m.at);
    return ok;
}

/* The frame of the entry at e. */
static vbq_frame entry_frame(const uint32_t *e)
{
    vbq_frame fr;
    memcpy(&fr, e, sizeof fr);
    return fr;
}

/* (cell << 32 | word position) */
static int key_cmp(const void *pa, const void *pb)
{
    uint64_t a = *(const uint64_t *)pa, b = *(const uint64_t *)pb;
    return a < b ? -1 : a > b;
}

int vb_hand_index_make(vb_hand_index *x, const uint32_t *hand, size_t words)
{
    x->hand = hand;
    x->n = 0;
    size_t n = 0;
    for (size_t at = 0; at + VBQ_HAND_HEAD <= words; n++)
        at += VBQ_HAND_WORDS(entry_frame(hand + at).len);
    if (VB_ARRAY_FIT(x->key, x->cap, n, 64) != VB_OK)
        return VB_ENOMEM;
    for (size_t at = 0; at + VBQ_HAND_HEAD <= words;) {
        vbq_frame fr = entry_frame(hand + at);
        x->key[x->n++] = (uint64_t)fr.off << 32 | (uint64_t)at; /* off: the cell */
        at += VBQ_HAND_WORDS(fr.len);
    }
    if (x->n > 1) /* none handed: x->key may still be NULL, which qsort may not take */
        qsort(x->key, x->n, sizeof *x->key, key_cmp);
    return VB_OK;
}

int vb_hand_index_cell(vb_hand_index *x, uint32_t i, const uint32_t **words, size_t *nwords,
                       size_t *patches)
{
    size_t lo = 0, hi = x->n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (x->key[mid] >> 32 < i)
            lo = mid + 1;
        else
            hi = mid;
    }
    size_t need = 0, k = lo;
    for (; k < x->n && x->key[k] >> 32 == i; k++)
        need += VBQ_HAND_WORDS(entry_frame(x->hand + (uint32_t)x->key[k]).len);
    *patches = k - lo;
    *nwords = need;
    *words = NULL;
    if (!need)
        return VB_OK;
    if (VB_ARRAY_FIT(x->scratch, x->scap, need, 1024) != VB_OK)
        return VB_ENOMEM;
    size_t w = 0;
    for (k = lo; k < x->n && x->key[k] >> 32 == i; k++) {
        const uint32_t *e = x->hand + (uint32_t)x->key[k];
        size_t n = VBQ_HAND_WORDS(entry_frame(e).len);
        memcpy(x->scratch + w, e, n * sizeof *e);
        w += n;
    }
    *words = x->scratch;
    return VB_OK;
}

void vb_hand_index_free(vb_hand_index *x)
{
    free(x->key);
    free(x->scratch);
    memset(x, 0, sizeof *x);
}

int vb_hand_keep_finished(uint32_t *h, size_t words, const uint32_t *cells, size_t ntasks,
                          const vbq_cell_out *out, size_t *kept)
{
    size_t w = 0;
    *kept = 0;
    for (size_t at = 0; at + VBQ_HAND_HEAD <= words;) {
        vbq_frame fr = entry_frame(h + at);
        size_t n = VBQ_HAND_WORDS(fr.len);
        if (fr.off >= ntasks || n > words - at)
            return VB_EINTERNAL;
        if (out[fr.off].status == VBQ_OK) {
            fr.off = cells[fr.off];
            memmove(h + w, h + at, n * sizeof *h);
            memcpy(h + w, &fr, sizeof fr);
            w += n;
        }
        at += n;
    }
    *kept = w;
    return VB_OK;
}
