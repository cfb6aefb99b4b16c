/* The tie cluster's rank test (vbq_cluster.h) proven "not a cluster" modulo
 * a prime, before GMP: a crystal jittered at 1e-12 has decimals of 15
 * digits, too long for the 128-bit path (cluster_small.c), and its
 * near-ties look flat in doubles but are not; each such list cost GMP's
 * elimination (a gcd per step) to find rank 5. On sc 4,096 jittered 1e-12
 * through PoCL: 14,109 lists, 534 M of the 4,843 M instructions of the
 * host's resume of the handed patches (callgrind,
 * papers/degenerate-input/results/res51_stop51.md).
 *
 * Why it is exact. The vectors V_j = (D_j, Delta_j, N_j) are integers (the
 * decimals scaled to 10^emin, as vbq_cluster_gmp makes them). Four of them
 * that are independent modulo p have a 4x4 minor that is not 0 modulo p,
 * so not 0 as an integer: they are independent over Q. So rank >= 4 modulo
 * p proves rank >= 4, and then vbq_cluster_gmp answers decided = 0 (it
 * stops there, or earlier at some N_j <= 0: decided = 0 too). A smaller
 * rank modulo p proves nothing (p may divide a minor): GMP answers as
 * before. p = 2^61 - 1: products of two residues fit 122 bits and reduce
 * with a shift and an add. */
#include <stdint.h>

#include "vbq_cluster.h"

typedef unsigned __int128 u128;

#define MODP (((uint64_t)1 << 61) - 1u)

/* a b mod p for a, b < p. */
static uint64_t mulm(uint64_t a, uint64_t b)
{
    u128 t = (u128)a * b;
    uint64_t r = (uint64_t)(t & MODP) + (uint64_t)(t >> 61); /* < 2^62 */
    return r >= MODP ? r - MODP : r;
}

static uint64_t addm(uint64_t a, uint64_t b)
{
    uint64_t r = a + b; /* < 2^62 */
    return r >= MODP ? r - MODP : r;
}

static uint64_t subm(uint64_t a, uint64_t b)
{
    return a >= b ? a - b : a + MODP - b;
}

/* d * 10^(d.exp10 - emin) mod p (emin <= d.exp10). */
static uint64_t scaled_modp(vb_decimal d, int32_t emin)
{
    int64_t m = d.mant % (int64_t)MODP;
    uint64_t r = (uint64_t)(m < 0 ? m + (int64_t)MODP : m), b = 10u;
    for (uint32_t k = (uint32_t)(d.exp10 - emin); k; k >>= 1) {
        if (k & 1u)
            r = mulm(r, b);
        b = mulm(b, b);
    }
    return r;
}

int vbq_cluster_modp(const vb_sphere_set *s, uint32_t i, const uint32_t *ids, uint32_t n,
                     int32_t emin)
{
    const vb_decimal *col[4] = {s->ex, s->ey, s->ez, s->er};
    uint64_t ci[4], row[4][5];
    int piv[4], nr = 0;
    for (int a = 0; a < 4; a++)
        ci[a] = scaled_modp(col[a][i], emin);
    for (uint32_t k = 0; k < n; k++) {
        uint64_t v[5];
        for (int a = 0; a < 4; a++)
            v[a] = subm(scaled_modp(col[a][ids[k]], emin), ci[a]);
        uint64_t d2 = addm(addm(mulm(v[0], v[0]), mulm(v[1], v[1])), mulm(v[2], v[2]));
        v[4] = subm(d2, mulm(v[3], v[3])); /* N_j = |D_j|^2 - Delta_j^2 */
        /* v <- row[p] v - v[p] row against each row: v[p] becomes 0 */
        for (int r = 0; r < nr; r++) {
            uint64_t vp = v[piv[r]], rp = row[r][piv[r]];
            if (!vp)
                continue;
            for (int c = 0; c < 5; c++)
                v[c] = subm(mulm(rp, v[c]), mulm(vp, row[r][c]));
        }
        int p = 0;
        while (p < 5 && !v[p])
            p++;
        if (p == 5)
            continue;
        for (int c = 0; c < 5; c++)
            row[nr][c] = v[c];
        piv[nr++] = p;
        if (nr == 4)
            return 1;
    }
    return 0;
}
