/* The sampling geometry of the seed paper, shared with the kernels (part
 * of vb_geom_shared.h, which includes it last; include that header, never
 * this one): Sec. 4-5, one grid cell of rays with subdivision and restarts;
 * tangent spheres of four spheres in double (candidates only); the
 * vertices of one cell. */
#ifndef VBS_CELL_SHARED_H
#define VBS_CELL_SHARED_H

/* ---- Sec. 4-5: one grid cell, with subdivision and restarts ------------- */

typedef struct vbs_quad {
    double u0, v0, h;     /* lower corner and side in face coordinates */
    vbs_u32 col[4];       /* colours at (u0,v0), (u0+h,v0), (u0,v0+h), (u0+h,v0+h) */
    vbs_u32 depth;
} vbs_quad;

/* Where a grid cell's candidates go: a private array of `cap` entries. */
typedef struct vbs_emit {
    vbs_cand *out;
    vbs_u32 cap, n;
    vbs_u32 overflow;     /* candidates that did not fit */
    vbs_u32 cell;
} vbs_emit;

/* Copies the bisector of sphere `id` out of the base's list (private copy for
 * Newton). Returns 0 if the id is not a neighbour of the base. */
VBS_FN int vbs_find_bisector(const VBS_GLOBAL vbs_base *base,
                             const VBS_GLOBAL vbs_bisector *bis, vbs_u32 id,
                             vbs_bisector *out)
{
    /* Bisectors of a base are stored sorted by id: binary search. */
    vbs_u32 lo = base->bis_start, hi = base->bis_start + base->bis_count;
    while (lo < hi) {
        vbs_u32 mid = lo + (hi - lo) / 2u;
        if (bis[mid].id < id)
            lo = mid + 1u;
        else
            hi = mid;
    }
    if (lo >= base->bis_start + base->bis_count || bis[lo].id != id)
        return 0;
    *out = bis[lo];
    return 1;
}

/* Tries to find the vertex of the triple from the ray d (unit): start at the
 * triple's own lower envelope along d (Sec. 5), and when the converged point
 * is not equidistant (a wrong sheet, Sec. 5.3) restart from each of the three
 * ray/bisector hits. Accepts only points whose direction lies within angle
 * `cosmax` of d. Returns 1 with P set, 0 on failure; *flags gets
 * VBS_CF_RESTARTED when a restart was needed. */
VBS_FN int vbs_solve_triple(const vbs_bisector tri[3], const double d[3], double eq_tol,
                            double cosmax, double sing, vbs_u32 max_iter, double P[3],
                            vbs_u32 *flags)
{
    double hits[3];
    double s0 = -1.0;
    for (int k = 0; k < 3; k++) {
        hits[k] = vbs_ray_hit(tri[k].ex, tri[k].ey, tri[k].ez, tri[k].delta, tri[k].num, d);
        if (hits[k] >= 0.0 && (s0 < 0.0 || hits[k] < s0))
            s0 = hits[k];
    }
    if (s0 < 0.0)
        return 0;
    /* Attempt 0: the envelope point; attempts 1..3: each bisector's hit. */
    for (int attempt = 0; attempt < 4; attempt++) {
        double s = attempt == 0 ? s0 : hits[attempt - 1];
        if (s < 0.0 || (attempt > 0 && s == s0))
            continue;
        P[0] = s * d[0];
        P[1] = s * d[1];
        P[2] = s * d[2];
        if (vbs_newton(&tri[0], &tri[1], &tri[2], sing, max_iter, P) != VBS_NEWTON_OK)
            return 0; /* singular or oscillating: the caller subdivides */
        double np = VBS_SQRT(P[0] * P[0] + P[1] * P[1] + P[2] * P[2]);
        if (!(np > 0.0))
            return 0;
        int equi = 1;
        for (int k = 0; k < 3; k++)
            if (!(VBS_FABS(vbs_defect(&tri[k], P)) <= eq_tol))
                equi = 0;
        if (!equi) {
            *flags |= VBS_CF_RESTARTED;
            continue;
        }
        double c = (P[0] * d[0] + P[1] * d[1] + P[2] * d[2]) / np;
        return c >= cosmax;
    }
    return 0;
}

