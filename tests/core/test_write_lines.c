/* vb_write_lines writes the bytes one thread's printf would, whatever the
 * thread count and whether the rounds go through stdio or through the
 * mapped file (VORBALL_WRITE_MAP=1, vb_write_map.h): items of 0 to 3 lines
 * of varying length over several rounds, between a header and a trailer
 * written through stdio, into an output under a temporary name (mapped), a
 * memory stream (never mapped) and a file opened write-only (never
 * mapped). A file size limit reached mid-way is an error the caller sees
 * (ferror or VB_EIO), never a signal at a store into the mapping. */
#define _GNU_SOURCE
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "vb.h"
#include "vb_output.h"
#include "vb_test.h"
#include "vb_write_lines.h"
#include "vb_write_map.h"

#define ITEMS 150000u /* about 4 rounds of 4 x 3 blocks of 4096 at 3 threads */

static double value(size_t k)
{
    uint64_t s = 0x9e3779b97f4a7c15ull ^ (k * 0x2545f4914f6cdd1dull);
    return vb_test_binades(&s, -8, 40);
}

/* Item k: k % 4 lines (none for k % 4 == 0). */
static void item(vb_text *t, const void *arg, size_t k)
{
    (void)arg;
    for (size_t j = 0; j < k % 4; j++) {
        vb_text_u32(t, 0, (uint32_t)k);
        vb_text_g17(t, '\t', value(k + j));
        vb_text_put(t, "\n", 1);
    }
}

static const char HEAD[] = "# header through stdio\n", TAIL[] = "]trailer\n";

/* What one thread's printf writes. */
static char *expected(size_t *len)
{
    size_t cap = (size_t)ITEMS * 3 * 40 + 64, n = 0;
    char *b = malloc(cap);
    n += (size_t)snprintf(b + n, cap - n, "%s", HEAD);
    for (size_t k = 0; k < ITEMS; k++)
        for (size_t j = 0; j < k % 4; j++)
            n += (size_t)snprintf(b + n, cap - n, "%u\t%.17g\n", (unsigned)k, value(k + j));
    n += (size_t)snprintf(b + n, cap - n, "%s", TAIL);
    *len = n;
    return b;
}

static void write_all(FILE *f)
{
    fputs(HEAD, f);
    CHECK_INT(vb_write_lines(f, ITEMS, item, NULL), VB_OK);
    fputs(TAIL, f);
}

static void same_file(const char *path, const char *want, size_t len, const char *what)
{
    FILE *f = fopen(path, "rb");
    char *got = malloc(len + 2);
    size_t n = f ? fread(got, 1, len + 1, f) : 0;
    if (f)
        fclose(f);
    CHECK_INT(n, len);
    int eq = n == len && memcmp(got, want, len) == 0;
    if (!eq)
        fprintf(stderr, "%s: bytes differ\n", what);
    CHECK(eq);
    free(got);
}

int main(void)
{
    size_t len;
    char *want = expected(&len);
    char path[] = "/tmp/vb_test_write_lines_XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    close(fd);
    vb_ctx *ctx = NULL;
    CHECK_INT(vb_open(&ctx, NULL), VB_OK);
    const char *threads[] = {"1", "2", "3"};
    for (int map = 0; map < 2; map++)
        for (int i = 0; i < 3; i++) {
            setenv("VORBALL_WRITE_MAP", map ? "1" : "0", 1);
            setenv("VORBALL_THREADS", threads[i], 1);
            char what[64];
            snprintf(what, sizeof what, "map %d, %s threads", map, threads[i]);
            /* An output under a temporary name: mapped exactly when asked. */
            FILE *f = vb_output_open(ctx, path);
            vb_map_out m;
            int mapped = vb_map_begin(f, &m) == 0;
            CHECK_INT(mapped, map);
            if (mapped)
                CHECK_INT(vb_map_end(f, &m), 0);
            write_all(f);
            CHECK_INT(vb_output_commit(ctx, f), VB_OK);
            same_file(path, want, len, what);
            /* A memory stream has no descriptor: stdio. */
            char *buf = NULL;
            size_t blen = 0;
            FILE *ms = open_memstream(&buf, &blen);
            CHECK_INT(vb_map_begin(ms, &m), -1);
            write_all(ms);
            fclose(ms);
            CHECK(blen == len && memcmp(buf, want, len) == 0);
            free(buf);
            /* Write-only (a shell's redirection): stdio. */
            FILE *wo = fopen(path, "w");
            CHECK_INT(vb_map_begin(wo, &m), -1);
            write_all(wo);
            fclose(wo);
            same_file(path, want, len, what);
        }
    /* The file may not grow past half the text: a round's fallocate fails
     * (EFBIG), the file is cut back and stdio's writes fail in turn. */
    struct rlimit old, half;
    CHECK_INT(getrlimit(RLIMIT_FSIZE, &old), 0);
    half = old;
    half.rlim_cur = (rlim_t)(len / 2);
    signal(SIGXFSZ, SIG_IGN);
    setenv("VORBALL_WRITE_MAP", "1", 1);
    setenv("VORBALL_THREADS", "3", 1);
    CHECK_INT(setrlimit(RLIMIT_FSIZE, &half), 0);
    FILE *f = vb_output_open(ctx, path);
    fputs(HEAD, f);
    int rc = vb_write_lines(f, ITEMS, item, NULL);
    fputs(TAIL, f);
    CHECK(rc == VB_EIO || (rc == VB_OK && ferror(f)));
    CHECK(vb_output_commit(ctx, f) == VB_EIO);
    CHECK_INT(setrlimit(RLIMIT_FSIZE, &old), 0);
    unlink(path);
    vb_close(ctx);
    free(want);
    VB_TEST_END();
}
