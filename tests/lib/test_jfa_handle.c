/* Unit test of the jfa handle (lib/vb_jfa.h, issue 29): the option table
 * by both spellings, the setter's refusals in the command's words (the
 * value kept when refused), the rules between options, the calls refused
 * before a run, and two runs read through the accessors: five 2D seeds
 * given as points (the exact labels the nearest seed of each pixel, ties
 * to the lowest index; the figures' text and JSON; the picture) and a 3D
 * run's three slices side by side. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vorball.h"

static void options(void)
{
    size_t n = vb_jfa_option_count();
    CHECK_INT((long)n, 17);
    vb_option o, p;
    CHECK_INT(vb_jfa_option_at(n, &o), -1);
    CHECK_INT(vb_jfa_option_find("-n", &o), 0);
    CHECK_INT(vb_jfa_option_find("size", &p), 0);
    CHECK_STR(o.name, p.name);
    CHECK_STR(o.name, "--size");
    CHECK_INT(o.type, VB_OPT_POW2);
    CHECK_STR(o.def, "512");
    CHECK_INT(vb_jfa_option_find("-V", &o), 0);
    CHECK_STR(o.name, "--variant");
    CHECK_INT(vb_jfa_option_find("--json", &o), 0);
    CHECK(o.py == NULL && o.type == VB_OPT_FLAG); /* an output of the command */
    CHECK_INT(vb_jfa_option_find("--nope", &o), -1);
    CHECK_INT(vb_jfa_option_find("json", &o), -1);
    CHECK_INT(vb_jfa_option_find(NULL, &o), -1);
}

/* err after vb_jfa_set(j, name, value) refused it, "" when accepted. */
static const char *refused(vb_jfa *j, const char *name, const char *value)
{
    static char err[512];
    err[0] = '\0';
    if (vb_jfa_set(j, name, value, err, sizeof err) == 0)
        err[0] = '\0';
    return err;
}

static void refusals(vb_ctx *ctx)
{
    vb_jfa *j = NULL;
    char err[512];
    CHECK_INT(vb_jfa_new(ctx, &j), VB_OK);
    CHECK_STR(refused(j, "-n", "64"), "");
    CHECK_STR(refused(j, "--size", "32768"), "bad --size '32768'");
    CHECK_INT(vb_errcode(ctx), VB_EMISUSE);
    CHECK_STR(refused(j, "dim", "4"), "--dim must be 2 or 3");
    CHECK_STR(refused(j, "k", "0"), "bad --seeds '0'");
    CHECK_STR(refused(j, "-m", "0"), "bad -m '0'");
    CHECK_STR(refused(j, "--margin", "-1"), "bad --margin '-1'");
    CHECK_STR(refused(j, "--rng", "x"), "bad --rng 'x'");
    CHECK_STR(refused(j, "--bogus", "1"), "unknown jfa option '--bogus'");
    CHECK_STR(refused(j, "--size", NULL), "option --size needs a value");
    CHECK(strstr(refused(j, "-V", "jfa,nope"), "nope") != NULL);
    CHECK(strstr(refused(j, "--dist", "gauss"), "gauss") != NULL);
    /* The rules between options. */
    CHECK_STR(refused(j, "--protein", "x.pdb"), "");
    CHECK_INT(vb_jfa_source_file(j, "seeds.txt"), VB_OK);
    CHECK_INT(vb_jfa_check(j, err, sizeof err), -1);
    CHECK_STR(err, "give either SEEDS or --protein");
    vb_jfa_free(j);
    CHECK_INT(vb_jfa_new(ctx, &j), VB_OK);
    CHECK_STR(refused(j, "--protein", "x.pdb"), "");
    CHECK_STR(refused(j, "-d", "2"), "");
    CHECK_INT(vb_jfa_check(j, err, sizeof err), -1);
    CHECK_STR(err, "--protein needs --dim 3");
    vb_jfa_free(j);
    CHECK_INT(vb_jfa_new(ctx, &j), VB_OK);
    CHECK_STR(refused(j, "--slice", "40"), "");
    CHECK_STR(refused(j, "-d", "3"), "");
    CHECK_STR(refused(j, "-n", "32"), "");
    CHECK_INT(vb_jfa_check(j, err, sizeof err), -1);
    CHECK_STR(err, "bad --slice '40' (z values below n)");
    CHECK_INT(vb_errcode(ctx), VB_EMISUSE);
    vb_jfa_free(j);
    CHECK_INT(vb_jfa_new(ctx, &j), VB_OK);
    CHECK_STR(refused(j, "device", "tpu"), ""); /* checked with the rules */
    CHECK_INT(vb_jfa_check(j, err, sizeof err), -1);
    CHECK(strstr(err, "tpu") != NULL);
    /* Nothing before a run. */
    vb_jfa_info info;
    vb_jfa_figures f;
    uint8_t *rgb = NULL;
    uint32_t w = 0;
    CHECK_INT(vb_jfa_info_get(j, &info), -1);
    CHECK_INT(vb_jfa_figures_get(j, 0, &f), -1);
    CHECK_INT(vb_jfa_picture(ctx, j, NULL, &rgb, &w), VB_EMISUSE);
    vb_jfa_free(j);
    vb_jfa_free(NULL);
}

