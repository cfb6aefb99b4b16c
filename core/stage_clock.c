/* Wall and CPU seconds by stage of the whole process (vb_stage_clock.h). */
#include "vb_stage_clock.h"

#include <string.h>
#include <time.h>

#include "vb_parallel.h"

static const char *const stage_name[VB_STAGE_N] = {"read", "validate", "run",
                                                   "complete", "write", "free"};

double vb_cpu_now(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0)
        return 0.0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double vb_thread_cpu_now(void)
{
#ifdef CLOCK_THREAD_CPUTIME_ID
    struct timespec ts;
    if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) == 0)
        return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
#endif
    return vb_now();
}

void vb_stage_clock_start(vb_stage_clock *c)
{
    memset(c, 0, sizeof *c);
    c->wall_start = c->wall0 = vb_now();
    c->cpu_start = c->cpu0 = vb_cpu_now();
}

void vb_stage_lap(vb_stage_clock *c, vb_stage s)
{
    if (!c)
        return;
    double w = vb_now(), u = vb_cpu_now();
    c->wall[s] += w - c->wall0;
    c->cpu[s] += u - c->cpu0;
    c->wall0 = w;
    c->cpu0 = u;
}

void vb_stage_clock_write(FILE *f, const vb_stage_clock *c)
{
    for (int s = 0; s < VB_STAGE_N; s++)
        fprintf(f, "process_%s_s\t%.6f\nprocess_%s_cpu_s\t%.6f\n", stage_name[s], c->wall[s],
                stage_name[s], c->cpu[s]);
    fprintf(f, "process_total_s\t%.6f\nprocess_total_cpu_s\t%.6f\n", c->wall0 - c->wall_start,
            c->cpu0 - c->cpu_start);
}
