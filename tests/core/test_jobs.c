/* Jobs on threads (core/parallel.c): vb_jobs_first_error picks the error one
 * thread taking the items in order would meet, whichever job met it. */
#include <stddef.h>
#include <stdint.h>

#include "vb_test.h"
#include "vb_parallel.h"

typedef struct job {
    int pad;
    int rc;
    size_t at;
} job;

static void first_error(void)
{
    job j[4] = {{0, VB_OK, SIZE_MAX}, {0, VB_OK, SIZE_MAX}, {0, VB_OK, SIZE_MAX},
                {0, VB_OK, SIZE_MAX}};
    size_t rc_off = offsetof(job, rc), at_off = offsetof(job, at);
    CHECK_INT(vb_jobs_first_error(j, sizeof *j, 4, rc_off, at_off), -1);
    CHECK_INT(vb_jobs_first_error(j, sizeof *j, 0, rc_off, at_off), -1);
    /* The earliest item wins, not the lowest job. */
    j[1] = (job){0, VB_ENOMEM, 40};
    j[3] = (job){0, VB_EPREC, 7};
    CHECK_INT(vb_jobs_first_error(j, sizeof *j, 4, rc_off, at_off), 3);
    /* Ties go to the lower job; a job past n is not looked at. */
    j[2] = (job){0, VB_EINTERNAL, 7};
    CHECK_INT(vb_jobs_first_error(j, sizeof *j, 4, rc_off, at_off), 2);
    CHECK_INT(vb_jobs_first_error(j, sizeof *j, 2, rc_off, at_off), 1);
    /* Unordered jobs: the lowest failing job. */
    CHECK_INT(vb_jobs_first_error(j, sizeof *j, 4, rc_off, VB_JOBS_UNORDERED), 1);
    /* A bare array of statuses. */
    int rcs[3] = {VB_OK, VB_OK, VB_EDEVICE};
    CHECK_INT(vb_jobs_first_error(rcs, sizeof *rcs, 3, 0, VB_JOBS_UNORDERED), 2);
}

int main(void)
{
    first_error();
    VB_TEST_END();
}
