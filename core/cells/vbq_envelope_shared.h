/* The direction cover, shared with the kernels (part of vb_cover_shared.h,
 * which includes it before vbq_cell_shared.h; include that header, never
 * this one): when a patch's envelope is decided at once (vbq_envelope_due)
 * and the double filter of that decision (vbq_env_triple, used by
 * vbq_envelope_filter; the argument and the exact fallback are in
 * core/cells/cover_envelope.c, the hull's way in cover_env_hull.c). */
#ifndef VBQ_ENVELOPE_SHARED_H
#define VBQ_ENVELOPE_SHARED_H

VBS_FN double vbq_env_n1(const double x[3])
{
    return (VBS_FABS(x[0]) + VBS_FABS(x[1])) + VBS_FABS(x[2]);
}

/* The filtered sign of X~ . Y (Y = dk~ x dl~, a triple product) against
 * its bound: nX, eX the L1 norm and error of X~; pyz = (nY + eY)(nZ + eZ),
 * nyz = nY nZ, eyz = pyz - nyz as its non-negative terms; 8u nX nY nZ for
 * the product's roundings, 1 + 1e-12 for the bound's own. 0: undecided. */
VBS_FN int vbq_env_sign(const double x[3], double nX, double eX, const double y[3], double pyz,
                        double nyz, double eyz)
{
    double v = (x[0] * y[0] + x[1] * y[1]) + x[2] * y[2];
    double b = (eX * pyz + nX * eyz + 8.0 * VBQ_U * nX * nyz) * (1.0 + 1e-12) + VBQ_TINY;
    return v > b ? 1 : (v < -b ? -1 : 0);
}

/* The rows Q of patch fr's face and square: qs[0] = n (the face's axis),
 * then e_u - u0 n, u1 n - e_u, e_v - v0 n, v1 n - e_v (exact doubles). */
VBS_FN void vbq_env_sides(vbs_u32 T, const vbq_frame *fr, double qs[5][3])
{
    double u0, u1, v0, v1;
    vbq_patch_square(T, fr->level, fr->iu, fr->iv, &u0, &u1, &v0, &v1);
    vbs_u32 ax = fr->f / 2u, au = (ax + 1u) % 3u, av = (ax + 2u) % 3u;
    double sgn = (fr->f & 1u) ? -1.0 : 1.0;
    for (int r = 0; r < 5; r++)
        for (int a = 0; a < 3; a++)
            qs[r][a] = 0.0;
    qs[0][ax] = sgn;
    qs[1][au] = 1.0;
    qs[1][ax] = -u0 * sgn;
    qs[2][au] = -1.0;
    qs[2][ax] = u1 * sgn;
    qs[3][av] = 1.0;
    qs[3][ax] = -v0 * sgn;
    qs[4][av] = -1.0;
    qs[4][ax] = v1 * sgn;
}

/* Is the owned triple (j, k, l) of the list lab[0 .. keep) a vertex of the
 * envelope on the patch (cover_envelope.c's tests, in doubles alone)? 0
 * when a decided test excludes it, else 2 when a test is undecided, else
 * 1: a function of the list as a set. *last: the label that beat the last
 * triple (tried first: speed only). */
VBS_FN int vbq_env_triple(const VBS_GLOBAL vbq_nb *nb, const VBS_GLOBAL vbs_u32 *lab,
                          vbs_u32 keep, vbs_u32 j, vbs_u32 k, vbs_u32 l, double qs[5][3],
                          vbs_u32 *last)
{
    vbq_nb rj = nb[lab[j]], rk = nb[lab[k]], rl = nb[lab[l]];
    double aj[3] = {rj.ax, rj.ay, rj.az};
    double dk[3] = {rk.ax - rj.ax, rk.ay - rj.ay, rk.az - rj.az};
    double dl[3] = {rl.ax - rj.ax, rl.ay - rj.ay, rl.az - rj.az}, y[3];
    y[0] = dk[1] * dl[2] - dk[2] * dl[1];
    y[1] = dk[2] * dl[0] - dk[0] * dl[2];
    y[2] = dk[0] * dl[1] - dk[1] * dl[0];
    double nY = vbq_env_n1(dk), nZ = vbq_env_n1(dl);
    double eY = (rj.err + rk.err) + 1.01 * VBQ_U * nY;
    double eZ = (rj.err + rl.err) + 1.01 * VBQ_U * nZ;
    double nyz = nY * nZ, eyz = (eY * nZ + nY * eZ) + eY * eZ, pyz = nyz + eyz;
    int sg = vbq_env_sign(qs[0], 1.0, 0.0, y, pyz, nyz, eyz);
    if (!sg)
        return 2;
    /* An undecided test does not stop the others: a decided exclusion
     * anywhere gives 0, so the answer does not depend on the list's order
     * (the group kernel's lists come in any order). */
    int und = 0;
    for (int e = 1; e < 5; e++) {
        int v = vbq_env_sign(qs[e], vbq_env_n1(qs[e]), 0.0, y, pyz, nyz, eyz);
        if (v && sg * v < 0)
            return 0;
        und |= !v;
    }
    int pv = vbq_env_sign(aj, vbq_env_n1(aj), rj.err, y, pyz, nyz, eyz);
    if (pv && sg * pv < 0)
        return 0;
    und |= !pv;
    for (vbs_u32 t = 0u; t <= keep; t++) {
        vbs_u32 m = t == 0u ? *last : t - 1u;
        if ((t > 0u && m == *last) || m >= keep || m == j || m == k || m == l)
            continue;
        vbq_nb rm = nb[lab[m]];
        double x[3] = {rm.ax - rj.ax, rm.ay - rj.ay, rm.az - rj.az};
        double nX = vbq_env_n1(x);
        int v = vbq_env_sign(x, nX, (rm.err + rj.err) + 1.01 * VBQ_U * nX, y, pyz, nyz, eyz);
        if (v && sg * v > 0) {
            *last = m;
            return 0;
        }
        und |= !v;
    }
    return und ? 2 : 1;
}

