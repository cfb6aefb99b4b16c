/* `vorball verify --periodic`: a periodic vertex file judged exactly. */
#ifndef VB_CLI_VERIFY_PERIODIC_H
#define VB_CLI_VERIFY_PERIODIC_H

#include <stdio.h>

#include "vertices_periodic.h"

/* Judges the periodic vertex file `path` against the validated set in the
 * box of p (--box, else the file's): each line must be its vertex's
 * canonical translate, within the images' proven reach, and certified by
 * the exact verifier against the atoms and their images (touching its
 * members, no sphere or image inside, point within tol), once. Writes the
 * problems (FILE:LINE: class) and a summary, or with json one object, to
 * out; *mismatch = 1 unless every line is certified. Returns VB_OK when
 * the judging ran, else an error status (VB_EINPUT_BOX, the reader's,
 * the images', VB_ENOMEM). */
int vb_cli_verify_periodic(vb_ctx *ctx, const vb_sphere_set *set, const vb_cli_periodic *p,
                           const char *path, double tol, int json, FILE *out, int *mismatch);

#endif
