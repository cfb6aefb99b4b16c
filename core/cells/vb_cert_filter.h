/* The certification filter's input (core/cells/cert_filter.c): the spheres
 * as scaled 64-bit integers and a grid of their centres, for the OpenCL
 * kernel (gpu/cert_filter.cl) and its plain-C twin here, which run the one
 * judge of vbd_cert_shared.h. A proposer of quadruples hands each
 * quadruple's per-root verdicts to the certifier with the quadruples
 * (vb_quad_list.verdict); only the roots left open reach the host's filter
 * and exact stage, so the vertices do not depend on whether, or where, the
 * filter ran. */
#ifndef VB_CERT_FILTER_H
#define VB_CERT_FILTER_H

#include <stddef.h>
#include <stdint.h>

#include "vb.h"
#include "vb_spheres.h"
#include "vbd_cert_shared.h"

typedef struct vb_cert_filter {
    int ok;                /* 0: the input does not fit (the filter judges nothing) */
    uint64_t serial;       /* distinct for every filter built in the process (device uploads) */
    size_t n;              /* spheres */
    int64_t *z;            /* 4n: X, Y, Z, R times 10^E, exact (|z| < 2^61) */
    vbd_grid g;
    size_t ncells;         /* nx ny nz */
    uint32_t *cell_start;  /* ncells + 1: the spheres of cell c are cell_ids[cell_start[c] ..] */
    uint32_t *cell_ids;    /* n sphere ids, by cell, increasing in each */
    int64_t *cell_z;       /* 4n: z of cell_ids' spheres, in that order (read in turn) */
    double *cell_d;        /* host twin only, where every |z| < 2^52 (else NULL): cell_z as
                            * doubles (exact), by column: X of all n, then Y, Z, R */
} vb_cert_filter;

/* Whether quadruples are judged before certification, from
 * VORBALL_DEVICE_CERT: 1 on every backend (the twin on host threads for
 * ref), 0 nowhere (old and new timed side by side), unset (or anything
 * else) on GPUs only: on the 2-core machine the twin and PoCL's kernel
 * cost more CPU than the host's own filter saves (README, "Certification
 * filter"). 1, 0, or -1 for unset. */
int vb_cert_filter_mode(void);

/* Builds f from set's exact decimals (scale 10^E with E the most decimal
 * places; the grid's cell side about twice the mean radius, at most 32
 * cells a sphere). f->ok = 0 when a scaled value reaches 2^61 or the set has
 * no decimals (nothing judged, nothing wrong). VB_OK or VB_ENOMEM (message
 * in ctx; f then holds nothing). Free with vb_cert_filter_free. */
int vb_cert_filter_build(vb_ctx *ctx, const vb_sphere_set *set, vb_cert_filter *f);

/* Frees what f holds and zeroes it (a zeroed f is allowed). */
void vb_cert_filter_free(vb_cert_filter *f);

/* The twin: verdict[k] = vbd_judge of quadruple q[k] for k < n (sorted
 * distinct ids below f->n), computed by vb_cert_judge_pick's judge, on
 * `threads` host threads (0: VORBALL_THREADS or all CPUs). Every verdict VBD_OPEN when !f->ok. Allocates nothing that
 * outlives the call. */
void vb_cert_filter_judge(const vb_cert_filter *f, const uint32_t (*q)[4], size_t n,
                          uint8_t *verdict, unsigned threads);

/* The twin's judge of one quadruple q (sorted distinct ids below f->n, f->ok):
 * vbd_judge's verdict, with each root's scan over f->cell_d where that is
 * there (core/cells/cert_scan.c). */
typedef uint32_t (*vb_cert_judge_fn)(const vb_cert_filter *f, const uint32_t *q);
uint32_t vb_cert_judge_one(const vb_cert_filter *f, const uint32_t *q);
uint32_t vb_cert_judge_one_avx2(const vb_cert_filter *f, const uint32_t *q);

/* The judge for this CPU: vb_cert_judge_one_avx2 where the build and the
 * CPU have AVX2, else vb_cert_judge_one (the same verdicts). */
vb_cert_judge_fn vb_cert_judge_pick(void);

/* The twin's judge of quadruples q[0..n) into out[0..n) (each
 * vb_cert_judge_one's verdict): _avx2 takes the lines of four at once in
 * AVX2 lanes (core/cells/cert_line4.h); vb_cert_judge_run_pick gives it
 * where the build and the CPU have AVX2, else vb_cert_judge_run. */
typedef void (*vb_cert_judge_run_fn)(const vb_cert_filter *f, const uint32_t (*q)[4], size_t n,
                                     uint8_t *out);
void vb_cert_judge_run(const vb_cert_filter *f, const uint32_t (*q)[4], size_t n, uint8_t *out);
void vb_cert_judge_run_avx2(const vb_cert_filter *f, const uint32_t (*q)[4], size_t n,
                            uint8_t *out);
vb_cert_judge_run_fn vb_cert_judge_run_pick(void);

/* The lines of four quadruples q[0..3] (f->ok): k[l] and L[l] as
 * vbd_line_make(f->z, q[l], &L[l]) gives them, bit for bit where k[l] = 1,
 * their interval steps in AVX2 lanes (cert_line4.h); returns the mask of
 * lanes that took vbd_line_end's scalar steps instead. vb_cert_lines_pick:
 * that function where the build and the CPU have AVX2, else NULL (no
 * vb_cert_judge_run_avx2 either). */
typedef unsigned (*vb_cert_lines_fn)(const vb_cert_filter *f, const uint32_t (*q)[4], vbd_line *L,
                                     int *k);
unsigned vb_cert_lines_four_avx2(const vb_cert_filter *f, const uint32_t (*q)[4], vbd_line *L,
                                 int *k);
vb_cert_lines_fn vb_cert_lines_pick(void);

#endif
