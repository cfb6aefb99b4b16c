/* Small helpers for the JSON that several commands write. */
#ifndef VB_JSON_H
#define VB_JSON_H

#include <stdio.h>

/* Writes s as a JSON string literal: quotes, backslashes and control bytes
 * escaped, other bytes (UTF-8 included) as they are. */
void vb_json_write_string(FILE *f, const char *s);

#endif
