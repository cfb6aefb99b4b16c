/* `vorball channels --device ref` against the OpenCL CPU device (PoCL), byte
 * for byte on the CSV table and the centreline PDB (the JSON too, less its
 * device name and timings), on synthetic molecules and corpus files; and the
 * fallback when OpenCL has no platform at all (OCL_ICD_VENDORS pointing at an
 * empty directory): warning W804 for every --device (one fallback rule: gpu
 * no longer tries the CPU device first, and W805 is retired), exit 0, and
 * the same output. */
#include <stdlib.h>
#include <sys/stat.h>

#include "cli_env.h"
#include "synth.h"
#include "vbg_runtime.h"
#include "vb_test.h"

/* Runs `vorball channels ARGS` with optional environment prefix; stderr goes
 * to dir/err.txt (overwritten). Returns the exit status. */
static int run(const char *env, const char *args)
{
    char cmd[16384];
    snprintf(cmd, sizeof cmd, "%s %s channels %s 2>%s/err.txt", env ? env : "", bin, args, dir);
    int st = system(cmd);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* Reads dir/name whole into a malloc'ed NUL-terminated buffer (NULL if absent). */
static char *slurp(const char *name, size_t *len)
{
    char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)n + 1);
    size_t got = fread(b, 1, (size_t)n, f);
    fclose(f);
    b[got] = '\0';
    *len = got;
    return b;
}

/* Nonzero when files a and b in dir hold the same bytes (and exist). */
static int same_file(const char *a, const char *b)
{
    size_t la, lb;
    char *x = slurp(a, &la), *y = slurp(b, &lb);
    int same = x && y && la == lb && memcmp(x, y, la) == 0;
    free(x);
    free(y);
    return same;
}

static int lines(const char *name)
{
    size_t n;
    char *b = slurp(name, &n);
    int c = 0;
    for (size_t i = 0; b && i < n; i++)
        c += b[i] == '\n';
    free(b);
    return c;
}

static int stderr_has(const char *what)
{
    size_t n;
    char *b = slurp("err.txt", &n);
    int has = b && strstr(b, what) != NULL;
    free(b);
    return has;
}

/* Runs INPUT OPTS on --device cpu and ref; demands identical table and
 * centrelines, and at least `rows` table rows. */
static void same_output(const char *input, const char *opts, int rows)
{
    char a[8192];
    const char *dev[2] = {"cpu", "ref"};
    for (int d = 0; d < 2; d++) {
        snprintf(a, sizeof a, "%s %s --device %s -o %s/%s.csv --centerlines %s/%s.pdb", input, opts,
                 dev[d], dir, dev[d], dir, dev[d]);
        CHECK_INT(run(NULL, a), 0);
        /* No fallback warning either way. */
        CHECK(!stderr_has("W804") && !stderr_has("W805") && !stderr_has("W806"));
    }
    CHECK(lines("cpu.csv") >= rows + 1);
    CHECK(same_file("cpu.csv", "ref.csv"));
    CHECK(same_file("cpu.pdb", "ref.pdb"));
}

/* The JSON table less the lines holding the device name and the timings. */
static void json_stable(const char *name, const char *out)
{
    size_t n;
    char *b = slurp(name, &n), p[512];
    snprintf(p, sizeof p, "%s/%s", dir, out);
    FILE *f = fopen(p, "w");
    for (char *l = b; b && f && *l;) {
        char *e = strchr(l, '\n');
        size_t k = e ? (size_t)(e - l) + 1 : strlen(l);
        char save = l[k];
        l[k] = '\0';
        if (!strstr(l, "\"device\"") && !strstr(l, "\"ms\"") && !strstr(l, "\"clock\""))
            fputs(l, f);
        l[k] = save;
        l += k;
    }
    if (f)
        fclose(f);
    free(b);
}

static void write_xyzr(const char *name, const vb_sphere_set *s)
{
    char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "w");
    for (size_t i = 0; f && i < s->n; i++)
        fprintf(f, "%.6f %.6f %.6f %.3f\n", s->x[i], s->y[i], s->z[i], s->r[i]);
    if (f)
        fclose(f);
}

