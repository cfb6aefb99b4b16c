/* Option values as numbers (vb_numtext.h). */
#include <errno.h>
#include <stdlib.h>

#include "vb_numtext.h"

int vb_parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE)
        return -1;
    *out = v;
    return 0;
}

int vb_parse_size(const char *s, size_t *out)
{
    char *end;
    if (*s == '-' || *s == '\0')
        return -1;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    if (*end != '\0' || errno == ERANGE)
        return -1;
    *out = (size_t)v;
    return 0;
}
