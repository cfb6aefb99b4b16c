// The CGAL cross-check: CGAL's exact Voronoi (or power) vertices of the
// centres, and an exact comparison with vorball's vertex lists.
//
// Two independent exact computations meet here. CGAL's side: a
// Delaunay_triangulation_3 (Regular_triangulation_3 for --power) over the
// exact-constructions kernel Epeck, built from the input decimals as GMP
// rationals; a vertex is the exact circumcentre of a finite cell, and cells
// whose circumspheres coincide (decided by CGAL's exact in-sphere predicate on
// the facet between them) are one vertex. vorball's side: each line's ids
// alone, from which the point is re-derived in GMP integers without CGAL.
// Nothing crosses the extern "C" boundary as an exception.
#include "vb_cgal.h"
#include "vb_diag.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <CGAL/version_macros.h>
#include <gmp.h>
#include <mpfr.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <memory>
#include <new>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace {

typedef CGAL::Epeck K;
typedef K::FT FT;
typedef K::Exact_kernel::FT ET;

typedef CGAL::Triangulation_vertex_base_with_info_3<uint32_t, K> DVb;
typedef CGAL::Delaunay_triangulation_cell_base_3<K> DCb0;
typedef CGAL::Triangulation_cell_base_with_info_3<size_t, K, DCb0> DCb;
typedef CGAL::Delaunay_triangulation_3<K, CGAL::Triangulation_data_structure_3<DVb, DCb>> DT;

typedef CGAL::Regular_triangulation_vertex_base_3<K> RVb0;
typedef CGAL::Triangulation_vertex_base_with_info_3<uint32_t, K, RVb0> RVb;
typedef CGAL::Regular_triangulation_cell_base_3<K> RCb0;
typedef CGAL::Triangulation_cell_base_with_info_3<size_t, K, RCb0> RCb;
typedef CGAL::Regular_triangulation_3<K, CGAL::Triangulation_data_structure_3<RVb, RCb>> RT;

// Epeck's exact number type depends on how CGAL was configured (Debian's
// 5.5 picks Boost's gmp_rational); these are the GMP-backed ones, each unused
// in the other configuration. Any other type fails to compile here, loudly.
#ifdef CGAL_USE_BOOST_MP
[[maybe_unused]] void et_to_mpq(mpq_ptr out, const boost::multiprecision::mpq_rational &e)
{
    mpq_set(out, e.backend().data());
}
[[maybe_unused]] void mpq_to_et(boost::multiprecision::mpq_rational &e, mpq_srcptr q)
{
    mpq_set(e.backend().data(), q);
}
#endif
[[maybe_unused]] void et_to_mpq(mpq_ptr out, const CGAL::Gmpq &e)
{
    mpq_set(out, e.mpq());
}
[[maybe_unused]] void mpq_to_et(CGAL::Gmpq &e, mpq_srcptr q)
{
    mpq_set(e.mpq(), q);
}

// Arrays of GMP numbers with a fixed size, cleared on destruction.
struct QVec {
    std::vector<__mpq_struct> v;
    explicit QVec(size_t n) : v(n)
    {
        for (auto &q : v)
            mpq_init(&q);
    }
    ~QVec()
    {
        for (auto &q : v)
            mpq_clear(&q);
    }
    QVec(const QVec &) = delete;
    QVec &operator=(const QVec &) = delete;
    mpq_ptr operator[](size_t i) { return &v[i]; }
    mpq_srcptr operator[](size_t i) const { return &v[i]; }
};

struct ZVec {
    std::vector<__mpz_struct> v;
    explicit ZVec(size_t n) : v(n)
    {
        for (auto &z : v)
            mpz_init(&z);
    }
    ~ZVec()
    {
        for (auto &z : v)
            mpz_clear(&z);
    }
    ZVec(const ZVec &) = delete;
    ZVec &operator=(const ZVec &) = delete;
    mpz_ptr operator[](size_t i) { return &v[i]; }
    mpz_srcptr operator[](size_t i) const { return &v[i]; }
};

struct MpfrVar {
    mpfr_t f;
    explicit MpfrVar(mpfr_prec_t p) { mpfr_init2(f, p); }
    ~MpfrVar() { mpfr_clear(f); }
    MpfrVar(const MpfrVar &) = delete;
    MpfrVar &operator=(const MpfrVar &) = delete;
};

// mant * 10^exp10 as an integer scaled by 10^shift (shift >= -exp10).
void decimal_scaled(mpz_ptr out, vb_decimal d, int shift)
{
    uint64_t a = d.mant < 0 ? 0 - (uint64_t)d.mant : (uint64_t)d.mant;
    mpz_import(out, 1, 1, sizeof a, 0, 0, &a);
    if (d.mant < 0)
        mpz_neg(out, out);
    long e = (long)d.exp10 + shift;
    if (e > 0) {
        mpz_t p;
        mpz_init(p);
        mpz_ui_pow_ui(p, 10, (unsigned long)e);
        mpz_mul(out, out, p);
        mpz_clear(p);
    }
}

