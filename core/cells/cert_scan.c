/* The host twin's judge of one quadruple (vb_cert_filter.h,
 * vb_cert_judge_pick): vbd_judge (vbd_cert_shared.h) with each root's
 * emptiness scan over the twin's exact doubles f->cell_d instead of the
 * 64-bit rows: the same cells, spheres and per-sphere test
 * (vbd_fast_test), so the same verdict. Compiled a second time for AVX2
 * (cert_scan_avx2.c, x86-64 only; CMake adds -mavx2 to that file alone,
 * which also gives the interval steps VEX code), where four spheres of a
 * row are tested at once: each lane runs vbd_fast_test's operations in
 * its order (no FMA: -mfma is not given and contraction is off), so a
 * lane's "outside" is the scalar test's, and every other lane (a member,
 * an intruder, a sphere it cannot place) is tested again by vbd_fast_test
 * itself. The AVX2 build also takes the lines of four quadruples at once
 * (vb_cert_judge_run_avx2: cert_line4.h's lanes, each vbd_line_end's
 * steps bit for bit). */
/* The interval steps with both bounds in one register (vb_ia_pairs.h): the
 * same bits, fewer instructions. */
#define VB_IA_HOST_PAIRS 1
#include "vb_cert_filter.h"

#if VB_CERT_SCAN_WIDE
#include <immintrin.h>
#include "cert_line4.h"
#define VB_CERT_JUDGE_FN vb_cert_judge_one_avx2
#else
#define VB_CERT_JUDGE_FN vb_cert_judge_one
#endif

/* Sphere u (cell order) of the scan by vbd_fast_test: 1 when it is proven
 * inside (VBD_NOT), else 0 with *open set when it cannot be placed; the
 * members of q are skipped, as vbd_root skips them. */
static int test_one(const vb_cert_filter *f, const uint32_t *q, const vbd_box *b,
                    const double *a, uint32_t u, int *open)
{
    uint32_t j = f->cell_ids[u];
    if (j == q[0] || j == q[1] || j == q[2] || j == q[3])
        return 0;
    size_t n = f->n;
    const double *X = f->cell_d;
    int fast = vbd_fast_test(b->p, b->s, X[u] - a[0], X[n + u] - a[1], X[2 * n + u] - a[2],
                             X[3 * n + u] - a[3]);
    if (fast == VBD_FAST_IN)
        return 1;
    if (fast == VBD_FAST_OPEN)
        *open = 1;
    return 0;
}

#if VB_CERT_SCAN_WIDE
/* A root's values in four lanes each (set once per root, not per row). */
typedef struct lanes {
    __m256d plo[3], phi[3], shi, a[4];
    __m128i q[4];
} lanes;

static void lanes_set(lanes *w, const uint32_t *q, const vbd_box *b, const double *a)
{
    for (int k = 0; k < 4; k++)
        w->q[k] = _mm_set1_epi32((int)q[k]);
    for (int k = 0; k < 3; k++) {
        w->plo[k] = _mm256_set1_pd(b->p[k].lo);
        w->phi[k] = _mm256_set1_pd(b->p[k].hi);
    }
    w->shi = _mm256_set1_pd(b->s.hi);
    for (int k = 0; k < 4; k++)
        w->a[k] = _mm256_set1_pd(a[k]);
}
#else
typedef struct lanes {
    int unused;
} lanes;
#endif

/* The spheres [j0, j1) of one row (a the base's row as doubles, w the
 * root's lanes): VBD_NOT when one is proven inside (the scan ends), else
 * VBD_OPEN, with *open set when one cannot be placed. */
