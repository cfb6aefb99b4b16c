/* The one writer of strings in the text formats several commands write:
 * JSON string literals and CSV fields. */
#ifndef VB_JSON_H
#define VB_JSON_H

#include <stdio.h>

/* Writes s as a JSON string literal: quotes, backslashes and control bytes
 * escaped, other bytes (UTF-8 included) as they are. */
void vb_json_write_string(FILE *f, const char *s);

/* As vb_json_write_string, with '<', '>' and '&' escaped too (\u003c...),
 * so the literal is safe inside an HTML <script> element. */
void vb_json_write_string_html(FILE *f, const char *s);

/* Writes s as one CSV field (RFC 4180): as it is, or between double quotes
 * with inner quotes doubled when it holds a comma, a quote, CR or LF. */
void vb_csv_write_field(FILE *f, const char *s);

#endif