void decimal_to_mpq(mpq_ptr out, vb_decimal d)
{
    int shift = d.exp10 < 0 ? -d.exp10 : 0;
    decimal_scaled(mpq_numref(out), d, shift);
    mpz_ui_pow_ui(mpq_denref(out), 10, (unsigned long)shift);
    mpq_canonicalize(out);
}

double round_q(mpq_srcptr q)
{
    MpfrVar r(53);
    mpfr_set_q(r.f, q, MPFR_RNDN);
    return mpfr_get_d(r.f, MPFR_RNDN);
}

// t = sqrt(d2) - R rounded to nearest. Written as (d2 - R^2) / (sqrt(d2) + R)
// so no digits cancel when the spheres nearly touch: the numerator is exact,
// the denominator a sum of positives. When d2 is the square of a rational
// the value is rational and rounded once, exactly; otherwise it is
// irrational and 512 bits put it safely away from any rounding boundary.
double tangent_radius(mpq_srcptr d2, mpq_srcptr R)
{
    mpq_t e;
    mpq_init(e);
    mpq_mul(e, R, R);
    mpq_sub(e, d2, e);
    double t;
    if (mpq_sgn(e) == 0) {
        t = 0.0;
    } else if (mpz_perfect_square_p(mpq_numref(d2)) && mpz_perfect_square_p(mpq_denref(d2))) {
        mpq_t s;
        mpq_init(s);
        mpz_sqrt(mpq_numref(s), mpq_numref(d2));
        mpz_sqrt(mpq_denref(s), mpq_denref(d2));
        mpq_sub(s, s, R);
        t = round_q(s);
        mpq_clear(s);
    } else {
        MpfrVar s(512), num(512);
        mpfr_set_q(s.f, d2, MPFR_RNDN);
        mpfr_sqrt(s.f, s.f, MPFR_RNDN);
        mpfr_add_q(s.f, s.f, R, MPFR_RNDN);
        mpfr_set_q(num.f, e, MPFR_RNDN);
        mpfr_div(num.f, num.f, s.f, MPFR_RNDN);
        t = mpfr_get_d(num.f, MPFR_RNDN);
    }
    mpq_clear(e);
    return t;
}

int cmp_point(mpq_srcptr a, mpq_srcptr b)
{
    for (int k = 0; k < 3; k++) {
        int c = mpq_cmp(a + k, b + k);
        if (c)
            return c;
    }
    return 0;
}

// Union-find over finite cells.
size_t find_root(std::vector<size_t> &parent, size_t i)
{
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

CGAL::Bounded_side cell_side(const DT &tr, DT::Cell_handle c, const DT::Point &p)
{
    return tr.side_of_sphere(c, p);
}

CGAL::Bounded_side cell_side(const RT &tr, RT::Cell_handle c, const RT::Weighted_point &p)
{
    return tr.side_of_power_sphere(c, p);
}

std::string ids_text(const uint32_t *ids, size_t n)
{
    std::string s;
    for (size_t i = 0; i < n; i++) {
        if (i)
            s += ',';
        s += std::to_string(ids[i]);
    }
    return s;
}

} // namespace

struct vb_cgal_diagram {
    int mode = VB_CGAL_VORONOI;
    bool equal_radii = true;
    size_t nspheres = 0;
    std::vector<size_t> start{0};   // CSR, canonical order (sorted by ids)
    std::vector<uint32_t> ids;
    std::vector<__mpq_struct> xyz;  // 3 per vertex, exact
    std::vector<double> x, y, z, t; // rounded to nearest
    vb_cgal_diagram() = default;
    vb_cgal_diagram(const vb_cgal_diagram &) = delete;
    vb_cgal_diagram &operator=(const vb_cgal_diagram &) = delete;
    ~vb_cgal_diagram()
    {
        for (auto &q : xyz)
            mpq_clear(&q);
    }
};