static inline uint32_t scan_row(const vb_cert_filter *f, const uint32_t *q, const vbd_box *b,
                                const double *a, const lanes *w, uint32_t j0, uint32_t j1,
                                int *open)
{
#if VB_CERT_SCAN_WIDE
    size_t n = f->n;
    const double *X = f->cell_d, *Y = X + n, *Z = Y + n, *R = Z + n;
    const __m256d zero = _mm256_setzero_pd(), grow = _mm256_set1_pd(1.0 + 0x1p-46);
    const __m256d tiny = _mm256_set1_pd(0x1p-1000), lane = _mm256_set_pd(3.0, 2.0, 1.0, 0.0);
    /* vbd_fast_test's "outside" in four lanes, its operations in its order
     * (max_pd(x, y) is x > y ? x : y, vb_fmax exactly). Lanes past j1 read
     * the next spheres or the padding of cell_d and cell_ids (4 more each)
     * and are masked off. */
    for (uint32_t t = j0; t < j1; t += 4) {
        __m256d d0 = _mm256_sub_pd(_mm256_loadu_pd(X + t), w->a[0]);
        __m256d d1 = _mm256_sub_pd(_mm256_loadu_pd(Y + t), w->a[1]);
        __m256d d2 = _mm256_sub_pd(_mm256_loadu_pd(Z + t), w->a[2]);
        __m256d wh = _mm256_add_pd(w->shi, _mm256_sub_pd(_mm256_loadu_pd(R + t), w->a[3]));
        __m256d l0 = _mm256_max_pd(_mm256_sub_pd(w->plo[0], d0), _mm256_sub_pd(d0, w->phi[0]));
        __m256d l1 = _mm256_max_pd(_mm256_sub_pd(w->plo[1], d1), _mm256_sub_pd(d1, w->phi[1]));
        __m256d l2 = _mm256_max_pd(_mm256_sub_pd(w->plo[2], d2), _mm256_sub_pd(d2, w->phi[2]));
        l0 = _mm256_max_pd(l0, zero);
        l1 = _mm256_max_pd(l1, zero);
        l2 = _mm256_max_pd(l2, zero);
        __m256d qq = _mm256_add_pd(zero, _mm256_mul_pd(l0, l0));
        qq = _mm256_add_pd(qq, _mm256_mul_pd(l1, l1));
        qq = _mm256_add_pd(qq, _mm256_mul_pd(l2, l2));
        __m256d thr = _mm256_add_pd(_mm256_mul_pd(_mm256_mul_pd(wh, wh), grow), tiny);
        __m256d out = _mm256_or_pd(_mm256_cmp_pd(wh, zero, _CMP_LT_OQ),
                                   _mm256_cmp_pd(qq, thr, _CMP_GT_OQ));
        __m256d live = _mm256_cmp_pd(lane, _mm256_set1_pd((double)(j1 - t)), _CMP_LT_OQ);
        unsigned left = (unsigned)_mm256_movemask_pd(_mm256_andnot_pd(out, live));
        /* The members (test_one skips them too) are most lanes left: off
         * here, the branch below is rarely taken. */
        __m128i id = _mm_loadu_si128((const __m128i *)(f->cell_ids + t));
        __m128i mem = _mm_or_si128(_mm_or_si128(_mm_cmpeq_epi32(id, w->q[0]), _mm_cmpeq_epi32(id, w->q[1])),
                                   _mm_or_si128(_mm_cmpeq_epi32(id, w->q[2]), _mm_cmpeq_epi32(id, w->q[3])));
        left &= ~(unsigned)_mm_movemask_ps(_mm_castsi128_ps(mem));
        for (; left; left &= left - 1)
            if (test_one(f, q, b, a, t + (uint32_t)__builtin_ctz(left), open))
                return VBD_NOT;
    }
#else
    (void)w;
    for (uint32_t t = j0; t < j1; t++)
        if (test_one(f, q, b, a, t, open))
            return VBD_NOT;
#endif
    return VBD_OPEN;
}

/* The indices c0 .. c1 in vbd_around's order from m (the centre's first):
 * n of them into out. */
static uint32_t around(uint32_t c0, uint32_t c1, uint32_t m, uint32_t *out)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < 2u * (c1 - c0) + 1u; i++) {
        int64_t c = vbd_around(c0, c1, m, i);
        if (c >= 0)
            out[n++] = (uint32_t)c;
    }
    return n;
}

/* vbd_root's scan of box b (VBD_SCAN) over f->cell_d: its slabs and rows
 * in its order, each row's list made once. */
static uint32_t scan_root(const vb_cert_filter *f, const uint32_t *q, const vbd_box *b)
{
    const int64_t *za = f->z + 4 * (size_t)q[0];
    double a[4];
    for (int k = 0; k < 4; k++)
        a[k] = (double)za[k];
    lanes w;
#if VB_CERT_SCAN_WIDE
    lanes_set(&w, q, b, a);
#endif
    const vbd_grid *g = &f->g;
    /* At most VBD_MAX_CELLS cells: no axis has more. */
    uint32_t zs[VBD_MAX_CELLS], ys[VBD_MAX_CELLS];
    uint32_t nz = around(b->c0[2], b->c1[2], b->mz, zs);
    uint32_t ny = around(b->c0[1], b->c1[1], b->my, ys);
    int open = b->open;
    for (uint32_t iz = 0; iz < nz; iz++)
        for (uint32_t iy = 0; iy < ny; iy++) {
            uint64_t row = ((uint64_t)zs[iz] * g->ny + ys[iy]) * g->nx;
            uint32_t j0 = f->cell_start[row + b->c0[0]];
            uint32_t j1 = f->cell_start[row + b->c1[0] + 1u];
            if (scan_row(f, q, b, a, &w, j0, j1, &open) == VBD_NOT)
                return VBD_NOT;
        }
    return open ? VBD_OPEN : VBD_VERTEX;
}

