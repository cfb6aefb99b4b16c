// The CGAL cross-check: CGAL's exact Voronoi (or power) vertices of the
// centres (the exact comparison with vorball's vertex lists:
// cgal_compare.cpp).
//
// Two independent exact computations meet here. CGAL's side: a
// Delaunay_triangulation_3 (Regular_triangulation_3 for --power) over the
// exact-constructions kernel Epeck, built from the input decimals as GMP
// rationals; a vertex is the exact circumcentre of a finite cell, and cells
// whose circumspheres coincide (decided by CGAL's exact in-sphere predicate on
// the facet between them) are one vertex. vorball's side: each line's ids
// alone, from which the point is re-derived in GMP integers without CGAL.
// Nothing crosses the extern "C" boundary as an exception.
#include "vb_uf.h"
#include "vbx_cgal.hpp"

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

using namespace vbx_cgal;

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

// The union-find of the library (vb_uf.h) over finite cells, freed on
// every way out.
struct CellSets {
    vb_uf u = {};
    explicit CellSets(size_t n)
    {
        if (vb_uf_fit(&u, n) != VB_OK)
            throw std::bad_alloc();
    }
    ~CellSets() { vb_uf_free(&u); }
    CellSets(const CellSets &) = delete;
    CellSets &operator=(const CellSets &) = delete;
};

CGAL::Bounded_side cell_side(const DT &tr, DT::Cell_handle c, const DT::Point &p)
{
    return tr.side_of_sphere(c, p);
}

CGAL::Bounded_side cell_side(const RT &tr, RT::Cell_handle c, const RT::Weighted_point &p)
{
    return tr.side_of_power_sphere(c, p);
}

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
    CellSets sets(cells.size());
    for (auto c : cells) {
        for (int i = 0; i < 4; i++) {
            auto nb = c->neighbor(i);
            if (tr.is_infinite(nb) || nb->info() < c->info())
                continue;
            const auto &far = nb->vertex(nb->index(c))->point();
            if (cell_side(tr, c, far) == CGAL::ON_BOUNDARY) {
                vb_uf_join(&sets.u, (uint32_t)c->info(), (uint32_t)nb->info());
            }
        }
    }
    // Members of each group: the union of its cells' vertices.
    std::vector<std::vector<uint32_t>> members(cells.size());
    std::vector<size_t> groups;
    for (size_t i = 0; i < cells.size(); i++) {
        size_t r = vb_uf_root(&sets.u, (uint32_t)i);
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

} // extern "C"
