// The CGAL cross-check, vorball's side (vb_cgal.h): each line's ids alone,
// from which the point is re-derived in GMP integers, compared exactly with
// CGAL's vertices (cgal_bridge.cpp builds them). No CGAL here.
#include "vbx_cgal.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <map>
#include <numeric>
#include <utility>

using namespace vbx_cgal;

namespace {

// vorball's side: the input as integers, X = x * 10^E and
// S = |X|^2 - (R * 10^E)^2 with E large enough to clear every denominator.
struct Scaled {
    size_t n;
    int E;
    ZVec X, S;
    mpz_t pow10;
    explicit Scaled(const vb_sphere_set *set) : n(set->n), E(0), X(3 * set->n), S(set->n)
    {
        for (size_t i = 0; i < n; i++)
            for (vb_decimal d : {set->ex[i], set->ey[i], set->ez[i], set->er[i]})
                E = std::max(E, -d.exp10);
        mpz_init(pow10);
        mpz_ui_pow_ui(pow10, 10, (unsigned long)E);
        mpz_t t;
        mpz_init(t);
        for (size_t i = 0; i < n; i++) {
            decimal_scaled(X[3 * i + 0], set->ex[i], E);
            decimal_scaled(X[3 * i + 1], set->ey[i], E);
            decimal_scaled(X[3 * i + 2], set->ez[i], E);
            decimal_scaled(t, set->er[i], E);
            mpz_mul(S[i], t, t);
            mpz_neg(S[i], S[i]);
            for (int c = 0; c < 3; c++)
                mpz_addmul(S[i], X[3 * i + c], X[3 * i + c]);
        }
        mpz_clear(t);
    }
    ~Scaled() { mpz_clear(pow10); }
    Scaled(const Scaled &) = delete;
    Scaled &operator=(const Scaled &) = delete;
};

// Scratch integers for recovering one point from ids.
struct Solver {
    ZVec a, b, c, r, tmp, N;
    mpz_t D, lhs, rhs;
    Solver() : a(3), b(3), c(3), r(3), tmp(3), N(3)
    {
        mpz_inits(D, lhs, rhs, (mpz_ptr)0);
    }
    ~Solver() { mpz_clears(D, lhs, rhs, (mpz_ptr)0); }
    Solver(const Solver &) = delete;
    Solver &operator=(const Solver &) = delete;
};

void sub3(const Scaled &s, size_t j, size_t i0, ZVec &out)
{
    for (int k = 0; k < 3; k++)
        mpz_sub(out[k], s.X[3 * j + k], s.X[3 * i0 + k]);
}

void cross3(const ZVec &u, const ZVec &v, ZVec &out)
{
    for (int k = 0; k < 3; k++) {
        int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        mpz_mul(out[k], u[k1], v[k2]);
        mpz_submul(out[k], u[k2], v[k1]);
    }
}

void dot3(mpz_ptr out, const ZVec &u, const ZVec &v)
{
    mpz_mul(out, u[0], v[0]);
    mpz_addmul(out, u[1], v[1]);
    mpz_addmul(out, u[2], v[2]);
}

bool is_zero3(const ZVec &u)
{
    return !mpz_sgn(u[0]) && !mpz_sgn(u[1]) && !mpz_sgn(u[2]);
}

// The exact point of the sphere ids `ids` (sorted): the point at one power
// distance from all of them, written to p[0..2]. Returns NULL on success or
// why the ids define no point.
const char *point_of_ids(const Scaled &s, Solver &w, const uint32_t *ids, size_t m, mpq_ptr p)
{
    if (m < 4)
        return "fewer than 4 ids";
    for (size_t i = 0; i < m; i++) {
        if (ids[i] >= s.n)
            return "id out of range";
        if (i && ids[i] == ids[i - 1])
            return "repeated id";
    }
    size_t i0 = ids[0], j = 1;
    // Four affinely independent centres: a, b, c span 3D from centre i0.
    for (; j < m; j++) {
        sub3(s, ids[j], i0, w.a);
        if (!is_zero3(w.a))
            break;
    }
    size_t ja = j++;
    for (; j < m; j++) {
        sub3(s, ids[j], i0, w.b);
        cross3(w.a, w.b, w.tmp);
        if (!is_zero3(w.tmp))
            break;
    }
    size_t jb = j++;
    for (; j < m; j++) {
        sub3(s, ids[j], i0, w.c);
        dot3(w.D, w.tmp, w.c);
        if (mpz_sgn(w.D))
            break;
    }
    if (j >= m)
        return "centres do not span 3D";
    size_t jc = j;
    // 2 (X_j - X_0) . P = S_j - S_0 for j = a, b, c; Cramer's rule gives
    // P = (r_a (b x c) + r_b (c x a) + r_c (a x b)) / (2 det[a b c]).
    mpz_sub(w.r[0], s.S[ids[ja]], s.S[i0]);
    mpz_sub(w.r[1], s.S[ids[jb]], s.S[i0]);
    mpz_sub(w.r[2], s.S[ids[jc]], s.S[i0]);
    for (int k = 0; k < 3; k++)
        mpz_set_ui(w.N[k], 0);
    const ZVec *rows[3][2] = {{&w.b, &w.c}, {&w.c, &w.a}, {&w.a, &w.b}};
    for (int q = 0; q < 3; q++) {
        cross3(*rows[q][0], *rows[q][1], w.tmp);
        for (int k = 0; k < 3; k++)
            mpz_addmul(w.N[k], w.r[q], w.tmp[k]);
    }
    mpz_mul_2exp(w.D, w.D, 1);
    // Every member at the same power distance: 2 N . (X_j - X_0) = D (S_j - S_0).
    for (size_t i = 1; i < m; i++) {
        sub3(s, ids[i], i0, w.tmp);
        dot3(w.lhs, w.N, w.tmp);
        mpz_mul_2exp(w.lhs, w.lhs, 1);
        mpz_sub(w.rhs, s.S[ids[i]], s.S[i0]);
        mpz_mul(w.rhs, w.rhs, w.D);
        if (mpz_cmp(w.lhs, w.rhs))
            return "members not at one power distance from any point";
    }
    for (int k = 0; k < 3; k++) {
        mpz_set(mpq_numref(p + k), w.N[k]);
        mpz_mul(mpq_denref(p + k), w.D, s.pow10);
        if (mpz_sgn(mpq_denref(p + k)) < 0) {
            mpz_neg(mpq_denref(p + k), mpq_denref(p + k));
            mpz_neg(mpq_numref(p + k), mpq_numref(p + k));
        }
        mpq_canonicalize(p + k);
    }
    return NULL;
}

// True when every sphere of `ids` is at one power distance from the exact
// point p: S_j - 2 P . X_j is the same for all j, with P = p * 10^E.
bool at_one_power_distance(const Scaled &s, const uint32_t *ids, size_t m, mpq_srcptr p)
{
    QVec P(3), v(2), tmp(1);
    mpq_ptr x = tmp[0];
    for (int k = 0; k < 3; k++) {
        mpq_set_z(x, s.pow10);
        mpq_mul(P[k], p + k, x);
    }
    bool same = true;
    for (size_t i = 0; i < m && same; i++) {
        mpq_ptr vi = v[i ? 1 : 0];
        mpq_set_z(vi, s.S[ids[i]]);
        for (int k = 0; k < 3; k++) {
            mpq_set_z(x, s.X[3 * (size_t)ids[i] + k]);
            mpq_mul(x, x, P[k]);
            mpq_sub(vi, vi, x);
            mpq_sub(vi, vi, x);
        }
        same = !i || mpq_equal(v[0], v[1]);
    }
    return same;
}

int compare(vb_ctx *ctx, const vb_cgal_diagram *d, const vb_sphere_set *set,
            const vb_vertex_list *v, const long *lines, unsigned flags, FILE *report,
            vb_cgal_diff *diff)
{
    *diff = vb_cgal_diff();
    if (set->n != d->nspheres)
        return vb_error(ctx, VB_EMISUSE, NULL, 0,
                        "vb_cgal_compare: the sphere set (%zu) is not the diagram's (%zu)",
                        set->n, d->nspheres);
    size_t nv = v->n, nc = d->start.size() - 1;
    auto line_of = [&](size_t i) { return lines ? lines[i] : (long)(i + 1); };
    auto vids = [&](size_t i) { return v->ids + v->start[i]; };
    auto vlen = [&](size_t i) { return v->start[i + 1] - v->start[i]; };

    // Exact point of every vorball line, from its ids.
    Scaled s(set);
    Solver w;
    QVec pts(3 * nv);
    std::vector<const char *> why(nv);
    std::vector<size_t> valid;
    for (size_t i = 0; i < nv; i++) {
        why[i] = point_of_ids(s, w, vids(i), vlen(i), pts[3 * i]);
        if (!why[i])
            valid.push_back(i);
    }
    std::sort(valid.begin(), valid.end(), [&](size_t a, size_t b) {
        int c = cmp_point(pts[3 * a], pts[3 * b]);
        return c ? c < 0 : a < b;
    });
    // Lines with one exact point form one vorball vertex.
    std::vector<std::vector<size_t>> glines;
    for (size_t q = 0; q < valid.size(); q++) {
        if (q == 0 || cmp_point(pts[3 * valid[q - 1]], pts[3 * valid[q]]))
            glines.emplace_back();
        glines.back().push_back(valid[q]);
    }
    // A Voronota quadruple need not determine its point (four coplanar cube
    // corners do not): such a line joins the vertex whose line prints the
    // same coordinates, when its spheres are exactly at one power distance
    // from that vertex's exact point. The doubles only choose the candidate.
    if (flags & VB_CGAL_ALLOW_SPLIT) {
        std::map<std::array<double, 3>, size_t> by_print;
        for (size_t g = 0; g < glines.size(); g++)
            for (size_t i : glines[g])
                by_print.emplace(std::array<double, 3>{v->x[i], v->y[i], v->z[i]}, g);
        for (size_t i = 0; i < nv; i++) {
            if (!why[i] || vlen(i) < 4)
                continue;
            auto it = by_print.find({v->x[i], v->y[i], v->z[i]});
            if (it == by_print.end())
                continue;
            const std::vector<size_t> &g = glines[it->second];
            if (at_one_power_distance(s, vids(i), vlen(i), pts[3 * g[0]])) {
                why[i] = NULL;
                glines[it->second].push_back(i);
            }
        }
    }
    size_t ng = glines.size();
    std::vector<size_t> corder(nc);
    std::iota(corder.begin(), corder.end(), 0);
    std::sort(corder.begin(), corder.end(), [&](size_t a, size_t b) {
        return cmp_point(&d->xyz[3 * a], &d->xyz[3 * b]) < 0;
    });
    // Pair vorball vertices with CGAL's: both lists sorted by exact point.
    std::vector<size_t> match_of_cgal(nc, SIZE_MAX), match_of_group(ng, SIZE_MAX);
    for (size_t g = 0, c = 0; g < ng && c < nc;) {
        int cmp = cmp_point(pts[3 * glines[g][0]], &d->xyz[3 * corder[c]]);
        if (cmp == 0) {
            match_of_cgal[corder[c]] = g;
            match_of_group[g] = corder[c];
            g++;
            c++;
        } else if (cmp < 0) {
            g++;
        } else {
            c++;
        }
    }
    diff->cgal = nc;
    diff->theirs = ng;
    // Coordinates are checked against CGAL's only when vorball's point is
    // the rational one: equal radii. With unequal radii (--power) vorball's
    // vertices are those of the additively weighted diagram.
    bool check_rounding = d->equal_radii;
    auto out = [&](const std::string &line) {
        if (report)
            fprintf(report, "%s\n", line.c_str());
    };
    auto num = [](double x) {
        char b[40];
        snprintf(b, sizeof b, "%.17g", x);
        return std::string(b);
    };

    std::vector<uint32_t> uni;
    for (size_t k = 0; k < nc; k++) {
        const uint32_t *cid = &d->ids[d->start[k]];
        size_t cn = d->start[k + 1] - d->start[k];
        std::string where = num(d->x[k]) + "\t" + num(d->y[k]) + "\t" + num(d->z[k]);
        size_t g = match_of_cgal[k];
        if (g == SIZE_MAX) {
            diff->missing++;
            out("missing\t" + ids_text(cid, cn) + "\t" + where);
            continue;
        }
        uni.clear();
        for (size_t i : glines[g])
            uni.insert(uni.end(), vids(i), vids(i) + vlen(i));
        std::sort(uni.begin(), uni.end());
        uni.erase(std::unique(uni.begin(), uni.end()), uni.end());
        bool ok = true, rounding_bad = false;
        if (uni.size() != cn || !std::equal(uni.begin(), uni.end(), cid)) {
            diff->membership++;
            ok = false;
            out("membership\t" + where + "\tcgal=" + ids_text(cid, cn) +
                "\tvorball=" + ids_text(uni.data(), uni.size()));
        }
        if (glines[g].size() > 1 && !(flags & VB_CGAL_ALLOW_SPLIT)) {
            diff->split++;
            ok = false;
            std::string ls;
            for (size_t i : glines[g])
                ls += (ls.empty() ? "" : ",") + std::to_string(line_of(i));
            out("split\t" + ids_text(cid, cn) + "\t" + where + "\tlines=" + ls);
        }
        if (check_rounding) {
            for (size_t i : glines[g]) {
                const char *names[4] = {"x", "y", "z", "t"};
                double mine[4] = {v->x[i], v->y[i], v->z[i], v->t[i]};
                double exact[4] = {d->x[k], d->y[k], d->z[k], d->t[k]};
                for (int f = 0; f < 4; f++)
                    if (mine[f] != exact[f]) {
                        if (!rounding_bad)
                            diff->rounding++;
                        rounding_bad = true;
                        ok = false;
                        out(std::string("rounding\t") + ids_text(cid, cn) + "\t" + names[f] +
                            "\tvorball=" + num(mine[f]) + "\texact=" + num(exact[f]) +
                            "\tline " + std::to_string(line_of(i)));
                    }
            }
        }
        if (ok)
            diff->matched++;
    }
    for (size_t g = 0; g < ng; g++) {
        if (match_of_group[g] != SIZE_MAX)
            continue;
        diff->extra++;
        for (size_t i : glines[g])
            out("extra\t" + ids_text(vids(i), vlen(i)) + "\t" + num(v->x[i]) + "\t" +
                num(v->y[i]) + "\t" + num(v->z[i]) + "\tline " + std::to_string(line_of(i)));
    }
    for (size_t i = 0; i < nv; i++)
        if (why[i]) {
            diff->invalid++;
            out("invalid\t" + ids_text(vids(i), vlen(i)) + "\t" + why[i] + "\tline " +
                std::to_string(line_of(i)));
        }
    return VB_OK;
}

} // namespace

extern "C" {

int vb_cgal_compare(vb_ctx *ctx, const vb_cgal_diagram *d, const vb_sphere_set *set,
                    const vb_vertex_list *theirs, const long *lines, unsigned flags,
                    FILE *report, vb_cgal_diff *diff)
{
    return guarded(ctx, "crosscheck", [&] {
        return compare(ctx, d, set, theirs, lines, flags, report, diff);
    });
}

int vb_cgal_identical(const vb_cgal_diff *diff)
{
    return !(diff->missing || diff->extra || diff->membership || diff->rounding || diff->split ||
             diff->invalid);
}

} // extern "C"

