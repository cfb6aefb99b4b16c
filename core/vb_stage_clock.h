/* The whole process by stage (issue #30's fixed cost): wall and CPU seconds
 * of each stage a command goes through, from reading the input to freeing
 * the output, declared once and printed by one loop (`--stats`). */
#ifndef VB_STAGE_CLOCK_H
#define VB_STAGE_CLOCK_H

#include <stdio.h>

typedef enum vb_stage {
    VB_STAGE_READ,     /* the input file parsed into a sphere set (exact decimals) */
    VB_STAGE_VALIDATE, /* duplicates, contained spheres, magnitudes */
    VB_STAGE_RUN,      /* device set-up, proposer and certification (vb_vertices_run) */
    VB_STAGE_COMPLETE, /* arc closure, topology, the certificate */
    VB_STAGE_WRITE,    /* the output file */
    VB_STAGE_FREE,     /* the result, the set and the context released */
    VB_STAGE_N
} vb_stage;

typedef struct vb_stage_clock {
    double wall[VB_STAGE_N], cpu[VB_STAGE_N]; /* seconds summed per stage */
    double wall0, cpu0;                       /* where the open stage began */
    double wall_start, cpu_start;             /* vb_stage_clock_start */
} vb_stage_clock;

/* The process's CPU seconds so far, all threads together (0 where the
 * clock cannot be read): beside the wall clock in stage clocks and the
 * channels JSON's "clock", as a loaded machine stretches the wall clock
 * but not this. */
double vb_cpu_now(void);

/* The calling thread's CPU seconds so far (its own clock: a difference of
 * two calls on one thread is that thread's CPU between them; wall seconds
 * where the system has no thread clock). */
double vb_thread_cpu_now(void);

/* Zeroes c and starts its clock: the next stage begins now. */
void vb_stage_clock_start(vb_stage_clock *c);

/* Ends the stage that began at the last start or lap (adding its wall and
 * CPU seconds to stage s) and begins the next one now. c may be NULL. */
void vb_stage_lap(vb_stage_clock *c, vb_stage s);

/* Writes "process_<stage>_s" and "process_<stage>_cpu_s" lines for every
 * stage, then the totals since vb_stage_clock_start ("process_total_s",
 * "process_total_cpu_s"), as name<TAB>value lines. */
void vb_stage_clock_write(FILE *f, const vb_stage_clock *c);

#endif
