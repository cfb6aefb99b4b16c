/* quad_filter.c compiled for FMA (CMake adds -mfma to this file alone):
 * vbx_two_prod takes fma(), everything else is the same source. Its ops run
 * only where the CPU has FMA (vbx_qf_ops_best), and give the same results
 * as the plain build (see vbx_two_prod). Contraction stays off: only the
 * explicit fma() fuses. */
#define VBX_DD_USE_FMA 1
#define vbx_qf_line vbx_qf_line_fma
#define vbx_qf_prep vbx_qf_prep_fma
#define vbx_qf_root vbx_qf_root_fma
#define vbx_qf_point vbx_qf_point_fma
#define vbx_qf_round vbx_qf_round_fma
#define vbx_qf_tangent_sign vbx_qf_tangent_sign_fma
#define vbx_qf_power_sign vbx_qf_power_sign_fma
#include "quad_filter.c"
