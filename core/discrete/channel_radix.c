/* The channel analysis's LSD radix sort (vbc_radix.h). */
#include <string.h>

#include "vbc_radix.h"

#define DIGIT_BITS 11
#define DIGIT_MASK ((1u << DIGIT_BITS) - 1)

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
    for (unsigned sh = lo_bit; sh < 64; sh += DIGIT_BITS) {
        if (((differ >> sh) & DIGIT_MASK) == 0)
            continue;
        size_t cnt[DIGIT_MASK + 2];
        memset(cnt, 0, sizeof cnt);
        for (size_t t = 0; t < n; t++)
            cnt[((key[t] >> sh) & DIGIT_MASK) + 1]++;
        for (size_t d = 0; d <= DIGIT_MASK; d++)
            cnt[d + 1] += cnt[d];
        for (size_t t = 0; t < n; t++) {
            size_t at = cnt[(key[t] >> sh) & DIGIT_MASK]++;
            ktmp[at] = key[t];
            if (val)
                vtmp[at] = val[t];
        }
        memcpy(key, ktmp, n * sizeof *key);
        if (val)
            memcpy(val, vtmp, n * sizeof *val);
    }
}