namespace {

// Groups the finite cells of `tr` by circumsphere and stores one vertex per
// group in `d`, canonical order. Two cells across a facet share their
// circumsphere exactly when the far vertex of one lies on the other's sphere;
// all cells of one sphere triangulate the polytope it circumscribes, so they
// are connected through such facets.
template <class Tr>
void collect_vertices(const Tr &tr, const QVec &cx, const QVec &cr, vb_cgal_diagram &d)
{
    std::vector<typename Tr::Cell_handle> cells;
    for (auto c : tr.finite_cell_handles()) {
        c->info() = cells.size();
        cells.push_back(c);
    }
    std::vector<size_t> parent(cells.size());
    std::iota(parent.begin(), parent.end(), 0);
    for (auto c : cells) {
        for (int i = 0; i < 4; i++) {
            auto nb = c->neighbor(i);
            if (tr.is_infinite(nb) || nb->info() < c->info())
                continue;
            const auto &far = nb->vertex(nb->index(c))->point();
            if (cell_side(tr, c, far) == CGAL::ON_BOUNDARY) {
                size_t a = find_root(parent, c->info()), b = find_root(parent, nb->info());
                if (a != b)
                    parent[std::max(a, b)] = std::min(a, b);
            }
        }
    }
    // Members of each group: the union of its cells' vertices.
    std::vector<std::vector<uint32_t>> members(cells.size());
    std::vector<size_t> groups;
    for (size_t i = 0; i < cells.size(); i++) {
        size_t r = find_root(parent, i);
        if (r == i)
            groups.push_back(i);
        for (int k = 0; k < 4; k++)
            members[r].push_back(cells[i]->vertex(k)->info());
    }
    for (size_t g : groups) {
        auto &m = members[g];
        std::sort(m.begin(), m.end());
        m.erase(std::unique(m.begin(), m.end()), m.end());
    }
    std::sort(groups.begin(), groups.end(),
              [&](size_t a, size_t b) { return members[a] < members[b]; });

    size_t nv = groups.size();
    d.xyz.resize(3 * nv);
    for (auto &q : d.xyz)
        mpq_init(&q);
    d.x.resize(nv);
    d.y.resize(nv);
    d.z.resize(nv);
    d.t.resize(nv);
    QVec tmp(2);
    mpq_ptr d2 = tmp[0], diff = tmp[1];
    for (size_t k = 0; k < nv; k++) {
        size_t g = groups[k];
        const auto &m = members[g];
        d.ids.insert(d.ids.end(), m.begin(), m.end());
        d.start.push_back(d.ids.size());
        // exact() refers into the lazy point, which must outlive ep.
        const auto centre = tr.dual(cells[g]);
        const auto &ep = CGAL::exact(centre);
        mpq_ptr p = &d.xyz[3 * k];
        et_to_mpq(p + 0, ep.x());
        et_to_mpq(p + 1, ep.y());
        et_to_mpq(p + 2, ep.z());
        d.x[k] = round_q(p + 0);
        d.y[k] = round_q(p + 1);
        d.z[k] = round_q(p + 2);
        mpq_set_ui(d2, 0, 1);
        for (int c = 0; c < 3; c++) {
            mpq_sub(diff, p + c, cx[3 * (size_t)m[0] + c]);
            mpq_mul(diff, diff, diff);
            mpq_add(d2, d2, diff);
        }
        d.t[k] = tangent_radius(d2, cr[m[0]]);
    }
}

int build(vb_ctx *ctx, const vb_sphere_set *set, int mode, vb_cgal_diagram **out)
{
    size_t n = set->n;
    if (n == 0)
        return vb_error(ctx, VB_EINPUT_EMPTY, set->source, 0, "no spheres to cross-check");
    if (mode != VB_CGAL_VORONOI && mode != VB_CGAL_POWER)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "vb_cgal_build: unknown mode %d", mode);
    QVec cx(3 * n), cr(n);
    for (size_t i = 0; i < n; i++) {
        decimal_to_mpq(cx[3 * i + 0], set->ex[i]);
        decimal_to_mpq(cx[3 * i + 1], set->ey[i]);
        decimal_to_mpq(cx[3 * i + 2], set->ez[i]);
        decimal_to_mpq(cr[i], set->er[i]);
    }
    bool equal = true;
    size_t differ = 0;
    for (size_t i = 1; i < n && equal; i++)
        if (!mpq_equal(cr[i], cr[0])) {
            equal = false;
            differ = i;
        }
    if (!equal && mode == VB_CGAL_VORONOI)
        return vb_error(ctx, VB_EINPUT, set->source, set->line ? set->line[differ] : 0,
                        "radii differ (%.17g on line %ld, %.17g here): the CGAL cross-check "
                        "needs equal radii, where the Voronoi diagram of spheres is that of "
                        "the centres; --power compares the power diagram instead",
                        set->r[0], set->line ? set->line[0] : 1L, set->r[differ]);
    ET e;
    auto ft = [&](mpq_srcptr q) {
        mpq_to_et(e, q);
        return FT(e);
    };