/* Is a closed patch that would subdivide (act 1) a stalled near-tie chain
 * whose ownership the host decides exactly (vbq_host_envelope,
 * core/cells/cover_envelope.c): its list excluded nothing for
 * VBQ_ENV_STALL levels, it has more than VBQ_CLUSTER_OWNED (fewer enumerate
 * cheaply once stalled) and at most VBQ_ENV_OWNED_SHALLOW owned labels, at
 * most VBQ_ENV_KEEP_SHALLOW in all; or a deep leaf (act 3) with as many labels, whose
 * C(owned, 3) quadruples the decision replaces by the envelope's own
 * (near-ties at the doubles' resolution reach the deepest level: sc 1,728
 * jittered 1e-12 wrote 91,186 quadruples, 52,264 so); off a GPU
 * (VBQ_ENV_DEEP) also a deep leaf or a patch past level VBQ_ENV_DEEP_LEVEL
 * with 3 to VBQ_ENV_OWNED owned labels, at most VBQ_ENV_KEEP in all (a
 * near-tie chain of few
 * labels: sc 2,744 jittered 1e-12 wrote 40,339 quadruples at such leaves,
 * 3,605 of them vertices, after ~40 levels of subdivision each),
 * every label's record has b exactly 0 and a finite error (spheres of the
 * base's radius in doubles; the host checks the decimals) and every vertex
 * is sought (no tangent-radius floor). The same answer on every backend:
 * a kernel decides such a patch with the double filter alone
 * (vbq_envelope_filter) and hands the cell to the host (status
 * VBQ_CLUSTER, like a tie cluster) only when a triple stays undecided, so
 * every backend writes the host's quadruples for it. */
VBS_FN int vbq_envelope_due(const vbq_env *e, const vbq_frame *fr, const VBS_GLOBAL vbq_nb *nb,
                            const VBS_GLOBAL vbs_u32 *lab, vbs_u32 keep, vbs_u32 owned, int act,
                            int closed)
{
    int deep = VBQ_ENV_DEEP(act, fr);
    if (!closed || (act != 1 && act != VBQ_ENV_DEEP_ACT) || owned < 3u ||
        (owned <= VBQ_CLUSTER_OWNED && !deep) ||
        owned > (deep ? VBQ_ENV_OWNED : VBQ_ENV_OWNED_SHALLOW) ||
        keep > (deep ? VBQ_ENV_KEEP : VBQ_ENV_KEEP_SHALLOW) ||
        (act == 1 && !deep && (keep != fr->len || fr->stall + 1u < VBQ_ENV_STALL)) ||
        e->tmax < (double)INFINITY)
        return 0;
    for (vbs_u32 a = 0u; a < keep; a++) {
        vbq_nb r = nb[lab[a]];
        if (r.b != 0.0 || !(r.err < (double)INFINITY))
            return 0;
    }
    return 1;
}

/* Does the double filter alone decide every owned triple of a due patch
 * (vbq_envelope_filter would not return 2)? Adds nothing. A deep patch of
 * few owned labels (VBQ_ENV_DEEP) is decided only then, on every backend:
 * an exact crystal's ties there (every sign 0) gave the enumeration's
 * quadruples at the cost of exact signs (fcc 1,372 exact 0.25 -> 0.27 s). */
VBS_FN int vbq_envelope_sure(const vbq_env *e, const vbq_arena *ar, vbs_u32 i, const vbq_frame *fr,
                             vbs_u32 top, vbs_u32 keep)
{
    double qs[5][3];
    vbq_env_sides(e->T, fr, qs);
    const VBS_GLOBAL vbs_u32 *lab = ar->lab + top;
    vbs_u32 last = 0u;
    for (vbs_u32 a = 0u; a < keep; a++) {
        if (ar->nb[lab[a]].id <= i)
            continue;
        for (vbs_u32 b = a + 1u; b < keep; b++) {
            if (ar->nb[lab[b]].id <= i)
                continue;
            for (vbs_u32 d = b + 1u; d < keep; d++)
                if (ar->nb[lab[d]].id > i && vbq_env_triple(ar->nb, lab, keep, a, b, d, qs, &last) == 2)
                    return 0;
        }
    }
    return 1;
}

#endif