/* The text vb_jfa_write writes (malloc'd). */
static char *written(const vb_jfa *j, int json)
{
    FILE *f = tmpfile();
    if (!f)
        return NULL;
    vb_jfa_write(j, f, json);
    long n = ftell(f);
    rewind(f);
    char *b = malloc((size_t)n + 1);
    size_t got = b ? fread(b, 1, (size_t)n, f) : 0;
    if (b)
        b[got] = '\0';
    fclose(f);
    return b;
}

static void points_run(vb_ctx *ctx)
{
    static const double seeds[5][2] = {
        {3.25, 4.0}, {20.5, 7.75}, {11.0, 25.5}, {28.0, 28.0}, {0.0, 31.0}};
    vb_jfa *j = NULL;
    char err[512];
    CHECK_INT(vb_jfa_new(ctx, &j), VB_OK);
    CHECK(vb_jfa_set(j, "size", "32", err, sizeof err) == 0 &&
          vb_jfa_set(j, "device", "ref", err, sizeof err) == 0 &&
          vb_jfa_set(j, "variant", "jfa,exact", err, sizeof err) == 0 &&
          vb_jfa_set(j, "check", NULL, err, sizeof err) == 0 &&
          vb_jfa_set(j, "--size", "100000", err, sizeof err) != 0); /* 32 kept */
    CHECK_INT(vb_jfa_source_points(j, &seeds[0][0], 5), VB_OK);
    CHECK_INT(vb_jfa_check(j, err, sizeof err), 0);
    CHECK_INT(vb_jfa_run(ctx, j), VB_OK);
    vb_jfa_info info;
    CHECK_INT(vb_jfa_info_get(j, &info), 0);
    CHECK_INT(info.runs, 2);
    CHECK_INT(info.dim, 2);
    CHECK_INT((long)info.n, 32);
    CHECK_INT((long)info.seeds, 5);
    CHECK_STR(info.source, "points");
    CHECK(info.exact_ms >= 0);
    vb_jfa_figures f;
    CHECK_INT(vb_jfa_figures_get(j, 2, &f), -1);
    CHECK_INT(vb_jfa_figures_get(j, 0, &f), 0);
    CHECK_STR(f.variant, "jfa");
    CHECK_INT(f.checked, 1);
    CHECK_INT(vb_jfa_figures_get(j, 1, &f), 0);
    CHECK_STR(f.variant, "exact");
    CHECK_INT((long)f.wrong, 0);
    CHECK_INT((long)f.differ, 0);
    CHECK_INT((long)f.pixels, 32 * 32);
    long bad = 0;
    for (int y = 0; y < 32; y++)
        for (int x = 0; x < 32; x++) {
            int best = 0;
            double bd = 1e300;
            for (int s = 0; s < 5; s++) {
                double dx = x - seeds[s][0], dy = y - seeds[s][1], d = dx * dx + dy * dy;
                if (d < bd) {
                    bd = d;
                    best = s;
                }
            }
            bad += f.labels[y * 32 + x] != (uint32_t)best;
        }
    CHECK_INT(bad, 0);
    char *text = written(j, 0), *json = written(j, 1);
    CHECK(text && strstr(text, "# grid: 32^2, 5 seeds (points)\n") != NULL);
    CHECK(json && strncmp(json, "{\"device\": \"reference (C)\"", 26) == 0);
    CHECK(json && strstr(json, "\"variant\": \"exact\"") != NULL);
    free(text);
    free(json);
    uint8_t *rgb = NULL;
    uint32_t w = 0;
    CHECK_INT(vb_jfa_picture(ctx, j, NULL, &rgb, &w), VB_OK);
    CHECK_INT((long)w, 32);
    long black = 0;
    for (size_t i = 0; rgb && i < 32 * 32; i++)
        black += !rgb[3 * i] && !rgb[3 * i + 1] && !rgb[3 * i + 2];
    CHECK(black > 0 && black < 32 * 32 / 2);
    free(rgb);
    vb_jfa_free(j);
}

static void slices_run(vb_ctx *ctx)
{
    vb_jfa *j = NULL;
    char err[512];
    CHECK_INT(vb_jfa_new(ctx, &j), VB_OK);
    CHECK(vb_jfa_set(j, "-d", "3", err, sizeof err) == 0 &&
          vb_jfa_set(j, "-n", "32", err, sizeof err) == 0 &&
          vb_jfa_set(j, "-k", "30", err, sizeof err) == 0 &&
          vb_jfa_set(j, "--device", "ref", err, sizeof err) == 0 &&
          vb_jfa_set(j, "-V", "exact", err, sizeof err) == 0 &&
          vb_jfa_set(j, "--slice", "3,16,31", err, sizeof err) == 0 &&
          vb_jfa_check(j, err, sizeof err) == 0);
    CHECK_INT(vb_jfa_run(ctx, j), VB_OK);
    uint8_t *rgb = NULL;
    uint32_t w = 0;
    CHECK_INT(vb_jfa_picture(ctx, j, NULL, &rgb, &w), VB_OK);
    CHECK_INT((long)w, 96);
    free(rgb);
    vb_jfa_free(j);
}

int main(void)
{
    vb_config cfg = {0, NULL};
    vb_ctx *ctx;
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 1;
    options();
    refusals(ctx);
    points_run(ctx);
    slices_run(ctx);
    vb_close(ctx);
    VB_TEST_END();
}
