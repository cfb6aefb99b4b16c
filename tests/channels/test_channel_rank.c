/* The table's order and reasons (vbc_rank, core/discrete/channel_rank.c).
 * #33: a channel is a branch of the pore when a third of its points lie in
 * the pore's spheres grown by 1 A; vbc_rank asks only the pore points whose
 * projection on the pore's line lies within the widest sphere's reach. Here
 * against the plain scan of every pore point (a copy below): curved pores
 * with radii from -1 to 6 A (one sphere far wider than the rest), channels
 * of points scattered near and on the grown spheres' surfaces, points a
 * reach away along the line (the window's edge, in or out by a rounding), a pore of one point and one whose
 * ends meet (no line: every point asked); pores of a few points far apart,
 * so that a point on one's edge is in no other. Half the cases have channels of
 * one point, whose reason is then that point's answer alone. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vbc_pore_frame.h"

static uint64_t rng = 88172645463325252ull;

static double uni(void)
{
    return vb_test_uniform(&rng, 0.0, 1.0);
}

/* The rule before #33, one pore point after the other. */
static int plain_runs_along(const vbc_point *P, size_t np, const vbc_point *Q, size_t nq)
{
    size_t near = 0;
    for (size_t k = 0; k < nq; k++)
        for (size_t j = 0; j < np; j++) {
            double dx = Q[k].x - P[j].x, dy = Q[k].y - P[j].y, dz = Q[k].z - P[j].z;
            double reach = fmax(P[j].r, 0.0) + 1.0;
            if (dx * dx + dy * dy + dz * dz <= reach * reach) {
                near++;
                break;
            }
        }
    return 3 * near >= nq;
}

/* A result of a pore of np points (a curve, or all at one place when
 * `still`) and nc channels of up to 12 points each; returns the number of
 * channels expected to be branches. */
static size_t make_case(vbc_result *res, size_t np, size_t nc, int still, int single, int *expect)
{
    memset(res, 0, sizeof *res);
    size_t total = np + 12 * nc;
    res->points = calloc(total, sizeof *res->points);
    res->channels = calloc(nc + 1, sizeof *res->channels);
    if (!res->points || !res->channels)
        return 0;
    res->nchannels = nc + 1;
    vbc_channel *pore = &res->channels[0];
    pore->kind = VBC_PORE;
    pore->why = VBC_WHY_PORE;
    pore->npoints = np;
    double a = uni() * 6.28, bend = 0.3 * uni();
    for (size_t j = 0; j < np; j++) {
        vbc_point *q = &res->points[j];
        double s = still ? 0.0 : (np <= 8 ? 20.0 : 0.25) * (double)j;
        q->x = 10.0 + 3.0 * sin(bend * s + a);
        q->y = -4.0 + s * 0.6 + 2.0 * cos(bend * s);
        q->z = 7.0 + s * 0.8;
        q->r = -1.0 + 5.0 * uni();
    }
    if (np > 3)
        res->points[np / 2].r = 6.0; /* one far wider than the rest */
    /* The pore's line, as vbc_rank takes it (first to last point). */
    const vbc_point *A = &res->points[0], *B = &res->points[np - 1];
    double u[3] = {B->x - A->x, B->y - A->y, B->z - A->z};
    double len = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int k = 0; k < 3; k++)
        u[k] = len > 0.0 ? u[k] / len : (k == 2);
    size_t used = np, branches = 0;
    for (size_t t = 1; t <= nc; t++) {
        vbc_channel *c = &res->channels[t];
        c->kind = uni() < 0.1 ? VBC_CAVITY : VBC_CHANNEL;
        c->through = uni() < 0.3;
        c->length = 100.0 * uni();
        c->bottleneck = 3.0 * uni();
        c->first_point = used;
        c->npoints = single ? 1 : 1 + (size_t)(11.0 * uni());
        for (size_t k = 0; k < c->npoints; k++) {
            vbc_point *q = &res->points[used + k];
            double w = uni();
            /* A third of the edge points on the widest sphere's edge, the
             * window's own. */
            size_t j = w < 0.1 && np > 3 ? np / 2 : (size_t)(uni() * (double)np) % np;
            const vbc_point *P = &res->points[j];
            double R = fmax(P->r, 0.0) + 1.0;
            if (w < 0.3) {
                /* a reach away along the line: on the window's edge */
                double sg = uni() < 0.5 ? R : -R;
                q->x = P->x + sg * u[0];
                q->y = P->y + sg * u[1];
                q->z = P->z + sg * u[2];
            } else {
                double d = R * (w < 0.6 ? 0.5 + uni() : 1.0 + 4.0 * uni());
                double th = 6.28 * uni(), ph = 3.14 * uni();
                q->x = P->x + d * sin(ph) * cos(th);
                q->y = P->y + d * sin(ph) * sin(th);
                q->z = P->z + d * cos(ph);
            }
        }
        expect[t] = c->kind == VBC_CAVITY ? VBC_WHY_CAVITY
                    : plain_runs_along(res->points, np, res->points + used, c->npoints)
                        ? VBC_WHY_PORE_BRANCH
                    : c->through ? VBC_WHY_THROUGH
                                 : VBC_WHY_TUNNEL;
        c->why = -1;
        c->first_lining = t; /* the channel's name, carried through the sort */
        branches += expect[t] == VBC_WHY_PORE_BRANCH;
        used += c->npoints;
    }
    return branches;
}

