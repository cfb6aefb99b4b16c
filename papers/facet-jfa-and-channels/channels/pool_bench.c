/* Microseconds per call of an empty vb_parallel_for (8 items) on 2, 8 and
 * 16 threads: wall and CPU (getrusage, all threads) over CALLS calls, the
 * median of 5 rounds. Built against one checkout's core/parallel*.c:
 *   cc -O2 -std=c11 -D_DEFAULT_SOURCE -I CHECKOUT/core -I CHECKOUT/include \
 *      pool_bench.c CHECKOUT/core/parallel*.c -lpthread -o pool_bench
 * usage: pool_bench [CALLS]   (default 2000) */
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>

#include "vb_parallel.h"

static void nothing(void *ctx, size_t i, int tid)
{
    (void)ctx, (void)i, (void)tid;
}

static double cpu_now(void)
{
    struct rusage r;
    getrusage(RUSAGE_SELF, &r);
    return (double)(r.ru_utime.tv_sec + r.ru_stime.tv_sec) +
           1e-6 * (double)(r.ru_utime.tv_usec + r.ru_stime.tv_usec);
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    int calls = argc > 1 ? atoi(argv[1]) : 2000;
    const int nts[3] = {2, 8, 16};
    printf("threads\twall_us_per_call\tcpu_us_per_call\n");
    for (int k = 0; k < 3; k++) {
        double wall[5], cpu[5];
        vb_parallel_for(nothing, NULL, 8, nts[k]); /* warm: the pool starts */
        for (int r = 0; r < 5; r++) {
            double w0 = vb_now(), c0 = cpu_now();
            for (int c = 0; c < calls; c++)
                vb_parallel_for(nothing, NULL, 8, nts[k]);
            wall[r] = 1e6 * (vb_now() - w0) / calls;
            cpu[r] = 1e6 * (cpu_now() - c0) / calls;
        }
        qsort(wall, 5, sizeof *wall, cmp);
        qsort(cpu, 5, sizeof *cpu, cmp);
        printf("%d\t%.1f\t%.1f\n", nts[k], wall[2], cpu[2]);
    }
    return 0;
}
