/* The OpenCL program cache under damage (issue 18, item 2): a cached binary
 * one byte short, cut in half, with a flipped byte, with a foreign header,
 * or built with other options and copied under the expected name is never
 * handed to the driver (PoCL aborted or crashed on each): the program is
 * rebuilt after warning W750 and the file rewritten, so the next run loads
 * it without a warning. On the CPU device (PoCL in CI). */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "vb_test.h"
#include "vbi_input.h"
#include "vbg_runtime.h"

static char cache_root[256], cache_dir[300];

/* The one file of the cache folder whose name starts with prefix. */
static int find_cached(const char *prefix, char *path, size_t cap)
{
    DIR *d = opendir(cache_dir);
    int found = 0;
    for (struct dirent *e; d && (e = readdir(d));)
        if (strncmp(e->d_name, prefix, strlen(prefix)) == 0 && strstr(e->d_name, ".bin") &&
            !strstr(e->d_name, ".tmp")) {
            snprintf(path, cap, "%s/%s", cache_dir, e->d_name);
            found++;
        }
    if (d)
        closedir(d);
    return found;
}

/* The bytes of a file (the input layer's vbi_slurp), NULL if unreadable. */
static unsigned char *slurp(const char *path, size_t *len)
{
    char *b = NULL;
    *len = 0;
    return vbi_slurp(NULL, path, &b, len) == VB_OK ? (unsigned char *)b : NULL;
}

static void spit(const char *path, const unsigned char *b, size_t len)
{
    FILE *f = fopen(path, "wb");
    fwrite(b, 1, len, f);
    fclose(f);
}

/* Builds jfa_exact.cl with opts on a fresh runtime (so the cache on disk is
 * read) and checks the program makes its kernel. Returns what the context
 * warned. */
static const char *build(const char *opts, int *rc)
{
    static char warned[4096];
    FILE *diag = tmpfile();
    vb_config cfg = {1, diag};
    vb_ctx *ctx;
    vb_open(&ctx, &cfg);
    vbg_runtime *rt = NULL;
    *rc = vbg_runtime_open(ctx, VB_DEVICE_CPU, &rt);
    cl_program prog;
    if (*rc == VB_OK)
        *rc = vbg_program_get(ctx, rt, "jfa_exact.cl", opts, &prog);
    if (*rc == VB_OK) {
        cl_int err;
        cl_kernel k = clCreateKernel(prog, "jfa_exact", &err);
        if (err != CL_SUCCESS)
            *rc = VB_EDEVICE;
        if (k)
            clReleaseKernel(k);
    }
    vbg_runtime_close(rt);
    vb_close(ctx);
    fflush(diag);
    rewind(diag);
    size_t n = fread(warned, 1, sizeof warned - 1, diag);
    warned[n] = '\0';
    fclose(diag);
    return warned;
}

int main(void)
{
    const char *bin = getenv("VORBALL_BINARY_DIR");
    snprintf(cache_root, sizeof cache_root, "%s/test-cache/program-cache-test.%ld",
             bin ? bin : "/tmp", (long)getpid());
    snprintf(cache_dir, sizeof cache_dir, "%s/vorball", cache_root);
    setenv("XDG_CACHE_HOME", cache_root, 1);
    /* PoCL is left to its own cache unless asked (gpu/runtime.c). */
    setenv("VORBALL_PROGRAM_CACHE", "1", 1);
    /* PoCL's own cache private too: a cache shared with another tree
     * (.ci/test's sanitizer tree reuses the Release tree's) changes what
     * the first build writes. */
    char pocl_dir[600];
    snprintf(pocl_dir, sizeof pocl_dir, "%s/pocl", cache_root);
    setenv("POCL_CACHE_DIR", pocl_dir, 1);
    unsetenv("VORBALL_KERNEL_DIR");
    unsetenv("VORBALL_NO_PROGRAM_CACHE");

    int rc;
    const char *w = build("", &rc);
    if (rc == VB_EDEVICE && strstr(w, "W750") == NULL) {
        printf("no OpenCL CPU device: skipped\n");
        return 0;
    }
    CHECK_INT(rc, VB_OK);
    CHECK(strstr(w, "W750") == NULL);
    char good_path[600], other_path[600];
    CHECK_INT(find_cached("jfa_exact.cl-", good_path, sizeof good_path), 1);
    size_t good_len = 0, other_len = 0;
    unsigned char *good = slurp(good_path, &good_len);
    CHECK(good != NULL && good_len > 100);
    /* The same kernel with other options: another file. */
    w = build("-DVB_CACHE_TEST_OTHER=1", &rc);
    CHECK_INT(rc, VB_OK);
    CHECK_INT(find_cached("jfa_exact.cl-", other_path, sizeof other_path), 2);
    if (strcmp(other_path, good_path) == 0) { /* readdir order: take the other one */
        DIR *d = opendir(cache_dir);
        for (struct dirent *e; d && (e = readdir(d));) {
            char p[600];
            snprintf(p, sizeof p, "%s/%s", cache_dir, e->d_name);
            if (strncmp(e->d_name, "jfa_exact.cl-", 13) == 0 && strcmp(p, good_path) != 0)
                snprintf(other_path, sizeof other_path, "%s", p);
        }
        if (d)
            closedir(d);
    }
    unsigned char *other = slurp(other_path, &other_len);
    CHECK(other != NULL && strcmp(other_path, good_path) != 0);

    /* A clean cache is read without a warning. */
    w = build("", &rc);
    CHECK_INT(rc, VB_OK);
    CHECK(strstr(w, "W750") == NULL);

    struct {
        const char *what, *reason;
    } cases[] = {{"one byte short", "its length does not match its header"},
                 {"half", "its length does not match its header"},
                 {"flipped byte", "its checksum does not match"},
                 {"other options", "built for another kernel"},
                 {"no header", "not a vorball program cache file"},
                 {"empty", "not a vorball program cache file"}};
    unsigned char *buf = malloc(good_len + other_len + 1);
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        size_t len = good_len;
        memcpy(buf, good, good_len);
        switch (c) {
        case 0: len = good_len - 1; break;
        case 1: len = good_len / 2; break;
        case 2: buf[good_len - good_len / 3] ^= 0x40; break;
        case 3: memcpy(buf, other, other_len); len = other_len; break;
        case 4: memset(buf, 0x7f, 64); break;
        case 5: len = 0; break;
        }
        spit(good_path, buf, len);
        w = build("", &rc);
        CHECK_INT(rc, VB_OK);
        char want[900];
        snprintf(want, sizeof want,
                 "W750: %s: cached program of jfa_exact.cl cannot be used (%s", good_path,
                 cases[c].reason);
        if (!strstr(w, want))
            fprintf(stderr, "case '%s': warnings were:\n%s\n", cases[c].what, w);
        CHECK(strstr(w, want) != NULL);
        /* Rewritten: the next run reads it silently. */
        w = build("", &rc);
        CHECK_INT(rc, VB_OK);
        CHECK(strstr(w, "W750") == NULL);
        size_t again_len = 0;
        unsigned char *again = slurp(good_path, &again_len);
        CHECK_INT(again_len, good_len);
        free(again);
    }
    free(buf);
    free(good);
    free(other);
    char cmd[700];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", cache_root);
    CHECK_INT(system(cmd), 0);
    VB_TEST_END();
}
