/* One cell of the direction cover on host threads (vbq_cover_cell of
 * vb_cover_shared.h) in a unit of its own, so that CMake can compile it a
 * second time for AVX2 (cover_cell_avx2.c, x86-64 only) and the host can
 * take that build where the CPU has it (vb_cover_cell_host). Contraction
 * stays off in both builds (-ffp-contract=off, no fma() here), so the
 * wider instructions compute the same roundings: every double, decision
 * and quadruple is the same (the corpus and backend identity tests compare
 * the bytes). Measured on the 2-core build machine: the cover 4-5 % less
 * CPU with AVX2 (papers/gpu-voronoi-cells-of-spheres/results/
 * cpu_vs_voronota_stop43.md). */
#include "vb_cover.h"

#ifndef VB_COVER_CELL_FN
#define VB_COVER_CELL_FN vb_cover_cell_plain
#endif

void VB_COVER_CELL_FN(const vbq_env *e, const vbq_arena *ar, uint32_t i, uint32_t root,
                      vbq_cell_out *o);

void VB_COVER_CELL_FN(const vbq_env *e, const vbq_arena *ar, uint32_t i, uint32_t root,
                      vbq_cell_out *o)
{
    vbq_cover_cell(e, ar, i, root, o);
}

#ifndef VB_COVER_CELL_WIDE
#ifdef VB_COVER_CELL_HAVE_AVX2
void vb_cover_cell_avx2(const vbq_env *e, const vbq_arena *ar, uint32_t i, uint32_t root,
                        vbq_cell_out *o);
#endif

typedef void (*cover_cell_fn)(const vbq_env *, const vbq_arena *, uint32_t, uint32_t,
                              vbq_cell_out *);

/* The build this CPU runs (asked once; the answer is the same every time). */
static cover_cell_fn cover_cell_best(void)
{
#if defined(VB_COVER_CELL_HAVE_AVX2) && defined(__GNUC__) && defined(__x86_64__)
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi2"))
        return vb_cover_cell_avx2;
#endif
    return vb_cover_cell_plain;
}

void vb_cover_cell_host(const vbq_env *e, const vbq_arena *ar, uint32_t i, uint32_t root,
                        vbq_cell_out *o)
{
    static _Atomic(cover_cell_fn) best;
    cover_cell_fn f = best;
    if (!f) {
        f = cover_cell_best();
        best = f;
    }
    f(e, ar, i, root, o);
}
#endif
