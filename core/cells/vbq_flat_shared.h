/* The direction cover, shared with the kernels (part of vb_cover_shared.h,
 * which includes it before vbq_cell_shared.h; include that header, never
 * this one): the flatness trigger of a tie cluster (vbq_looks_flat). */
#ifndef VBQ_FLAT_SHARED_H
#define VBQ_FLAT_SHARED_H

/* The host's fourth pass of vbq_looks_flat: are the owned labels' points
 * within tol of the 3-space through p0 spanned by the unit vectors v1, v2
 * and w2 / |w2| (w2: the point farthest from the plane, at squared
 * distance far)? The same products and sums as the pass it was (the terms
 * of v3 added last), so the same answers. */
VBS_FN int vbq_flat_space(const VBS_GLOBAL vbq_nb *nb, const VBS_GLOBAL vbs_u32 *lab, vbs_u32 keep,
                          vbs_u32 i, const double p0[4], const double v1[4], const double v2[4],
                          const double w2[4], double far, double tol)
{
    double v3[4], n3 = VBS_SQRT(far), worst = -1.0;
    for (int k = 0; k < 4; k++)
        v3[k] = w2[k] / n3;
    for (vbs_u32 a = 0u; a < keep; a++) {
        vbq_nb r = nb[lab[a]];
        if (r.id <= i)
            continue;
        double w[4] = {r.ax - p0[0], r.ay - p0[1], r.az - p0[2], r.b - p0[3]};
        double c1 = w[0] * v1[0] + w[1] * v1[1] + w[2] * v1[2] + w[3] * v1[3];
        double c2 = w[0] * v2[0] + w[1] * v2[1] + w[2] * v2[2] + w[3] * v2[3];
        double c3 = w[0] * v3[0] + w[1] * v3[1] + w[2] * v3[2] + w[3] * v3[3];
        double d2 = 0.0;
        for (int k = 0; k < 4; k++) {
            double e = w[k] - c1 * v1[k] - c2 * v2[k] - c3 * v3[k];
            d2 += e * e;
        }
        worst = d2 > worst ? d2 : worst;
    }
    return !(worst > tol * tol);
}

/* Do the owned labels (ids > i) of lab[0 .. keep) look like an exact tie
 * cluster: are their points (a, b) in R^4 on one affine plane, or (not on
 * a GPU: VBQ_FLAT_SPACE) on one affine 3-space (spheres tangent to one
 * sphere, unequal radii: asked only where some b is not 0), as far as the
 * doubles tell (within 8 times the records' error bounds and 1e-12 of the
 * points' size)? Only a trigger: the host decides exactly
 * (vbq_host_cluster) and enumerates whatever is not a cluster; near-ties
 * beyond the doubles' noise do not look flat and are left to the
 * subdivision. Three passes: the point farthest from the first, the one
 * farthest from their line, then every distance to the plane of the three;
 * then vbq_flat_space. With b = 0 (the base's radius) every point is on
 * one 3-space, and the near-ties of equal balls are left to the
 * subdivision and the envelope decision. */
VBS_FN int vbq_looks_flat(const VBS_GLOBAL vbq_nb *nb, const VBS_GLOBAL vbs_u32 *lab, vbs_u32 keep,
                          vbs_u32 i)
{
    double p0[4] = {0.0, 0.0, 0.0, 0.0}, v1[4] = {0.0, 0.0, 0.0, 0.0}, v2[4] = {0.0, 0.0, 0.0, 0.0};
    double scale = 0.0, emax = 0.0, best = -1.0, bmax = 0.0;
    int have = 0;
    for (vbs_u32 a = 0u; a < keep; a++) {
        vbq_nb r = nb[lab[a]];
        if (r.id <= i)
            continue;
        if (!(r.err < (double)INFINITY))
            return 0;
        double q[4] = {r.ax, r.ay, r.az, r.b};
        emax = r.err > emax ? r.err : emax;
        bmax = VBS_FABS(r.b) > bmax ? VBS_FABS(r.b) : bmax;
        for (int k = 0; k < 4; k++)
            scale = VBS_FABS(q[k]) > scale ? VBS_FABS(q[k]) : scale;
        if (!have) {
            for (int k = 0; k < 4; k++)
                p0[k] = q[k];
            have = 1;
            continue;
        }
        double d2 = 0.0;
        for (int k = 0; k < 4; k++)
            d2 += (q[k] - p0[k]) * (q[k] - p0[k]);
        if (d2 > best) {
            best = d2;
            for (int k = 0; k < 4; k++)
                v1[k] = q[k] - p0[k];
        }
    }
    double tol = 8.0 * emax + 1e-12 * scale;
    if (!(best > tol * tol))
        return 1;
    double n1 = VBS_SQRT(best);
    for (int k = 0; k < 4; k++)
        v1[k] /= n1;
    for (int pass = 0; pass < 2; pass++) {
        double far = -1.0, w2[4] = {0.0, 0.0, 0.0, 0.0};
#ifdef VBQ_LANES
        /* the pass in lanes, then the farthest label's e again */
        vbs_u32 at;
        vbq_flat_far_lanes(nb, lab, keep, i, p0, v1, v2, &far, &at);
        for (vbs_u32 a = at; a < at + 1u && a < keep; a++) {
#else
        for (vbs_u32 a = 0u; a < keep; a++) {
#endif
            vbq_nb r = nb[lab[a]];
            if (r.id <= i)
                continue;
            double w[4] = {r.ax - p0[0], r.ay - p0[1], r.az - p0[2], r.b - p0[3]};
            double c1 = w[0] * v1[0] + w[1] * v1[1] + w[2] * v1[2] + w[3] * v1[3];
            double c2 = w[0] * v2[0] + w[1] * v2[1] + w[2] * v2[2] + w[3] * v2[3];
            double e[4], d2 = 0.0;
            for (int k = 0; k < 4; k++) {
                e[k] = w[k] - c1 * v1[k] - c2 * v2[k];
                d2 += e[k] * e[k];
            }
#ifdef VBQ_LANES
            far = -1.0; /* the same d2 again: taken below */
#endif
            if (d2 > far) {
                far = d2;
                for (int k = 0; k < 4; k++)
                    w2[k] = e[k];
            }
        }
        if (!(far > tol * tol))
            return 1;
        if (pass == 1)
            return VBQ_FLAT_SPACE && bmax > tol &&
                   vbq_flat_space(nb, lab, keep, i, p0, v1, v2, w2, far, tol);
        double n2 = VBS_SQRT(far);
        for (int k = 0; k < 4; k++)
            v2[k] = w2[k] / n2;
    }
    return 0;
}

#endif
