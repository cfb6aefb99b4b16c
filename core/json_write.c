/* JSON string literals and CSV fields for the writers of every command. */
#include <string.h>

#include "vb_json.h"

static void write_string(FILE *f, const char *s, int html)
{
    fputc('"', f);
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        if (*p == '"' || *p == '\\')
            fprintf(f, "\\%c", *p);
        else if (*p < 0x20 || (html && (*p == '<' || *p == '>' || *p == '&')))
            fprintf(f, "\\u%04x", *p);
        else
            fputc(*p, f);
    }
    fputc('"', f);
}

void vb_json_write_string(FILE *f, const char *s)
{
    write_string(f, s, 0);
}

void vb_json_write_string_html(FILE *f, const char *s)
{
    write_string(f, s, 1);
}

void vb_csv_write_field(FILE *f, const char *s)
{
    if (!strpbrk(s, ",\"\r\n")) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (const char *p = s; *p; p++) {
        if (*p == '"')
            fputc('"', f);
        fputc(*p, f);
    }
    fputc('"', f);
}