    std::unique_ptr<vb_cgal_diagram> d(new vb_cgal_diagram);
    d->mode = mode;
    d->equal_radii = equal;
    d->nspheres = n;
    int dimension;
    size_t kept;
    if (mode == VB_CGAL_VORONOI) {
        std::vector<std::pair<DT::Point, uint32_t>> pts;
        pts.reserve(n);
        for (size_t i = 0; i < n; i++)
            pts.emplace_back(DT::Point(ft(cx[3 * i]), ft(cx[3 * i + 1]), ft(cx[3 * i + 2])),
                             (uint32_t)i);
        DT tr(pts.begin(), pts.end());
        dimension = tr.dimension();
        kept = tr.number_of_vertices();
        if (kept != n)
            return vb_error(ctx, VB_EINPUT_DUPLICATE, set->source, 0,
                            "%zu centres coincide with others (equal radii): identical "
                            "spheres should have been refused",
                            n - kept);
        if (dimension == 3)
            collect_vertices(tr, cx, cr, *d);
    } else {
        std::vector<std::pair<RT::Weighted_point, uint32_t>> pts;
        pts.reserve(n);
        QVec w(1);
        for (size_t i = 0; i < n; i++) {
            mpq_mul(w[0], cr[i], cr[i]);
            RT::Bare_point p(ft(cx[3 * i]), ft(cx[3 * i + 1]), ft(cx[3 * i + 2]));
            pts.emplace_back(RT::Weighted_point(p, ft(w[0])), (uint32_t)i);
        }
        RT tr(pts.begin(), pts.end());
        dimension = tr.dimension();
        kept = tr.number_of_vertices();
        if (kept != n)
            vb_warn(ctx, VB_W_CROSSCHECK_HIDDEN, set->source, 0,
                    "%zu of %zu spheres own no power cell (hidden by larger neighbours); "
                    "they are in no power vertex",
                    n - kept, n);
        if (dimension == 3)
            collect_vertices(tr, cx, cr, *d);
    }
    if (dimension < 3)
        vb_warn(ctx, VB_W_CROSSCHECK_FLAT, set->source, 0,
                "the centres span only %dD: the diagram has no vertices", dimension);
    *out = d.release();
    return VB_OK;
}

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

// Maps any exception to a status with a message.
template <class F>
int guarded(vb_ctx *ctx, const char *what, F &&f)
{
    try {
        return f();
    } catch (const std::bad_alloc &) {
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "%s: out of memory", what);
    } catch (const std::exception &e) {
        return vb_error(ctx, VB_EINTERNAL, NULL, 0, "%s: CGAL failed: %s", what, e.what());
    } catch (...) {
        return vb_error(ctx, VB_EINTERNAL, NULL, 0, "%s: unknown C++ exception", what);
    }
}

} // namespace

extern "C" {

const char *vb_cgal_version(void)
{
    return CGAL_VERSION_STR;
}

int vb_cgal_build(vb_ctx *ctx, const vb_sphere_set *set, int mode, vb_cgal_diagram **out)
{
    *out = NULL;
    return guarded(ctx, "CGAL triangulation", [&] { return build(ctx, set, mode, out); });
}

void vb_cgal_free(vb_cgal_diagram *d)
{
    delete d;
}

size_t vb_cgal_size(const vb_cgal_diagram *d)
{
    return d->start.size() - 1;
}

int vb_cgal_to_list(vb_ctx *ctx, const vb_cgal_diagram *d, vb_vertex_list *out)
{
    for (size_t k = 0; k + 1 < d->start.size(); k++) {
        int rc = vb_vertex_list_push(out, &d->ids[d->start[k]], d->start[k + 1] - d->start[k],
                                     d->x[k], d->y[k], d->z[k], d->t[k], 0.0,
                                     VB_VERTEX_CERTIFIED);
        if (rc)
            return vb_error(ctx, rc, NULL, 0, "out of memory listing CGAL's vertices");
    }
    return VB_OK;
}

int vb_cgal_exact_point(vb_ctx *ctx, const vb_cgal_diagram *d, size_t k, char **x, char **y,
                        char **z)
{
    *x = *y = *z = NULL;
    if (k + 1 >= d->start.size())
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "vb_cgal_exact_point: no vertex %zu", k);
    char **dst[3] = {x, y, z};
    for (int c = 0; c < 3; c++) {
        mpq_srcptr q = &d->xyz[3 * k + c];
        size_t len = mpz_sizeinbase(mpq_numref(q), 10) + mpz_sizeinbase(mpq_denref(q), 10) + 3;
        *dst[c] = (char *)malloc(len);
        if (!*dst[c]) {
            for (int b = 0; b < c; b++) {
                free(*dst[b]);
                *dst[b] = NULL;
            }
            return vb_error(ctx, VB_ENOMEM, NULL, 0, "out of memory printing a rational");
        }
        mpq_get_str(*dst[c], 10, q);
    }
    return VB_OK;
}

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