VBS_FN void vbs_emit_point(const VBS_GLOBAL vbs_base *base, vbs_u32 a, vbs_u32 b, vbs_u32 c,
                           const double P[3], vbs_u32 flags, vbs_emit *em)
{
    if (em->n >= em->cap) {
        em->overflow++;
        return;
    }
    vbs_cand *o = em->out + em->n;
    double np = VBS_SQRT(P[0] * P[0] + P[1] * P[1] + P[2] * P[2]);
    o->x = base->cx + base->scale * P[0];
    o->y = base->cy + base->scale * P[1];
    o->z = base->cz + base->scale * P[2];
    o->t = base->scale * np - base->r;
    o->ids[0] = base->id;
    o->ids[1] = a;
    o->ids[2] = b;
    o->ids[3] = c;
    o->cell = em->cell;
    o->seq = em->n;
    o->flags = flags;
    o->pad = 0u;
    em->n++;
}

/* Unit average of corner rays `mask` (bit k = corner k) of quad q on face f;
 * *cosr gets the cosine of the largest angle from it to those corners. */
VBS_FN void vbs_quad_ray(vbs_u32 f, const vbs_quad *q, vbs_u32 mask, double d[3], double *cosr)
{
    double cd[4][3];
    double sx = 0.0, sy = 0.0, sz = 0.0;
    for (vbs_u32 k = 0u; k < 4u; k++) {
        double u = q->u0 + ((k & 1u) ? q->h : 0.0);
        double v = q->v0 + ((k & 2u) ? q->h : 0.0);
        vbs_face_dir(f, u, v, cd[k]);
        if (mask & (1u << k)) {
            sx += cd[k][0];
            sy += cd[k][1];
            sz += cd[k][2];
        }
    }
    double n = VBS_SQRT(sx * sx + sy * sy + sz * sz);
    d[0] = sx / n;
    d[1] = sy / n;
    d[2] = sz / n;
    double cmin = 1.0;
    for (vbs_u32 k = 0u; k < 4u; k++) {
        double c = cd[k][0] * d[0] + cd[k][1] * d[1] + cd[k][2] * d[2];
        if (c < cmin)
            cmin = c;
    }
    *cosr = cmin;
}

/* Processes one grid cell of base `base` on face f (Sec. 4-5): three finite
 * colours -> Newton from the averaged ray; four -> every triple from the
 * average of its three corners, and subdivision when they disagree (5.2);
 * singular Jacobian, oscillation or a failed restart -> subdivision into four
 * children with five new rays (5.1), down to p->max_depth. Rays of colour
 * VBS_INF_COLOUR mark a vertex at infinity and take part in no triple. */
