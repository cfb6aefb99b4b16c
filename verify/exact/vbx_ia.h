/* Interval arithmetic in double: the filter of every exact predicate, under
 * the names verify/ uses. The arithmetic and its error bound are
 * core/vb_ia_shared.h's, the one copy the device's certification filter
 * (core/cells/vbd_cert_shared.h) compiles too. */
#ifndef VBX_IA_H
#define VBX_IA_H

#include "vb_ia_shared.h"

typedef vb_ia vbx_ia;

#define vbx_succ_bits vb_succ_bits
#define vbx_succ vb_succ
#define vbx_pred vb_pred
#define vbx_min vb_fmin
#define vbx_max vb_fmax
#define vbx_ia_make vb_ia_make
#define vbx_ia_point vb_ia_point
#define vbx_ia_add vb_ia_add
#define vbx_ia_sub vb_ia_sub
#define vbx_ia_neg vb_ia_neg
#define vbx_ia_mul vb_ia_mul
#define vbx_ia_sqr vb_ia_sqr
#define vbx_ia_div vb_ia_div
#define vbx_ia_sqrt vb_ia_sqrt
#define vbx_ia_sign vb_ia_sign
#define vbx_ia_mid vb_ia_mid

#endif
