/* The decimal text of an enclosure, shared by the TSV and JSON writers of
 * the cell measures, so both print the same digits. */
#ifndef VBM_TEXT_H
#define VBM_TEXT_H

#include "vbx_ia.h"

/* The double printed (%.12g) for an enclosure's lower end: lo moved down by
 * 1e-11 of itself, so that printing 12 significant digits (which moves it
 * by at most 5e-12 of itself) leaves the printed value below lo. Measures
 * are >= 0: 0 for lo <= 0. */
static inline double vbm_text_lo(double x)
{
    return x <= 0.0 ? 0.0 : vbx_pred(x - x * 1e-11);
}

/* The double printed for an upper end: hi moved up likewise. */
static inline double vbm_text_hi(double x)
{
    return x <= 0.0 ? 0.0 : vbx_succ(x + x * 1e-11);
}

/* The value printed: the enclosure's midpoint. */
static inline double vbm_text_mid(double lo, double hi)
{
    return 0.5 * lo + 0.5 * hi;
}

#endif