VBS_FN void vbs_process_cell(const VBS_GLOBAL vbs_base *base,
                             const VBS_GLOBAL vbs_bisector *bis,
                             const VBS_GLOBAL vbs_u32 *tile_off,
                             const VBS_GLOBAL vbs_u32 *tile_idx, const vbs_params *p,
                             vbs_u32 f, const vbs_quad *root, vbs_u32 extra_flags,
                             vbs_emit *em)
{
    vbs_quad stack[VBS_STACK];
    vbs_u32 top = 0u;
    stack[top++] = *root;
    double eq_tol = p->tol / base->scale;
    while (top > 0u) {
        vbs_quad q = stack[--top];
        /* Distinct finite colours and the corners that carry each. */
        vbs_u32 cols[4], masks[4], nc = 0u;
        for (vbs_u32 k = 0u; k < 4u; k++) {
            vbs_u32 c = q.col[k];
            if (c == VBS_INF_COLOUR)
                continue;
            vbs_u32 m = 0u;
            while (m < nc && cols[m] != c)
                m++;
            if (m == nc) {
                cols[nc] = c;
                masks[nc] = 0u;
                nc++;
            }
            masks[m] |= 1u << k;
        }
        if (nc < 3u)
            continue;
        vbs_u32 flags = extra_flags | (q.depth > root->depth ? VBS_CF_SUBDIVIDED : 0u);
        int failed = 0;
        if (nc == 3u) {
            vbs_bisector tri[3];
            double d[3], cosr, P[3];
            vbs_u32 fl = flags;
            vbs_quad_ray(f, &q, 15u, d, &cosr);
            /* Accept points within twice the cell's angular radius. */
            double cosmax = 2.0 * cosr * cosr - 1.0;
            if (vbs_find_bisector(base, bis, cols[0], &tri[0]) &&
                vbs_find_bisector(base, bis, cols[1], &tri[1]) &&
                vbs_find_bisector(base, bis, cols[2], &tri[2]) &&
                vbs_solve_triple(tri, d, eq_tol, cosmax, p->sing, p->max_iter, P, &fl))
                vbs_emit_point(base, cols[0], cols[1], cols[2], P, fl, em);
            else
                failed = 1;
        } else {
            /* Four colours: one triple per omitted colour, started from the
             * average of the three corners that carry the kept colours. */
            double pts[4][3];
            vbs_u32 ok[4], fls[4];
            vbs_u32 nok = 0u;
            double d4[3], cos4;
            vbs_quad_ray(f, &q, 15u, d4, &cos4);
            double cosmax = 2.0 * cos4 * cos4 - 1.0;
            for (vbs_u32 skip = 0u; skip < 4u; skip++) {
                vbs_bisector tri[3];
                vbs_u32 m = 0u, mask = 0u;
                ok[skip] = 0u;
                fls[skip] = flags | VBS_CF_FOURCOLOUR;
                int have = 1;
                for (vbs_u32 k = 0u; k < 4u; k++) {
                    if (k == skip)
                        continue;
                    have &= vbs_find_bisector(base, bis, cols[k], &tri[m]);
                    mask |= masks[k];
                    m++;
                }
                double d[3], cosr;
                vbs_quad_ray(f, &q, mask, d, &cosr);
                if (have && vbs_solve_triple(tri, d, eq_tol, cosmax, p->sing, p->max_iter,
                                             pts[skip], &fls[skip])) {
                    ok[skip] = 1u;
                    nok++;
                }
            }
            /* Agreement: every converged triple at one point (within tol). */
            int agree = nok == 4u;
            for (vbs_u32 a = 0u; a < 4u && agree; a++)
                for (vbs_u32 b = a + 1u; b < 4u; b++) {
                    double dx = pts[a][0] - pts[b][0], dy = pts[a][1] - pts[b][1],
                           dz = pts[a][2] - pts[b][2];
                    if (!(VBS_SQRT(dx * dx + dy * dy + dz * dz) <= eq_tol))
                        agree = 0;
                }
            if (agree || q.depth >= p->max_depth) {
                for (vbs_u32 skip = 0u; skip < 4u; skip++) {
                    if (!ok[skip])
                        continue;
                    vbs_u32 t3[3], m = 0u;
                    for (vbs_u32 k = 0u; k < 4u; k++)
                        if (k != skip)
                            t3[m++] = cols[k];
                    vbs_emit_point(base, t3[0], t3[1], t3[2], pts[skip], fls[skip], em);
                }
            } else {
                failed = 1;
            }
        }
        if (!failed || q.depth >= p->max_depth || top + 4u > VBS_STACK)
            continue;
        /* Sec. 5.1: five new rays (edge midpoints and centre), four children. */
        double hh = 0.5 * q.h, d[3], s;
        vbs_u32 T = p->tiles;
        vbs_u32 cb = vbs_envelope_at(base, bis, tile_off, tile_idx, T, f, q.u0 + hh, q.v0, d, &s);
        vbs_u32 cl = vbs_envelope_at(base, bis, tile_off, tile_idx, T, f, q.u0, q.v0 + hh, d, &s);
        vbs_u32 cm = vbs_envelope_at(base, bis, tile_off, tile_idx, T, f, q.u0 + hh, q.v0 + hh, d, &s);
        vbs_u32 cr = vbs_envelope_at(base, bis, tile_off, tile_idx, T, f, q.u0 + q.h, q.v0 + hh, d, &s);
        vbs_u32 ct = vbs_envelope_at(base, bis, tile_off, tile_idx, T, f, q.u0 + hh, q.v0 + q.h, d, &s);
        vbs_quad c;
        c.h = hh;
        c.depth = q.depth + 1u;
        /* Pushed in reverse so the lower-left child is processed first. */
        c.u0 = q.u0 + hh; c.v0 = q.v0 + hh;
        c.col[0] = cm; c.col[1] = cr; c.col[2] = ct; c.col[3] = q.col[3];
        stack[top++] = c;
        c.u0 = q.u0; c.v0 = q.v0 + hh;
        c.col[0] = cl; c.col[1] = cm; c.col[2] = q.col[2]; c.col[3] = ct;
        stack[top++] = c;
        c.u0 = q.u0 + hh; c.v0 = q.v0;
        c.col[0] = cb; c.col[1] = q.col[1]; c.col[2] = cm; c.col[3] = cr;
        stack[top++] = c;
        c.u0 = q.u0; c.v0 = q.v0;
        c.col[0] = q.col[0]; c.col[1] = cb; c.col[2] = cl; c.col[3] = cm;
        stack[top++] = c;
    }
}

