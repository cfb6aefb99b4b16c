/* The contact's pieces along an arc (vbm_arcfun.h): stepped from one end
 * to the other, each piece's length from the last one's width against its
 * share (vbm_contact_step), each proven by vbm_arc_piece_values. */
#include "vbm_arcfun.h"

/* The contact alone over [x0, x1] to the width tg[CON], added to *out
 * (est_area: planned's, the first piece's length by vbm_contact_start):
 * pieces stepped along the arc by vbm_contact_step (vbm_contact_tm.h), each
 * proven by piece_values as before, each share the target left times its
 * part of the length left (what a piece leaves unused goes to the next;
 * one kept at its shortest, as piece's VBM_ARC_MAX_DEPTH, may exceed its share,
 * and the others' then fall back to half the even share). Returns 0 when
 * an interval cannot bound a piece at its shortest. */
#define STEP_MIN 0x1p-20 /* of the arc's length: piece's VBM_ARC_MAX_DEPTH */
int vbm_arc_march(const vbm_arcfun *f, double x0, double x1, const double *tg, double est_area,
                  vbm_sums *out)
{
    double a = x0, left = tg[CON], L = x1 - x0, lmin = (x1 - x0) * STEP_MIN;
    if (est_area >= 0.0)
        L *= vbm_contact_start(est_area / tg[CON]);
    while (a < x1) {
        double b = x1 - a <= 1.25 * L || !(a + L > a) ? x1 : a + L, xc = 0.5 * (a + b);
        double share = vbx_max(left * ((b - a) / (x1 - a)), 0.5 * tg[CON] * ((b - a) / (x1 - x0)));
        double t[NV] = {INFINITY, INFINITY, share};
        int last = b - a <= lmin || !(xc > a && xc < b);
        vbx_ia v[NV];
        int ok = vbm_arc_piece_values(f, a, b, t, !last, NULL, 0, NULL, v);
        if (!ok && last)
            return 0;
        double rho = ok ? vbm_ia_width(v[CON]) / share : INFINITY;
        if (!last && !(rho <= 1.0)) { /* shorter */
            L = vbx_max((b - a) * (ok ? vbm_contact_step(rho) : 0.5), lmin);
            continue;
        }
        vbm_arc_add_piece(f, v, out);
        left -= vbm_ia_width(v[CON]);
        L = vbx_max((b - a) * vbm_contact_step(rho), lmin);
        a = b;
    }
    return 1;
}
