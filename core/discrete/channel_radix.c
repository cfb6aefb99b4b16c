/* The channel analysis's LSD radix sort (vbc_radix.h). */
#include <string.h>

#include "vbc_radix.h"

/* Digits of 11 bits for long lists; 8 below 2048 keys, where a pass's
 * table (2^bits counts to clear and sum) would outweigh the keys (a
 * channel's components hold tens to hundreds of voxels each). Every
 * width gives the one stable order. */
#define WIDE_BITS 11
#define NARROW_BITS 8
#define NARROW_BELOW 2048

void vbc_radix_sort(uint64_t *key, uint32_t *val, uint64_t *ktmp, uint32_t *vtmp, size_t n,
                    unsigned lo_bit)
{
    uint64_t any = 0, all = ~(uint64_t)0;
    for (size_t t = 0; t < n; t++) {
        any |= key[t];
        all &= key[t];
    }
    /* Bits where the keys differ: only digits holding one of them move. */
    uint64_t differ = any ^ all;
    unsigned bits = n < NARROW_BELOW ? NARROW_BITS : WIDE_BITS;
    size_t mask = ((size_t)1 << bits) - 1;
    for (unsigned sh = lo_bit; sh < 64; sh += bits) {
        if (((differ >> sh) & mask) == 0)
            continue;
        size_t cnt[((size_t)1 << WIDE_BITS) + 1];
        memset(cnt, 0, (mask + 2) * sizeof *cnt);
        for (size_t t = 0; t < n; t++)
            cnt[((key[t] >> sh) & mask) + 1]++;
        for (size_t d = 0; d <= mask; d++)
            cnt[d + 1] += cnt[d];
        for (size_t t = 0; t < n; t++) {
            size_t at = cnt[(key[t] >> sh) & mask]++;
            ktmp[at] = key[t];
            if (val)
                vtmp[at] = val[t];
        }
        memcpy(key, ktmp, n * sizeof *key);
        if (val)
            memcpy(val, vtmp, n * sizeof *val);
    }
}