static void test_backends_agree(void)
{
    vb_sphere_set *cyl = synth_cylinder(8, 12, 6.0, 1.6, 2.6);
    vb_sphere_set *shell = synth_shell(240, 9.0, 1.6);
    write_xyzr("cyl.xyzr", cyl);
    write_xyzr("shell.xyzr", shell);
    vb_spheres_free(cyl);
    vb_spheres_free(shell);
    char in[2048];
    snprintf(in, sizeof in, "%s/cyl.xyzr", dir);
    same_output(in, "--probe 1.0 --grid 32", 1);
    same_output(in, "--probe 1.0 --grid 64 --jfa jfa+1", 1);
    snprintf(in, sizeof in, "%s/shell.xyzr", dir);
    same_output(in, "--probe 1.0 --grid 32 --cavities", 1);
    snprintf(in, sizeof in, "%s/corpus/data/1grm_single_hole2.pdb", src);
    same_output(in, "--probe 1.0 --grid 32", 2);
    same_output(in, "--probe 1.0 --grid 64", 1);
    same_output(in, "--probe 1.0 --grid 64 --jfa facet", 1);
    snprintf(in, sizeof in, "%s/corpus/data/ngl_md_ascii_trj.pdb", src);
    same_output(in, "--grid 32 --frames 0:51:25", 2);

    /* JSON: identical but for the device name and the timings (the lines
     * of the "ms" and "clock" objects). */
    char a[8192];
    const char *dev[2] = {"cpu", "ref"};
    for (int d = 0; d < 2; d++) {
        snprintf(a, sizeof a, "%s/corpus/data/1grm_single_hole2.pdb --probe 1.0 --grid 32 --json "
                 "--device %s -o %s/%s.json", src, dev[d], dir, dev[d]);
        CHECK_INT(run(NULL, a), 0);
    }
    json_stable("cpu.json", "cpu.sj");
    json_stable("ref.json", "ref.sj");
    CHECK(lines("cpu.sj") > 20);
    CHECK(same_file("cpu.sj", "ref.sj"));
}

/* No OpenCL platform: auto and gpu fall back to the reference and say so. */
static void test_fallback(void)
{
    char env[512], a[8192];
    snprintf(env, sizeof env, "OCL_ICD_VENDORS=%s/empty", dir);
    snprintf(a, sizeof a, "%s/corpus/data/1grm_single_hole2.pdb --probe 1.0 --grid 32 -o %s/cpu.csv "
             "--centerlines %s/cpu.pdb --device cpu", src, dir, dir);
    CHECK_INT(run(NULL, a), 0);
    const char *dev[2] = {"auto", "gpu"};
    for (int d = 0; d < 2; d++) {
        snprintf(a, sizeof a, "%s/corpus/data/1grm_single_hole2.pdb --probe 1.0 --grid 32 -o %s/fb.csv "
                 "--centerlines %s/fb.pdb --device %s", src, dir, dir, dev[d]);
        char old[512];
        snprintf(old, sizeof old, "%s/fb.csv", dir);
        remove(old);
        CHECK_INT(run(env, a), 0);
        /* auto on a host without a GPU is the reference, no OpenCL tried
         * (vbc_channels_device): nothing to warn about. */
        if (d == 1 || vbg_runtime_gpu_present())
            CHECK(stderr_has("W804"));
        else
            CHECK(!stderr_has("W804"));
        CHECK(!stderr_has("W805"));
        CHECK(stderr_has("on reference (C)"));
        CHECK(same_file("cpu.csv", "fb.csv"));
        CHECK(same_file("cpu.pdb", "fb.pdb"));
    }
    /* --device cpu with no platform falls back the same way. */
    snprintf(a, sizeof a, "%s/corpus/data/1grm_single_hole2.pdb --probe 1.0 --grid 32 -o %s/fb.csv "
             "--device cpu", src, dir);
    CHECK_INT(run(env, a), 0);
    CHECK(stderr_has("W804"));
    CHECK(same_file("cpu.csv", "fb.csv"));
}

int main(void)
{
    if (cli_env_open("vbc_ref") != 0)
        return 1;
    char empty[300];
    snprintf(empty, sizeof empty, "%s/empty", dir);
    if (mkdir(empty, 0700) != 0)
        return 1;
    test_backends_agree();
    test_fallback();
    cli_env_close();
    VB_TEST_END();
}
