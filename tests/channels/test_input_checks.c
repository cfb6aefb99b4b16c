/* #18 (7): `channels` and `jfa --protein` check their input as `vertices`
 * does (radius -1: E103, duplicate spheres: E104, |x| > 1e9: E107, each with
 * its own exit code), and the frames of a DCD are checked one by one: a
 * NaN coordinate is E102 naming the frame, 3e38 is E107. */
#include <math.h>
#include <string.h>

#include "cli_env.h"
#include "vb_dcd.h"
#include "vb_test.h"

static char err[8192];

/* Runs `vorball ARGS`, stderr kept in err; returns the exit status. */
static int run(const char *args)
{
    char cmd[4096], path[512];
    snprintf(path, sizeof path, "%s/err.txt", dir);
    snprintf(cmd, sizeof cmd, "%s %s >/dev/null 2>%s", bin, args, path);
    int st = system(cmd);
    FILE *f = fopen(path, "r");
    size_t n = f ? fread(err, 1, sizeof err - 1, f) : 0;
    err[n] = '\0';
    if (f)
        fclose(f);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static const char *write_file(const char *name, const char *text)
{
    static char path[8][512];
    static int k;
    char *p = path[k++ % 8];
    snprintf(p, 512, "%s/%s", dir, name);
    FILE *f = fopen(p, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    return p;
}

static void bad_spheres(void)
{
    static const struct {
        const char *name, *text, *diag;
        int exit;
    } cases[] = {
        {"neg.xyzr", "0 0 0 1.5\n3 0 0 -1\n0 3 0 1.5\n0 0 3 1.5\n", "E103: ", 13},
        {"dup.xyzr", "0 0 0 1.5\n3 0 0 1.5\n0 3 0 1.5\n3 0 0 1.5\n", "E104: ", 14},
        {"big.xyzr", "0 0 0 1.5\n3e10 0 0 1.5\n0 3 0 1.5\n0 0 3 1.5\n", "E107: ", 17},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        const char *in = write_file(cases[c].name, cases[c].text);
        char a[1024];
        snprintf(a, sizeof a, "channels %s --grid 16 --device ref", in);
        CHECK_INT(run(a), cases[c].exit);
        CHECK(strstr(err, cases[c].diag) != NULL);
        snprintf(a, sizeof a, "jfa --protein %s -n 16 --device ref", in);
        CHECK_INT(run(a), cases[c].exit);
        CHECK(strstr(err, cases[c].diag) != NULL);
    }
}

/* A DCD of the 4-atom topology whose frame 1 holds `bad` at atom 2's x. */
static const char *dcd_with(vb_ctx *ctx, const char *name, double bad)
{
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    double x[4] = {0, 3, 0, 0}, y[4] = {0, 0, 3, 0}, z[4] = {0, 0, 0, 3};
    vb_dcd_writer *w;
    CHECK_INT(vb_dcd_writer_open(ctx, path, 4, 1.0, "input checks", &w), VB_OK);
    CHECK_INT(vb_dcd_writer_frame(ctx, w, x, y, z), VB_OK);
    x[1] = bad;
    CHECK_INT(vb_dcd_writer_frame(ctx, w, x, y, z), VB_OK);
    CHECK_INT(vb_dcd_writer_close(ctx, w), VB_OK);
    return path;
}

static void bad_frames(vb_ctx *ctx)
{
    const char *topo = write_file("topo.pdb",
        "ATOM      1  C   ALA A   1       0.000   0.000   0.000  1.00  0.00           C\n"
        "ATOM      2  C   ALA A   1       3.000   0.000   0.000  1.00  0.00           C\n"
        "ATOM      3  C   ALA A   1       0.000   3.000   0.000  1.00  0.00           C\n"
        "ATOM      4  C   ALA A   1       0.000   0.000   3.000  1.00  0.00           C\n"
        "END\n");
    char a[2048];
    snprintf(a, sizeof a, "channels %s --dcd %s --grid 16 --device ref", topo,
             dcd_with(ctx, "nan.dcd", NAN));
    CHECK_INT(run(a), 12);
    CHECK(strstr(err, "E102: ") && strstr(err, "frame 1"));
    snprintf(a, sizeof a, "channels %s --dcd %s --grid 16 --device ref", topo,
             dcd_with(ctx, "huge.dcd", 3e38));
    CHECK_INT(run(a), 17);
    CHECK(strstr(err, "E107: ") && strstr(err, "frame 1"));
    /* Frame 0 alone is fine. */
    snprintf(a, sizeof a, "channels %s --dcd %s --frames 0 --grid 16 --device ref", topo,
             dcd_with(ctx, "ok.dcd", 3.0));
    CHECK_INT(run(a), 0);
}

int main(void)
{
    if (cli_env_open("vb_input_checks") != 0)
        return 1;
    vb_ctx *ctx;
    vb_config cfg = {0, NULL};
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 1;
    bad_spheres();
    bad_frames(ctx);
    vb_close(ctx);
    cli_env_close();
    VB_TEST_END();
}
