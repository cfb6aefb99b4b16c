/* Option values as numbers: a whole string, nothing before or after, read
 * as a double or as a non-negative integer (the command line's parsers and
 * the channel options' table share them). */
#ifndef VB_NUMTEXT_H
#define VB_NUMTEXT_H

#include <stddef.h>

/* Parses all of s as a double (strtod: decimal or hex, "inf" and "nan"
 * too; the caller checks the range). Returns 0 with *out set, or -1 when s
 * is empty, has other characters, or overflows. */
int vb_parse_double(const char *s, double *out);

/* Parses all of s as a non-negative decimal integer. Returns 0 with *out
 * set, or -1 when s is empty, signed, has other characters, or overflows. */
int vb_parse_size(const char *s, size_t *out);

#endif