/* Grid cell (f, iu, iv) of a batch base, corners read from the colour array
 * of that base (6*S*S entries, face-major, then v, then u). */
VBS_FN void vbs_grid_quad(const VBS_GLOBAL vbs_u32 *colours, vbs_u32 S, vbs_u32 f,
                          vbs_u32 iu, vbs_u32 iv, vbs_quad *q)
{
    const VBS_GLOBAL vbs_u32 *c = colours + f * S * S;
    q->u0 = vbs_sample_coord(iu, S);
    q->v0 = vbs_sample_coord(iv, S);
    q->h = vbs_sample_coord(iu + 1u, S) - q->u0;
    q->col[0] = c[iv * S + iu];
    q->col[1] = c[iv * S + iu + 1u];
    q->col[2] = c[(iv + 1u) * S + iu];
    q->col[3] = c[(iv + 1u) * S + iu + 1u];
    q->depth = 0u;
}

/* ---- Tangent spheres of four spheres, in double (candidates only) ------ */

/* Points p and radii t with |p - c_k| = t + r_k for the four spheres s[k]
 * (x, y, z, r each), relative to sphere 0: with q = p - c_0, e_k = c_k - c_0,
 * the differences give three linear equations 2 e_k.q + 2 (r_k - r_0) t =
 * |e_k|^2 - r_k^2 + r_0^2. The best-conditioned 3x3 minor of [e_k | dr_k]
 * gives three unknowns as u + w s in the fourth, and |q|^2 = (t + r_0)^2
 * becomes a quadratic in s. Writes up to two roots (x, y, z, t) to out and
 * returns their number; 0 when the minor is singular (the exact certifier
 * handles such sets) or no real root has t + r_k >= 0 for all k. */
VBS_FN int vbs_tangent_roots(const double s[4][4], double out[2][4])
{
    double M[3][4], b[3];
    for (int k = 0; k < 3; k++) {
        double ex = s[k + 1][0] - s[0][0], ey = s[k + 1][1] - s[0][1], ez = s[k + 1][2] - s[0][2];
        M[k][0] = ex;
        M[k][1] = ey;
        M[k][2] = ez;
        M[k][3] = s[k + 1][3] - s[0][3];
        b[k] = 0.5 * ((ex * ex + ey * ey + ez * ez) - s[k + 1][3] * s[k + 1][3] + s[0][3] * s[0][3]);
    }
    /* Free column: the one whose removal leaves the largest |det|. */
    int free_col = -1;
    double best = 0.0, bdet = 0.0;
    int cols[3];
    for (int f = 0; f < 4; f++) {
        int c[3], m = 0;
        for (int j = 0; j < 4; j++)
            if (j != f)
                c[m++] = j;
        double det = M[0][c[0]] * (M[1][c[1]] * M[2][c[2]] - M[1][c[2]] * M[2][c[1]]) -
                     M[0][c[1]] * (M[1][c[0]] * M[2][c[2]] - M[1][c[2]] * M[2][c[0]]) +
                     M[0][c[2]] * (M[1][c[0]] * M[2][c[1]] - M[1][c[1]] * M[2][c[0]]);
        if (VBS_FABS(det) > best) {
            best = VBS_FABS(det);
            bdet = det;
            free_col = f;
            cols[0] = c[0];
            cols[1] = c[1];
            cols[2] = c[2];
        }
    }
    double scale = 0.0;
    for (int k = 0; k < 3; k++)
        for (int j = 0; j < 4; j++)
            scale += M[k][j] * M[k][j];
    if (free_col < 0 || !(best > 1e-12 * scale * VBS_SQRT(scale)))
        return 0;
    /* Solve A x = r for r = b (u) and r = -M[:,free] (w) by Cramer. */
    double u[4] = {0.0, 0.0, 0.0, 0.0}, w[4] = {0.0, 0.0, 0.0, 0.0};
    for (int pass = 0; pass < 2; pass++) {
        double r[3];
        for (int k = 0; k < 3; k++)
            r[k] = pass == 0 ? b[k] : -M[k][free_col];
        for (int j = 0; j < 3; j++) {
            double A[3][3];
            for (int k = 0; k < 3; k++)
                for (int m = 0; m < 3; m++)
                    A[k][m] = m == j ? r[k] : M[k][cols[m]];
            double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                         A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                         A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
            if (pass == 0)
                u[cols[j]] = det / bdet;
            else
                w[cols[j]] = det / bdet;
        }
    }
    w[free_col] = 1.0;
    double r0 = s[0][3];
    double qa = w[0] * w[0] + w[1] * w[1] + w[2] * w[2] - w[3] * w[3];
    double qb = 2.0 * ((u[0] * w[0] + u[1] * w[1] + u[2] * w[2] - u[3] * w[3]) - r0 * w[3]);
    double qc = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2] - u[3] * u[3]) - 2.0 * r0 * u[3] - r0 * r0;
    double roots[2];
    int nr = 0;
    double mag = VBS_FABS(qa) + VBS_FABS(qb) + VBS_FABS(qc);
    if (VBS_FABS(qa) <= 1e-14 * mag) {
        if (VBS_FABS(qb) > 0.0)
            roots[nr++] = -qc / qb;
    } else {
        double disc = qb * qb - 4.0 * qa * qc;
        if (disc < 0.0 && disc > -1e-12 * qb * qb)
            disc = 0.0;
        if (disc >= 0.0) {
            double sq = VBS_SQRT(disc);
            /* Numerically stable pair of roots. */
            double qq = -0.5 * (qb + (qb >= 0.0 ? sq : -sq));
            roots[nr++] = qq / qa;
            if (qq != 0.0 && disc > 0.0)
                roots[nr++] = qc / qq;
        }
    }
    int n = 0;
    for (int k = 0; k < nr; k++) {
        double X[4];
        for (int j = 0; j < 4; j++)
            X[j] = u[j] + w[j] * roots[k];
        int ok = 1;
        double tol = 1e-9 * (VBS_SQRT(scale) + VBS_FABS(X[3]) + r0);
        for (int m = 0; m < 4 && ok; m++) {
            double px = X[0] + s[0][0] - s[m][0], py = X[1] + s[0][1] - s[m][1],
                   pz = X[2] + s[0][2] - s[m][2];
            double dist = VBS_SQRT(px * px + py * py + pz * pz);
            if (!(VBS_FABS(dist - (X[3] + s[m][3])) <= tol))
                ok = 0;
        }
        if (!ok)
            continue;
        out[n][0] = X[0] + s[0][0];
        out[n][1] = X[1] + s[0][1];
        out[n][2] = X[2] + s[0][2];
        out[n][3] = X[3];
        n++;
    }
    return n;
}