static void check_case(size_t np, size_t nc, int still, int single)
{
    vbc_result res;
    int *expect = calloc(nc + 1, sizeof *expect);
    size_t branches = make_case(&res, np, nc, still, single, expect);
    CHECK(res.points && res.channels && expect);
    if (!res.points || !res.channels || !expect) {
        free(res.points);
        free(res.channels);
        free(expect);
        return;
    }
    vbc_rank(&res);
    size_t got = 0, bad = 0;
    for (size_t t = 0; t < res.nchannels; t++) {
        const vbc_channel *c = &res.channels[t];
        if (c->kind == VBC_PORE) {
            CHECK_INT((int)t, 0);
            continue;
        }
        bad += c->why != expect[c->first_lining];
        got += c->why == VBC_WHY_PORE_BRANCH;
    }
    CHECK_INT((int)bad, 0);
    CHECK_INT((int)got, (int)branches);
    /* The order: groups, then the through channels widest first. */
    for (size_t t = 2; t < res.nchannels; t++) {
        const vbc_channel *x = &res.channels[t - 1], *y = &res.channels[t];
        if (x->why == VBC_WHY_THROUGH && y->why == VBC_WHY_THROUGH)
            CHECK(x->bottleneck >= y->bottleneck);
    }
    free(res.points);
    free(res.channels);
    free(expect);
}

int main(void)
{
    size_t branch_cases = 0;
    for (int round = 0; round < 40; round++) {
        size_t np = 2 + (size_t)(uni() * 200.0), nc = 1 + (size_t)(uni() * 60.0);
        vbc_result res;
        int *expect = calloc(nc + 1, sizeof *expect);
        uint64_t keep = rng;
        branch_cases += make_case(&res, np, nc, 0, round & 1, expect) > 0;
        free(res.points);
        free(res.channels);
        free(expect);
        rng = keep; /* the same case again, ranked */
        check_case(np, nc, 0, round & 1);
    }
    CHECK(branch_cases >= 30); /* the cases do have branches */
    /* Pores of a few points 20 A apart: a point on a sphere's edge is in
     * no other, so its answer is that sphere's alone (the window's edge). */
    for (int round = 0; round < 20; round++)
        check_case(4 + (size_t)round % 5, 200, 0, 1);
    check_case(1, 20, 0, 0);  /* one pore point: no line */
    check_case(30, 20, 1, 0); /* every point at one place: no line */
    VB_TEST_END();
}
