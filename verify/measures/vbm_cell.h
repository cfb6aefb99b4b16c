/* One atom's constrained cell measured over its sphere of directions
 * (cell_patches.c): the internal interface between the driver
 * (measures.c) and the integrator. */
#ifndef VBM_CELL_H
#define VBM_CELL_H

#include <stddef.h>
#include <stdint.h>

#include "vb_parallel.h"
#include "vbx_ia.h"

/* A neighbour j of atom i, as enclosures of exact values: d = cj - ci,
 * delta = Rj - Ri, N = |d|^2 - delta^2 (> 0: neither sphere inside the
 * other), k = N / (2 r) - delta with r = Ri + probe. Along a direction u the
 * cell boundary with j lies at t = N / (2 (u.d + delta)) where u.d + delta >
 * 0, and j's expanded ball covers the direction on i's expanded sphere iff
 * u.d > k. */
typedef struct vbm_nb {
    vbx_ia d[3], delta, N, k;
    uint32_t id;
    uint8_t con; /* its contact area is wanted from this atom (vbm_atom_in.contacts
                  * set; the other atom of the face may integrate it instead) */
} vbm_nb;

typedef struct vbm_pair {
    uint32_t j; /* neighbour index into vbm_atom_in.nb */
    vbx_ia area;
} vbm_pair;

typedef struct vbm_atom_in {
    vbx_ia r;             /* Ri + probe */
    const vbm_nb *nb;     /* the neighbours within reach (expanded balls that may meet) */
    size_t nnb;           /* < 65536 */
    double tolerance;     /* relative, see vb_measure_options */
    size_t max_patches;
    int contacts;         /* some nb[j].con is set: contact areas wanted */
    double *clock;        /* NULL, or the seconds per stage (VB_CELL_*, vb_measures.h)
                           * this thread adds to (vbm_lap) */
} vbm_atom_in;

/* Adds the time since t0 to clock[stage] and returns now (t0 of the next
 * stage); nothing (0) when clock is NULL, the untimed run. */
static inline double vbm_lap(double *clock, int stage, double t0)
{
    if (!clock)
        return 0.0;
    double t = vb_now();
    clock[stage] += t - t0;
    return t;
}

typedef struct vbm_atom_out {
    vbx_ia vol, sas;
    vbm_pair *pairs;      /* npairs contact enclosures with hi > 0, of the neighbours with
                           * con set (malloc'd; caller frees) */
    size_t npairs;
    size_t patches;
    int loose;            /* a value is wider than the tolerance asks */
} vbm_atom_out;

/* The floor of neighbour j's contact target (tolerance * max(|area|,
 * floor)): 1e-3 of the area of the smaller expanded sphere of the face's two
 * atoms, so that the one side that integrates a contact asks what the
 * stricter side would (when both were integrated and met, the meet was as
 * narrow as that side's). A target, not an enclosure: plain doubles. */
static inline double vbm_contact_floor(const vbm_atom_in *in, size_t j)
{
    double r = in->r.hi, rj = r + in->nb[j].delta.hi, m = rj < r ? rj : r;
    return m > 0.0 ? 1e-3 * 12.566370614359172 * m * m : 0.0;
}

/* Per-thread scratch of vbm_cell_integrate (zero-initialise; free with
 * vbm_scratch_free). */
typedef struct vbm_scratch {
    void *patch, *heap, *cand, *pair, *tmp, *sum;
    void *stokes; /* vbm_cell_stokes' work space */
    size_t cap_patch, cap_heap, cap_cand, cap_pair, cap_tmp, cap_sum;
} vbm_scratch;

/* Integrates the volume, SAS area and (in->contacts) contact areas of one
 * atom's constrained cell to in->tolerance or in->max_patches. Returns VB_OK
 * or VB_ENOMEM (out->pairs NULL then). */
int vbm_cell_integrate(const vbm_atom_in *in, vbm_scratch *sc, vbm_atom_out *out);

void vbm_scratch_free(vbm_scratch *sc);

/* The volume, SAS area and (in->contacts) contact areas of one atom's
 * constrained cell in closed form over the boundaries of the regions its
 * neighbours own (stokes_cell.c), to in->tolerance. Returns 1 with *out
 * filled as vbm_cell_integrate fills it, 0 when an interval cannot decide
 * the arrangement or bound an integral (the caller integrates by patches,
 * vbm_cell_integrate), -1 on ENOMEM. */
int vbm_cell_stokes(const vbm_atom_in *in, vbm_scratch *sc, vbm_atom_out *out);

/* Frees vbm_cell_stokes' work space (sc->stokes; NULL is fine). */
void vbm_stokes_free(void *w);

#endif
