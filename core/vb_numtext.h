/* Option values as numbers: a whole string, nothing before or after, read
 * as a double or as a non-negative integer (the command line's parsers and
 * the channel options' table share them). */
#ifndef VB_NUMTEXT_H
#define VB_NUMTEXT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* Parses all of s as a double (strtod: decimal or hex, "inf" and "nan"
 * too; the caller checks the range). Returns 0 with *out set, or -1 when s
 * is empty, has other characters, or overflows. */
int vb_parse_double(const char *s, double *out);

/* Parses all of s as a non-negative decimal integer. Returns 0 with *out
 * set, or -1 when s is empty, signed, has other characters, or overflows. */
int vb_parse_size(const char *s, size_t *out);

/* Room for vb_format_g17's text and its NUL ("-1.2345678901234567e-308"). */
#define VB_G17_MAX 32

/* Writes x to out exactly as snprintf(out, VB_G17_MAX, "%.17g", x) does in
 * the default rounding mode (every double reads back bit-exactly), NUL
 * terminated, much faster for the numbers vertex files hold (fixed
 * notation); returns the length. core/numtext_g17.c. */
size_t vb_format_g17(double x, char out[VB_G17_MAX]);

/* Writes v in decimal ("%u"), NUL terminated; returns the length. */
size_t vb_format_u32(uint32_t v, char out[11]);

/* Writes v in decimal ("%d"), NUL terminated; returns the length. */
size_t vb_format_i32(int32_t v, char out[12]);

#endif
