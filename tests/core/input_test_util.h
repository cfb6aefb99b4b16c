/* Helpers of the input-layer tests: read a string, check an error's code and
 * its "name:line:" prefix, find corpus files. */
#ifndef INPUT_TEST_UTIL_H
#define INPUT_TEST_UTIL_H

#include <stdlib.h>
#include <string.h>

#include "vb_spheres.h"
#include "vb_test.h"

/* A context whose warnings go to a temporary file the test can read. */
static inline vb_ctx *open_ctx(FILE **diag)
{
    vb_ctx *ctx = NULL;
    vb_config cfg = {.verbosity = 1, .diag = NULL};
    if (diag) {
        *diag = tmpfile();
        cfg.diag = *diag;
    }
    vb_open(&ctx, &cfg);
    return ctx;
}

/* Everything written to the diagnostic file so far (static buffer). */
static inline const char *diag_text(FILE *diag)
{
    static char buf[8192];
    fflush(diag);
    long pos = ftell(diag);
    rewind(diag);
    size_t n = fread(buf, 1, sizeof buf - 1, diag);
    buf[n] = '\0';
    fseek(diag, pos, SEEK_SET);
    return buf;
}

static inline int read_text(vb_ctx *ctx, const char *name, const char *text, const vb_read_options *o,
                     vb_sphere_set **out)
{
    return vb_spheres_read_buffer(ctx, name, text, strlen(text), o, out);
}

/* Reads text and validates with min_count; frees the set. Returns the code. */
static inline int read_validate(vb_ctx *ctx, const char *name, const char *text,
                         const vb_read_options *o, size_t min_count)
{
    vb_sphere_set *s = NULL;
    vb_clear_error(ctx);
    int rc = read_text(ctx, name, text, o, &s);
    if (rc == VB_OK)
        rc = vb_spheres_validate(ctx, s, min_count);
    vb_spheres_free(s);
    return rc;
}

/* Checks the code and that the message starts with `prefix` (e.g. "t:3:"). */
#define CHECK_ERROR(ctx, rc, code, prefix)                                                      \
    do {                                                                                        \
        CHECK_INT((rc), (code));                                                                \
        CHECK_INT(vb_errcode(ctx), (code));                                                     \
        if (strncmp(vb_errmsg(ctx), (prefix), strlen(prefix)) == 0) {                           \
            vb_test_passed++;                                                                   \
        } else {                                                                                \
            vb_test_failed++;                                                                   \
            fprintf(stderr, "%s:%d: message \"%s\" does not start with \"%s\"\n", __FILE__,     \
                    __LINE__, vb_errmsg(ctx), (prefix));                                        \
        }                                                                                       \
    } while (0)

#define CHECK_DEC(d, m, e)                                                                      \
    do {                                                                                        \
        CHECK_INT((d).mant, (m));                                                               \
        CHECK_INT((d).exp10, (e));                                                              \
    } while (0)

/* Path of a corpus file: $VORBALL_SOURCE_DIR/corpus/<rel> (static buffer). */
static inline const char *corpus_path(const char *rel)
{
    static char buf[4096];
    const char *root = getenv("VORBALL_SOURCE_DIR");
    snprintf(buf, sizeof buf, "%s/corpus/%s", root ? root : ".", rel);
    return buf;
}

/* Writes text to a temporary file and returns its path (static buffer). */
static inline const char *temp_file(const char *text)
{
    static char path[64];
    strcpy(path, "/tmp/vb_input_testXXXXXX");
    int fd = mkstemp(path);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    return path;
}

/* The decimal of text s (tests of exact boxes and images). */
static inline vb_decimal dec_of(const char *s)
{
    vb_decimal e;
    vb_decimal_parse(s, strlen(s), &e, NULL);
    return e;
}

/* Whether decimal e equals the number written s, exactly. */
static inline int dec_is(vb_decimal e, const char *s)
{
    return vb_decimal_cmp(e, dec_of(s)) == 0;
}

#endif
