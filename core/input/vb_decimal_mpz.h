/* Exact decimals as GMP integers: the one conversion that the exact tests
 * of the core (containment, tie clusters) share. Kept apart from
 * vb_spheres.h so that header needs no gmp.h. */
#ifndef VB_DECIMAL_MPZ_H
#define VB_DECIMAL_MPZ_H

#include <gmp.h>

#include "vb_spheres.h"

/* z = d * 10^(d.exp10 - emin), an integer when emin <= d.exp10 (decimals
 * scaled to a common exponent emin: the smallest of those compared). tmp is
 * scratch. */
void vb_decimal_to_mpz(mpz_t z, vb_decimal d, int32_t emin, mpz_t tmp);

#endif
