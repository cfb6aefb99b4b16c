/* The channel analysis's radix sort (private to core/discrete): keys of 64
 * bits with an optional 32-bit value each, least significant digit first,
 * so equal keys keep their order. Linear where a comparison sort is
 * n log n, and the one order on any number of threads. */
#ifndef VBC_RADIX_H
#define VBC_RADIX_H

#include <stddef.h>
#include <stdint.h>

/* Sorts key[0..n) ascending by their bits lo_bit .. 63, stably, carrying
 * val[t] with key[t] when val is not NULL; ktmp (n keys) and vtmp (n
 * values, unused when val is NULL) are scratch. Digits on which every key
 * agrees cost no pass. Allocates nothing. */
void vbc_radix_sort(uint64_t *key, uint32_t *val, uint64_t *ktmp, uint32_t *vtmp, size_t n,
                    unsigned lo_bit);

/* The 64-bit key whose ascending order is the descending order of the
 * double c (not NaN), the two zeros one key. */
static inline uint64_t vbc_radix_desc(double c)
{
    union {
        double d;
        uint64_t u;
    } b;
    b.d = c == 0.0 ? 0.0 : c;
    /* Ascending doubles as unsigned: flip every bit of a negative, the sign
     * bit of a positive; descending is the complement. */
    uint64_t asc = (b.u >> 63) ? ~b.u : b.u | ((uint64_t)1 << 63);
    return ~asc;
}

#endif
