/* The xtc3d integer compression of XTC coordinates, decoding side.
 *
 * Each coordinate is an integer (the position times the frame's precision).
 * The packed data are one big-endian bit stream. An atom is either "large"
 * - its three integers, offset by minint, as one mixed-radix number of
 * ceil(log2(prod sizes)) bits (sizes = maxint - minint + 1), or as three
 * plain bit fields when a size exceeds 2^24 - or one of a run of "small"
 * atoms coded relative to the previous one in a radix of magicints[smallidx]
 * per axis. After each large atom a flag bit says whether a new run length
 * follows (5 bits: 3 * atoms + a change of smallidx of -1, 0 or +1); without
 * it the previous run length holds. In a run, the first small atom and the
 * large one come out swapped (the writer's trick for water: O first). */
#include "vb_xdr.h"

#include <string.h>

/* magicints[k] is about 2^(k/3): the radix of one axis of a small atom at
 * smallidx k, so three axes take k bits. The values are part of the format
 * (including its rounding quirks: 5060, 524287, 8388607). */
static const int32_t magicints[] = {
    0,       0,       0,       0,       0,        0,        0,        0,       0,       8,
    10,      12,      16,      20,      25,       32,       40,       50,      64,      80,
    101,     128,     161,     203,     256,      322,      406,      512,     645,     812,
    1024,    1290,    1625,    2048,    2580,     3250,     4096,     5060,    6501,    8192,
    10321,   13003,   16384,   20642,   26007,    32768,    41285,    52015,   65536,   82570,
    104031,  131072,  165140,  208063,  262144,   330280,   416127,   524287,  660561,  832255,
    1048576, 1321122, 1664510, 2097152, 2642245,  3329021,  4194304,  5284491, 6658042, 8388607,
    10568983, 13316085, 16777216,
};
#define XTC_FIRSTIDX 9
#define XTC_LASTIDX ((int32_t)(sizeof magicints / sizeof magicints[0]))

/* A big-endian bit stream. */
typedef struct {
    const unsigned char *p;
    size_t len, pos;
    uint64_t acc;
    int bits; /* unread bits at the bottom of acc */
} bit_reader;

/* The next n bits (0..32), most significant first; -1 past the end. */
static int get_bits(bit_reader *b, int n, uint32_t *out)
{
    while (b->bits < n) {
        if (b->pos >= b->len)
            return -1;
        b->acc = (b->acc << 8) | b->p[b->pos++];
        b->bits += 8;
    }
    b->bits -= n;
    *out = (uint32_t)((b->acc >> b->bits) & ((1ull << n) - 1u));
    return 0;
}

/* Bits needed for a value below `size`. */
static int bits_of(uint64_t size)
{
    int n = 0;
    while (n < 64 && (1ull << n) <= size)
        n++;
    return n;
}

/* Bits of the mixed-radix number of three values below sizes[k]. The
 * product is taken in bytes as the format defines it, so rounding cannot
 * differ from the writer's. */
static int bits_of_product(const uint32_t sizes[3])
{
    unsigned char bytes[16] = {1};
    int nbytes = 1;
    for (int i = 0; i < 3; i++) {
        uint64_t carry = 0;
        int k;
        for (k = 0; k < nbytes; k++) {
            carry += (uint64_t)bytes[k] * sizes[i];
            bytes[k] = (unsigned char)(carry & 0xff);
            carry >>= 8;
        }
        while (carry && k < 16) {
            bytes[k++] = (unsigned char)(carry & 0xff);
            carry >>= 8;
        }
        nbytes = k;
    }
    int top = nbytes - 1, n = 0;
    while (n < 8 && (1u << n) <= bytes[top])
        n++;
    return n + top * 8;
}

/* Three values below sizes[0..2] from one mixed-radix number of nbits bits:
 * its bytes arrive least significant first; dividing by sizes[2] then
 * sizes[1] leaves the remainders out[2], out[1] and the quotient out[0]. */
