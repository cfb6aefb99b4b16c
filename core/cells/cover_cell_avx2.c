/* cover_cell.c compiled for AVX2 (CMake adds -mavx2 -mbmi2 to this file
 * alone, on x86-64): the same vbq_cover_cell, run only where the CPU has
 * AVX2 and BMI2 (vb_cover_cell_host). Contraction stays off, so it gives
 * the plain build's doubles (see cover_cell.c). */
#define VB_COVER_CELL_FN vb_cover_cell_avx2
#define VB_COVER_CELL_WIDE 1
#include "cover_cell.c"
