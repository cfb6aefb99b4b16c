/* A periodic vertex file judged exactly (`vorball verify --periodic`): the
 * periodic wing reads it and names its members by the images
 * (core/periodic/), the exact verifier judges them (vb_verify_list). */
#ifndef VB_PERIODIC_VERIFY_H
#define VB_PERIODIC_VERIFY_H

#include <stddef.h>
#include <stdint.h>

#include "vb_periodic.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The judgement of each line and the counts. */
typedef struct vb_periodic_judgement {
    size_t n;          /* vertex lines */
    long *line;        /* n: 1-based line of each in the file */
    uint8_t *flags;    /* n: VB_PERIODIC_NOT_CANONICAL | VB_PERIODIC_BEYOND */
    int *problems;     /* n: VB_VERIFY_* bits of the exact verifier (0 when not judged) */
    size_t certified, not_canonical, beyond, not_vertex, wrong, missing, duplicate;
} vb_periodic_judgement;

/* Judges the periodic vertex file `path` against the validated set in box:
 * each line must be its vertex's canonical translate, within the images'
 * proven reach, and certified by the exact verifier against the atoms and
 * their images (touching its members, no sphere or image inside, point
 * within tol), once. Fills *out (free with vb_periodic_judgement_free);
 * a line is certified when it has no flag and no problem. VB_OK when the
 * judging ran, else the reader's, the images' or VB_ENOMEM. */
int vb_periodic_verify_file(vb_ctx *ctx, const vb_sphere_set *set, const vb_box *box,
                            const char *path, double tol, vb_periodic_judgement *out);

/* Frees what j holds and zeroes it; NULL is allowed. */
void vb_periodic_judgement_free(vb_periodic_judgement *j);

#ifdef __cplusplus
}
#endif
#endif