static int get_mixed(bit_reader *b, int nbits, const uint32_t sizes[3], uint32_t out[3])
{
    unsigned char bytes[16] = {0};
    int nbytes = 0;
    uint32_t v;
    if (nbits > 8 * 16)
        return -1;
    if (nbits <= 64) {
        /* The same number in one 64-bit word (every run of small atoms and
         * most large ones): two divisions instead of two per byte, the
         * same remainders and the quotient's low 32 bits as below. */
        uint64_t x = 0;
        for (int sh = 0; nbits > 0; sh += 8, nbits -= 8) {
            if (get_bits(b, nbits < 8 ? nbits : 8, &v) != 0)
                return -1;
            x |= (uint64_t)v << sh;
        }
        if (x <= UINT32_MAX) { /* a 32-bit division is the cheaper */
            uint32_t y = (uint32_t)x;
            out[2] = y % sizes[2];
            y /= sizes[2];
            out[1] = y % sizes[1];
            out[0] = y / sizes[1];
            return 0;
        }
        out[2] = (uint32_t)(x % sizes[2]);
        x /= sizes[2];
        out[1] = (uint32_t)(x % sizes[1]);
        out[0] = (uint32_t)(x / sizes[1]);
        return 0;
    }
    while (nbits > 8) {
        if (get_bits(b, 8, &v) != 0)
            return -1;
        bytes[nbytes++] = (unsigned char)v;
        nbits -= 8;
    }
    if (nbits > 0) {
        if (get_bits(b, nbits, &v) != 0)
            return -1;
        bytes[nbytes++] = (unsigned char)v;
    }
    for (int i = 2; i > 0; i--) {
        uint64_t rem = 0;
        for (int j = nbytes - 1; j >= 0; j--) {
            rem = (rem << 8) | bytes[j];
            uint64_t q = rem / sizes[i];
            bytes[j] = (unsigned char)q;
            rem -= q * sizes[i];
        }
        out[i] = (uint32_t)rem;
    }
    out[0] = (uint32_t)bytes[0] | (uint32_t)bytes[1] << 8 | (uint32_t)bytes[2] << 16 |
             (uint32_t)bytes[3] << 24;
    return 0;
}

int vb_xtc_unpack(const unsigned char *data, size_t len, size_t natoms, const int32_t minint[3],
                  const int32_t maxint[3], int32_t smallidx, int32_t *ints)
{
    uint32_t size[3];
    int large = 0, bits[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++) {
        int64_t s = (int64_t)maxint[k] - minint[k] + 1;
        if (s <= 0 || s > 0xffffffffll)
            return -1;
        size[k] = (uint32_t)s;
        large |= s > 0xffffff;
    }
    if (large)
        for (int k = 0; k < 3; k++)
            bits[k] = bits_of(size[k]);
    int packed_bits = large ? 0 : bits_of_product(size);
    if (smallidx < XTC_FIRSTIDX || smallidx >= XTC_LASTIDX)
        return -1;
    bit_reader b = {data, len, 0, 0, 0};
    size_t i = 0;
    int32_t run = 0;
    while (i < natoms) {
        int32_t big[3];
        uint32_t u[3];
        if (large) {
            for (int k = 0; k < 3; k++)
                if (get_bits(&b, bits[k], &u[k]) != 0)
                    return -1;
        } else if (get_mixed(&b, packed_bits, size, u) != 0) {
            return -1;
        }
        for (int k = 0; k < 3; k++)
            big[k] = (int32_t)((int64_t)u[k] + minint[k]);
        uint32_t flag, r;
        int is_smaller = 0;
        if (get_bits(&b, 1, &flag) != 0)
            return -1;
        if (flag) {
            if (get_bits(&b, 5, &r) != 0)
                return -1;
            run = (int32_t)r;
            is_smaller = run % 3;
            run -= is_smaller;
            is_smaller--;
        }
        if (i + 1 + (size_t)(run / 3) > natoms)
            return -1;
        int32_t *dst = ints + 3 * i;
        i++;
        if (run > 0) {
            const uint32_t radix = (uint32_t)magicints[smallidx];
            const uint32_t sizes[3] = {radix, radix, radix};
            const int32_t half = magicints[smallidx] / 2;
            int32_t prev[3] = {big[0], big[1], big[2]};
            for (int32_t k = 0; k < run; k += 3) {
                if (get_mixed(&b, smallidx, sizes, u) != 0)
                    return -1;
                int32_t cur[3];
                for (int a = 0; a < 3; a++)
                    cur[a] = (int32_t)((int64_t)u[a] + prev[a] - half);
                i++;
                if (k == 0) {
                    /* The large atom was written second: the small one
                     * comes out first, and later ones follow it. */
                    memcpy(dst, cur, sizeof cur);
                    memcpy(dst + 3, big, sizeof big);
                    dst += 6;
                } else {
                    memcpy(dst, cur, sizeof cur);
                    dst += 3;
                }
                memcpy(prev, cur, sizeof cur);
            }
        } else {
            memcpy(dst, big, sizeof big);
        }
        smallidx += is_smaller;
        if (smallidx < XTC_FIRSTIDX || smallidx >= XTC_LASTIDX)
            return -1;
    }
    return 0;
}