/* The verdicts of q's roots from its line L (k: vbd_line_make's result). */
static uint32_t judge_roots(const vb_cert_filter *f, const uint32_t *q, const vbd_line *L, int k)
{
    if (k < 0)
        return VBD_NOT | (VBD_NOT << 2);
    if (k == 0)
        return VBD_OPEN;
    /* Both boxes before either scan: their interval steps, independent,
     * overlap in the CPU. */
    vbd_box b[2];
    uint32_t v[2];
    for (int r = 0; r < 2; r++)
        v[r] = vbd_root_box(f->z, &f->g, q[0], L, r, &b[r]);
    for (int r = 0; r < 2; r++)
        if (v[r] == VBD_SCAN)
            v[r] = scan_root(f, q, &b[r]);
    return v[0] | (v[1] << 2);
}

uint32_t VB_CERT_JUDGE_FN(const vb_cert_filter *f, const uint32_t *q)
{
    if (!f->cell_d)
        return vbd_judge(f->z, f->cell_start, f->cell_ids, f->cell_z, &f->g, q[0], q[1], q[2],
                         q[3]);
    vbd_line L;
    return judge_roots(f, q, &L, vbd_line_make(f->z, q[0], q[1], q[2], q[3], &L));
}

#if VB_CERT_SCAN_WIDE
unsigned vb_cert_lines_four_avx2(const vb_cert_filter *f, const uint32_t (*q)[4], vbd_line *L,
                                 int *k)
{
    vb_ia e[4][15], M[4][25], delta[4];
    const vb_ia *ep[4], *Mp[4];
    vbd_line *Lp[4];
    int live[4];
    for (int l = 0; l < 4; l++) {
        live[l] = vbd_line_begin(f->z, q[l][0], q[l][1], q[l][2], q[l][3], &L[l], e[l], M[l]);
        ep[l] = e[l];
        Mp[l] = M[l];
        Lp[l] = &L[l];
        if (!live[l]) {
            /* A lane of defined values (its results are not used). */
            L[l].D = L[l].v[0] = L[l].v[1] = L[l].v[2] = vb_ia_point(1.0);
            for (int i = 0; i < 15; i++)
                e[l][i] = vb_ia_point(1.0);
            for (int i = 0; i < 25; i++)
                M[l][i] = vb_ia_point(1.0);
        }
    }
    unsigned bad = line4_end(ep, Mp, Lp, delta), scalar = 0;
    for (int l = 0; l < 4; l++) {
        k[l] = 0;
        if (live[l] && (bad >> l & 1u)) {
            k[l] = vbd_line_end(e[l], M[l], &L[l]);
            scalar |= 1u << l;
        } else if (live[l] && vb_ia_sign(L[l].A))
            k[l] = vbd_line_roots(&L[l], delta[l]);
    }
    return scalar;
}

/* Four quadruples q[0..3] into out[0..3]: their lines four at once. */
static void judge_four(const vb_cert_filter *f, const uint32_t (*q)[4], uint8_t *out)
{
    vbd_line L[4];
    int k[4];
    vb_cert_lines_four_avx2(f, q, L, k);
    for (int l = 0; l < 4; l++)
        out[l] = (uint8_t)judge_roots(f, q[l], &L[l], k[l]);
}

void vb_cert_judge_run_avx2(const vb_cert_filter *f, const uint32_t (*q)[4], size_t n,
                            uint8_t *out)
{
    size_t k = 0;
    for (; f->cell_d && k + 4 <= n; k += 4)
        judge_four(f, q + k, out + k);
    for (; k < n; k++)
        out[k] = (uint8_t)vb_cert_judge_one_avx2(f, q[k]);
}
#endif

#if !VB_CERT_SCAN_WIDE
void vb_cert_judge_run(const vb_cert_filter *f, const uint32_t (*q)[4], size_t n, uint8_t *out)
{
    for (size_t k = 0; k < n; k++)
        out[k] = (uint8_t)vb_cert_judge_one(f, q[k]);
}

/* The AVX2 build's function f where the build and the CPU have AVX2, else
 * the portable p (NULL: none). */
#if defined(VB_CERT_SCAN_HAVE_AVX2) && defined(__GNUC__) && defined(__x86_64__)
#define WIDE_OR(f, p) (__builtin_cpu_supports("avx2") ? (f) : (p))
#else
#define WIDE_OR(f, p) (p)
#endif

vb_cert_judge_fn vb_cert_judge_pick(void)
{
    return WIDE_OR(vb_cert_judge_one_avx2, vb_cert_judge_one);
}

vb_cert_judge_run_fn vb_cert_judge_run_pick(void)
{
    return WIDE_OR(vb_cert_judge_run_avx2, vb_cert_judge_run);
}

vb_cert_lines_fn vb_cert_lines_pick(void)
{
    return WIDE_OR(vb_cert_lines_four_avx2, NULL);
}
#endif
