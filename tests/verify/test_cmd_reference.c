/* `vorball reference` as users run it: output lines, formats, exit codes. */
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include "vb_test.h"

static const char *vorball;
static char dir[256];

/* Runs `vorball <args>` through the shell; returns the exit code and the
 * first `cap` bytes of stdout in out. */
static int run(const char *args, char *out, size_t cap)
{
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "'%s' %s", vorball, args);
    FILE *p = popen(cmd, "r");
    if (!p)
        return -1;
    size_t n = fread(out, 1, cap - 1, p);
    out[n] = '\0';
    int st = pclose(p);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static void write_file(const char *name, const char *text)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: test_cmd_reference VORBALL\n");
        return 2;
    }
    vorball = argv[1];
    snprintf(dir, sizeof dir, "/tmp/vb_test_cmd_reference_%ld", (long)getpid());
    char mk[300];
    snprintf(mk, sizeof mk, "mkdir -p %s", dir);
    CHECK_INT(system(mk), 0);
    /* Cubic lattice: the one vertex has all eight spheres (degree 8). */
    write_file("cube.xyzr", "-1 -1 -1 0.5\n1 -1 -1 0.5\n-1 1 -1 0.5\n1 1 -1 0.5\n"
                            "-1 -1 1 0.5\n1 -1 1 0.5\n-1 1 1 0.5\n1 1 1 0.5\n");
    write_file("three.xyzr", "0 0 0 1\n3 0 0 1\n0 3 0 1\n");
    static char out[65536];
    char args[1024];

    snprintf(args, sizeof args, "reference %s/cube.xyzr", dir);
    CHECK_INT(run(args, out, sizeof out), 0);
    CHECK(strstr(out, "\n0,1,2,3,4,5,6,7\t0\t0\t0\t1.2320508075688772\tcertified\n") != NULL);

    snprintf(args, sizeof args, "reference --output-format voronota %s/cube.xyzr", dir);
    CHECK_INT(run(args, out, sizeof out), 0);
    /* Voronota lists the degree-8 vertex as quadruple lines. */
    CHECK(strstr(out, "0 1 2 3 0 0 0 1.2320508075688772") != NULL ||
          strstr(out, "0 1 2 4 0 0 0 1.2320508075688772") != NULL);

    snprintf(args, sizeof args, "reference %s/cube.xyzr --output-format json -o %s/cube.json --stats 2>%s/err",
             dir, dir, dir);
    CHECK_INT(run(args, out, sizeof out), 0);
    snprintf(args, sizeof args, "%s/cube.json", dir);
    FILE *f = fopen(args, "r");
    size_t n = f ? fread(out, 1, sizeof out - 1, f) : 0;
    out[n] = '\0';
    if (f)
        fclose(f);
    CHECK(strstr(out, "\"ids\":[0,1,2,3,4,5,6,7]") != NULL);
    snprintf(args, sizeof args, "%s/err", dir);
    f = fopen(args, "r");
    n = f ? fread(out, 1, sizeof out - 1, f) : 0;
    out[n] = '\0';
    if (f)
        fclose(f);
    CHECK(strstr(out, "quadruples: 70") != NULL);
    CHECK(strstr(out, "exact evaluations") != NULL);

    /* stdin, and the spelling of `vorball vertices`. */
    snprintf(args, sizeof args, "reference --output-format voronota - < %s/cube.xyzr", dir);
    CHECK_INT(run(args, out, sizeof out), 0);
    CHECK(strstr(out, " 0 0 0 1.2320508075688772") != NULL);

    CHECK_INT(run("reference --help", out, sizeof out), 0);
    CHECK(strstr(out, "usage: vorball reference") != NULL);
    CHECK_INT(run("reference --bogus x 2>/dev/null", out, sizeof out), 2);
    CHECK_INT(run("reference 2>/dev/null", out, sizeof out), 2);
    snprintf(args, sizeof args, "reference %s/missing.xyzr 2>/dev/null", dir);
    CHECK_INT(run(args, out, sizeof out), 3);
    snprintf(args, sizeof args, "reference %s/three.xyzr 2>/dev/null", dir);
    CHECK_INT(run(args, out, sizeof out), 16); /* fewer than 4 spheres */
    snprintf(args, sizeof args, "reference --format nosuch %s/cube.xyzr 2>/dev/null", dir);
    CHECK_INT(run(args, out, sizeof out), 2);

    snprintf(mk, sizeof mk, "rm -rf %s", dir);
    CHECK_INT(system(mk), 0);
    VB_TEST_END();
}
