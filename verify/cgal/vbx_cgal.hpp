// Internals shared by the two halves of the CGAL bridge (cgal_bridge.cpp:
// CGAL's vertices; cgal_compare.cpp: the exact comparison with a vertex
// list): GMP arrays, the input decimals as integers, the diagram's
// storage and the exception guard of the extern "C" calls. No CGAL here.
#ifndef VBX_CGAL_HPP
#define VBX_CGAL_HPP

#include "vb_cgal.h"
#include "vb_diag.h"

#include <gmp.h>
#include <mpfr.h>

#include <exception>
#include <new>
#include <string>
#include <vector>

namespace vbx_cgal {

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
inline void decimal_scaled(mpz_ptr out, vb_decimal d, int shift)
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

inline int cmp_point(mpq_srcptr a, mpq_srcptr b)
{
    for (int k = 0; k < 3; k++) {
        int c = mpq_cmp(a + k, b + k);
        if (c)
            return c;
    }
    return 0;
}

inline std::string ids_text(const uint32_t *ids, size_t n)
{
    std::string s;
    for (size_t i = 0; i < n; i++) {
        if (i)
            s += ',';
        s += std::to_string(ids[i]);
    }
    return s;
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

} // namespace vbx_cgal

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

#endif
