/* cert_scan.c compiled for AVX2 (CMake adds -mavx2 to this file alone, on
 * x86-64): the same judge, its scan four spheres a step, run only where the
 * CPU has AVX2 (vb_cert_judge_pick). Contraction stays off and FMA is not enabled,
 * so every lane rounds as vbd_fast_test does. */
#define VB_CERT_SCAN_WIDE 1
#include "cert_scan.c"
