/* The filter of vb_certify_quads for one root: refused, certified or open
 * from double enclosures alone (see certify_quads.c's head comment). */
#include "vbx_qties.h"

/* |p - c_j| - R_j - t over the enclosures (as in certifier.c). */
static vbx_ia distance_excess(const vbx_ia cj[4], const vbx_ia box[4])
{
    vbx_ia d2 = vbx_ia_sqr(vbx_ia_sub(box[0], cj[0]));
    d2 = vbx_ia_add(d2, vbx_ia_sqr(vbx_ia_sub(box[1], cj[1])));
    d2 = vbx_ia_add(d2, vbx_ia_sqr(vbx_ia_sub(box[2], cj[2])));
    return vbx_ia_sub(vbx_ia_sub(vbx_ia_sqrt(d2), cj[3]), box[3]);
}

/* The scan's second stage for sphere j, which root R's double box cannot
 * place: outside when t + R_j < 0 is proven (the distance exceeds t + R_j),
 * else, once t + R_j > 0 is proven, the sign of the power, which is the
 * distance's there: in doubles with a static bound first (vbx_qf_power_fast),
 * then in double intervals (vbx_qf_power_ia), then in
 * double-double (vbx_qf_power_sign). 0: still open. The radius difference
 * is exact in double below 2^53 and a sum rounded to nearest keeps its sign
 * (as in vbx_qf_tangent_sign). */
static int second_stage(const vb_certifier *c, vb_cert_quad_stats *cs, const vbx_qline *L,
                        const vbx_qprep *P, vbx_qroot *R, const vbx_ia qs[4],
                        const double mr[8], uint32_t j)
{
    const vbx_qdata *qd = &c->qd;
    int64_t rj = qd->z[4 * (size_t)j + 3] - qd->z[4 * (size_t)L->q[0] + 3];
    if (rj >= ((int64_t)1 << 53) || rj <= -((int64_t)1 << 53))
        return 0;
    double r = (double)rj;
    if (R->s.hi + r < 0.0)
        return 1;
    if (!(R->s.lo + r > 0.0))
        return 0;
    int sg = vbx_qf_power_fast(qd, L, mr, j);
    if (!sg)
        sg = vbx_qf_power_ia(qd, L, qs, j);
    if (!sg) {
        sg = qd->ops->power(qd, L, P, R, j);
        if (sg)
            cs->power_signs_dd++;
    }
    if (sg)
        cs->power_signs++;
    return sg;
}

int vbx_qfilter_root(vb_ctx *ctx, const vb_certifier *c, vb_cert_quad_stats *cs,
                     const vbx_qline *L, const vbx_qprep *P, vbx_qroot *R)
{
    vb_stats *st = vb_ctx_stats(ctx);
    int open = 0;
    for (int i = 0; i < 4; i++) {
        st->filter_calls++;
        int sg = vbx_qf_tangent_sign(L, R->s, i);
        if (sg < 0) {
            cs->refused_tangent++;
            return ROOT_REFUSED;
        }
        if (sg == 0) {
            st->filter_failures++;
            open = 1;
        }
    }
    if (!c->qd.ops->point(&c->qd, L, P, R)) {
        st->filter_failures++;
        return ROOT_UNPLACED;
    }
    const vbx_ia *p = R->p;
    const uint32_t *q = L->q;
    const vbx_sindex *t = &c->t;
    vbx_probe pr;
    vbx_probe_init(&pr, t, p);
    vbx_walk walk;
    vbx_walk_init(&walk, t, p);
    vbx_ia qs[4];
    double mr[8];
    int have_qs = 0;
    /* A far root (t ~ 10^10 on a jittered face): the distance's double box
     * cannot place what the probes leave open, the power mostly can, so it
     * goes first. Each gives the exact sign or none: speed only. */
    int far = p[3].lo > 1e6;
    /* ... and there the scan would meet every sphere of the face layer (the
     * distance's bound skips no node the ball's flat side touches): the
     * power bound of a node clears whole groups off the vertex's own
     * neighbours (speed only: the spheres it clears are outside). */
    vbx_qf_group fg = {&c->qd, L, mr, t->rmin};
    if (far) {
        vbx_qf_power_qs(&c->qd, L, R, qs);
        vbx_qf_power_mr(qs, mr);
        have_qs = 1;
        vbx_walk_skip(&walk, vbx_qf_group_outside, &fg);
    }
    size_t s0, s1;
    uint64_t calls = 0, failures = 0;
    int verdict = ROOT_EMPTY;
    while (verdict == ROOT_EMPTY && vbx_walk_next(&walk, &s0, &s1))
        for (size_t s = s0; s < s1; s++) {
            calls++;
            const double *cm = &t->mid[4 * s];
            if (vbx_probe_outside(&pr, cm))
                continue;
            uint32_t j = t->ids[s];
            if (j == q[0] || j == q[1] || j == q[2] || j == q[3]) {
                calls--;
                continue;
            }
            const vbx_ia *cj = &t->box[4 * s];
            int sg = vbx_probe_inside(&pr, cm, cj[3].lo) ? -1
                     : far                               ? 0
                                                         : vbx_ia_sign(distance_excess(cj, p));
            /* After the first sphere left open the root is open: the power
             * stages, which decide near-ties and are dear, then run no more
             * (a cospherical vertex's dozens of members each fail all
             * three). A later sphere only they could prove inside leaves
             * the root open, never refused, so the exact path decides. */
            if (sg == 0 && !failures) {
                if (!have_qs) {
                    vbx_qf_power_qs(&c->qd, L, R, qs);
                    vbx_qf_power_mr(qs, mr);
                }
                have_qs = 1;
                sg = second_stage(c, cs, L, P, R, qs, mr, j);
            }
            if (sg == 0 && far)
                sg = vbx_ia_sign(distance_excess(cj, p));
            if (sg > 0)
                continue;
            if (sg < 0) {
                verdict = ROOT_REFUSED;
                break;
            }
            failures++;
            open = 1;
        }
    st->filter_calls += calls;
    st->filter_failures += failures;
    if (verdict == ROOT_REFUSED) {
        cs->refused_intruder++;
        return ROOT_REFUSED;
    }
    return open ? ROOT_OPEN : ROOT_EMPTY;
}
