/* The integrals along one arc bounding a neighbour's region of directions
 * (vbm_arc.h; the formulas at the top of stokes_cell.c, the pieces'
 * files in vbm_arcfun.h).
 *
 * On the arcs of j's own cap circle z is constant and dphi the arc's
 * angle (closed form, vbm_arc_angle); on the others the integral runs
 * over t = tan(angle / 2) about the arc's middle: the exact ends' few ulps
 * by a bound times their length (end_piece), the area and the volume on
 * planned, halved pieces (arc_pieces.c), the contact on pieces stepped
 * along the arc (arc_march.c). */
#include <string.h>

#include "vbm_arcfun.h"
#include "vbm_caps.h"

/* The integral from the exact end t (an interval) to the double m inside
 * it: (m - t) times the integrand somewhere in t. */
static int end_piece(const vbm_arcfun *f, vbx_ia t, double m, vbm_sums *out)
{
    vbm_s1 v[NV];
    if (!vbm_arcfun_series(f, f->want & ~(1 << CON), t, v, 0, 0, NULL))
        return 0;
    /* the contact's by contact_bound, not its series (a root, two logs):
     * the end is a few ulps long (c1k --contacts: 8.40 -> 8.15 G) */
    if (f->o.contacts && f->want & 1 << CON && !vbm_arcfun_contact_bound(f, t, &v[CON].c[0]))
        return 0;
    vbx_ia dt = vbx_ia_sub(vbx_ia_point(m), t);
    for (int k = 0; k < NV; k++)
        out->v[k] = vbx_ia_add(out->v[k], vbx_ia_mul(dt, v[k].c[0]));
    return 1;
}

int vbm_arc_integrate(const vbm_owner *o, vbm_arcrec *a, const double *tg, int again,
                      size_t *pieces)
{
    vbx_ia cm, sm;
    vbm_unit_at(0.5 * (a->tp + a->tq), &cm, &sm);
    vbx_ia t0 = vbm_half_tan(a->p[0], a->p[1], cm, sm), t1 = vbm_half_tan(a->q[0], a->q[1], cm, sm);
    if (!(t1.lo > t0.hi))
        return 0;
    vbm_sums s = {{vbx_ia_point(0.0), vbx_ia_point(0.0), vbx_ia_point(0.0)}, 0};
    int wantc = o->contacts;
    if (a->own) { /* z = c: F(c) times the angle 2 (atan t1 - atan t0) */
        vbx_ia ang = vbm_arc_angle(t0, t1);
        vbx_ia omz = vbx_ia_sub(vbx_ia_point(1.0), a->c), F = vbx_ia_point(0.0);
        if (wantc && !vbm_owner_fcon(o, a->c, &F))
            return 0;
        a->v[AREA] = vbx_ia_mul(omz, ang);
        a->v[VOL] = vbx_ia_mul(vbx_ia_mul(omz, vbm_owner_fvol_over(o, a->c)), ang);
        a->v[CON] = vbx_ia_mul(F, ang);
        ++*pieces;
        return 1;
    }
    vbm_arcfun f;
    vbm_phic pc = {.state = 0};
    vbm_arcfun_make(&f, o, a, cm, sm, &pc);
    double m0 = vbx_ia_mid(t0), m1 = vbx_ia_mid(t1);
    /* again: the values already within their targets stay (1crn
     * --contacts, 1 thread: the second pass integrated ~2800 arcs again,
     * mostly for a contact target the first pass could not know, and
     * redid their area and volume too) */
    int av = !again || vbm_ia_width(a->v[AREA]) > tg[AREA] || vbm_ia_width(a->v[VOL]) > tg[VOL];
    int con = wantc && (!again || vbm_ia_width(a->v[CON]) > tg[CON]);
    f.want = (av ? 1 << AREA | 1 << VOL : 0) | (con ? 1 << CON : 0);
    if (!end_piece(&f, t0, m0, &s) || !end_piece(&f, t1, m1, &s))
        return 0;
    /* the area and volume on their pieces, the contact on its own (it needs
     * more): neither evaluated where only the other falls short */
    double ta[NV] = {tg[AREA], tg[VOL], INFINITY}, tc[NV] = {INFINITY, INFINITY, tg[CON]};
    f.want = 1 << AREA | 1 << VOL;
    double est_area = -1.0;
    if (av && !vbm_arc_planned(&f, m0, m1, ta, &s, &est_area))
        return 0;
    f.want = 1 << CON;
    if (con && !vbm_arc_march(&f, m0, m1, tc, est_area, &s))
        return 0;
    if (!av) {
        s.v[AREA] = a->v[AREA];
        s.v[VOL] = a->v[VOL];
    }
    if (!con && wantc)
        s.v[CON] = a->v[CON];
    memcpy(a->v, s.v, sizeof a->v);
    *pieces += s.pieces;
    return 1;
}