/* Colour of grid ray (f, iu, iv) of a base: the envelope stage per ray. */
VBS_FN vbs_u32 vbs_ray_colour(const VBS_GLOBAL vbs_base *base,
                              const VBS_GLOBAL vbs_bisector *bis,
                              const VBS_GLOBAL vbs_u32 *tile_off,
                              const VBS_GLOBAL vbs_u32 *tile_idx, vbs_u32 T, vbs_u32 S,
                              vbs_u32 f, vbs_u32 iu, vbs_u32 iv)
{
    double d[3], s;
    return vbs_envelope_at(base, bis, tile_off, tile_idx, T, f, vbs_sample_coord(iu, S),
                           vbs_sample_coord(iv, S), d, &s);
}

/* The vertex stage for grid cell `cell` (f * (S-1)^2 + iv * (S-1) + iu) of a
 * base whose 6*S*S colours are `colours`; candidates go to em. */
VBS_FN void vbs_cell_vertices(const VBS_GLOBAL vbs_base *base,
                              const VBS_GLOBAL vbs_bisector *bis,
                              const VBS_GLOBAL vbs_u32 *tile_off,
                              const VBS_GLOBAL vbs_u32 *tile_idx, const vbs_params *p,
                              const VBS_GLOBAL vbs_u32 *colours, vbs_u32 cell, vbs_emit *em)
{
    vbs_u32 S = p->samples, g = S - 1u;
    vbs_u32 f = cell / (g * g), r = cell % (g * g);
    vbs_u32 iv = r / g, iu = r % g;
    vbs_quad q;
    vbs_grid_quad(colours, S, f, iu, iv, &q);
    /* Most cells see one or two colours: leave before any setup. */
    if (q.col[0] == q.col[1] && q.col[2] == q.col[3])
        return;
    if (q.col[0] == q.col[2] && q.col[1] == q.col[3])
        return;
    em->cell = cell;
    vbs_process_cell(base, bis, tile_off, tile_idx, p, f, &q, 0u, em);
}

#endif
