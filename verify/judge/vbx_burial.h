/* Burial bounds of the exact reference (see burial.c for the proof). */
#ifndef VBX_BURIAL_H
#define VBX_BURIAL_H

#include "vbx_exact.h"

/* T[i] (n entries, caller-allocated) gets a bound such that every vertex
 * touching sphere i has t < T[i], or INFINITY where none was shown.
 * Returns VB_OK or VB_ENOMEM. */
int vbx_burial_bounds(const vbx_data *d, double *T);

#endif
