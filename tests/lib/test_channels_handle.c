/* Unit test of the channels handle (lib/vb_channels.h, issue 29): the
 * option table by both spellings, the setter's and checker's refusals, a
 * reset, the calls refused before an engine or a run, and one frame of
 * gramicidin (corpus/data/1grm_single_hole2.pdb, grid 64, the reference)
 * read through the accessors: the rows' slices in range, each bottleneck
 * the smallest radius of its row's points, the CSV one line per row, the
 * flag volume's channel voxels the frame's count, and the pore row's axis. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vorball.h"

static void options(void)
{
    size_t n = vb_channels_option_count();
    CHECK(n > 20);
    vb_channels_option o, p;
    CHECK_INT(vb_channels_option_at(n, &o), -1);
    CHECK_INT(vb_channels_option_at(0, &o), 0);
    CHECK_INT(vb_channels_option_find("--probe", &o), 0);
    CHECK_INT(vb_channels_option_find("probe", &p), 0);
    CHECK_STR(o.name, p.name);
    CHECK_INT(o.type, VB_OPT_REAL);
    CHECK_STR(o.def, "1.4");
    CHECK_INT(vb_channels_option_find("--centrelines", &o), 0); /* the alias */
    CHECK_STR(o.name, "--centerlines");
    CHECK(o.py == NULL); /* an output of the command: no keyword */
    CHECK_INT(vb_channels_option_find("--nope", &o), -1);
    CHECK_INT(vb_channels_option_find("nope", &o), -1);
    CHECK_INT(vb_channels_option_find(NULL, &o), -1);
}

static void refusals(vb_ctx *ctx)
{
    vb_channels *ch = NULL;
    char err[512];
    CHECK_INT(vb_channels_new(ctx, &ch), VB_OK);
    CHECK_INT(vb_channels_set(ch, "--grid", "100", err, sizeof err), -1);
    CHECK(strstr(err, "power of two") != NULL);
    CHECK_INT(vb_channels_set(ch, "--bogus", "1", err, sizeof err), -1);
    CHECK(strstr(err, "--bogus") != NULL);
    CHECK_INT(vb_channels_set(ch, "--pymol", "x.pml", err, sizeof err), 0);
    CHECK_INT(vb_channels_check(ch, err, sizeof err), -1); /* --pymol needs --centerlines */
    CHECK(strstr(err, "--centerlines") != NULL);
    vb_channels_request r;
    vb_channels_request_get(ch, &r);
    CHECK_STR(r.pymol, "x.pml");
    vb_channels_reset(ch);
    vb_channels_request_get(ch, &r);
    CHECK(r.pymol == NULL);
    CHECK_INT(vb_channels_check(ch, err, sizeof err), 0);
    /* No engine, no run yet. */
    vb_channels_frame f;
    size_t nflags;
    CHECK_INT(vb_channels_frame_get(ch, &f), -1);
    CHECK(vb_channels_last(ch) == NULL);
    CHECK(vb_channels_flags(ch, &nflags) == NULL && nflags == 0);
    CHECK_STR(vb_channels_device_name(ch), "");
    vb_sphere_set *none = NULL;
    vb_read_options ro = {0};
    const char *src = getenv("VORBALL_SOURCE_DIR");
    char path[4096];
    snprintf(path, sizeof path, "%s/corpus/data/1grm_single_hole2.pdb", src ? src : ".");
    CHECK_INT(vb_spheres_load(ctx, path, &ro, NULL, 1, &none), VB_OK);
    CHECK_INT(vb_channels_run(ctx, ch, none, 0, 1, 1, 0), VB_EMISUSE);
    vb_spheres_free(none);
    vb_channels_free(ch);
    vb_channels_free(NULL);
}

/* The frame through the accessors, against what the table says. */
static void one_frame(vb_ctx *ctx, const vb_sphere_set *s)
{
    vb_channels *ch = NULL;
    char err[512];
    CHECK_INT(vb_channels_new(ctx, &ch), VB_OK);
    CHECK_INT(vb_channels_set(ch, "grid", "64", err, sizeof err), 0);
    CHECK_INT(vb_channels_set(ch, "--device", "ref", err, sizeof err), 0);
    CHECK_INT(vb_channels_check(ch, err, sizeof err), 0);
    CHECK_INT(vb_channels_open(ctx, ch), VB_OK);
    CHECK(strlen(vb_channels_device_name(ch)) > 0);
    CHECK_INT(vb_channels_run(ctx, ch, s, 0, 1, 1, VB_CHANNELS_KEEP_FLAGS), VB_OK);
    vb_channels_frame f;
    CHECK_INT(vb_channels_frame_get(ch, &f), 0);
    CHECK_INT(f.nx, 64);
    CHECK(f.h > 0 && f.ms_total > 0);
    const vb_channels_result *res = vb_channels_last(ch);
    CHECK(res != NULL);
    size_t rows = vb_channels_result_rows(res), np = vb_channels_result_points(res), nl;
    const int32_t *lining = vb_channels_result_lining(res, &nl);
    CHECK(rows > 0 && np > 0 && nl > 0 && lining != NULL);
    vb_channel_row row;
    vb_channel_point p;
    for (size_t k = 0; k < rows; k++) {
        CHECK_INT(vb_channels_result_row(res, k, &row), 0);
        CHECK(row.npoints > 0 && row.first_point + row.npoints <= np);
        CHECK(row.first_lining + row.nlining <= nl && row.bottleneck_at < row.npoints);
        double rmin = 1e300;
        for (size_t q = 0; q < row.npoints; q++) {
            CHECK_INT(vb_channels_result_point(res, row.first_point + q, &p), 0);
            CHECK(p.atom >= 0 && (size_t)p.atom < s->n);
            rmin = p.r < rmin ? p.r : rmin;
        }
        CHECK_NEAR(row.bottleneck, rmin, 0.0);
    }
    CHECK_INT(vb_channels_result_row(res, rows, &row), -1);
    CHECK_INT(vb_channels_result_point(res, np, &p), -1);
    vb_channels_pore pore;
    vb_channels_result_row(res, 0, &row);
    /* Gramicidin's pore is row 0, open at both ends. */
    CHECK_INT(row.kind, 2);
    CHECK_INT(vb_channels_result_pore(res, &pore), 1);
    CHECK(pore.why != NULL);
    CHECK_NEAR(pore.u[0] * pore.u[0] + pore.u[1] * pore.u[1] + pore.u[2] * pore.u[2], 1.0, 1e-9);
    CHECK(pore.step > 0 && pore.F > 0 && pore.g_macro_pS > 0);
    CHECK(pore.open_lo && pore.open_hi);
    /* The flag volume: its channel voxels are the frame's count. */
    size_t nflags, channel = 0;
    const uint8_t *flags = vb_channels_flags(ch, &nflags);
    CHECK(flags != NULL && nflags == (size_t)f.nx * f.ny * f.nz);
    for (size_t v = 0; flags && v < nflags; v++)
        channel += (flags[v] & VB_CHANNEL_F_CHANNEL) != 0;
    CHECK_INT(channel, f.channel_voxels);
    /* The CSV: a header and one line per row. */
    char *buf = NULL;
    size_t len = 0, lines = 0;
    FILE *m = open_memstream(&buf, &len);
    vb_channels_write_frame_csv(ch, m);
    fclose(m);
    for (size_t k = 0; k < len; k++)
        lines += buf[k] == '\n';
    CHECK_INT(lines, rows + 1);
    free(buf);
    /* The profile: a header and one line per point of every row. */
    m = open_memstream(&buf, &len);
    vb_channels_write_frame_profile(ch, m);
    fclose(m);
    lines = 0;
    for (size_t k = 0; k < len; k++)
        lines += buf[k] == '\n';
    size_t points = 0;
    for (size_t k = 0; k < rows; k++) {
        vb_channels_result_row(res, k, &row);
        points += row.npoints;
    }
    CHECK_INT(lines, points + 1);
    free(buf);
    /* Done: the results go, the engine stays for the next frame. */
    vb_channels_done(ch);
    CHECK(vb_channels_last(ch) == NULL);
    CHECK_INT(vb_channels_run(ctx, ch, s, 1, 2, 0, 0), VB_OK);
    CHECK_INT(vb_channels_frame_get(ch, &f), 0);
    CHECK_INT(f.frame, 1);
    CHECK(vb_channels_flags(ch, &nflags) == NULL); /* not kept this time */
    CHECK_INT(vb_channels_result_rows(vb_channels_last(ch)), rows);
    vb_channels_free(ch);
}

int main(void)
{
    vb_config cfg = {0, NULL};
    vb_ctx *ctx;
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 1;
    options();
    refusals(ctx);
    const char *src = getenv("VORBALL_SOURCE_DIR");
    char path[4096];
    snprintf(path, sizeof path, "%s/corpus/data/1grm_single_hole2.pdb", src ? src : ".");
    vb_read_options ro = {0};
    vb_sphere_set *s = NULL;
    CHECK_INT(vb_spheres_load(ctx, path, &ro, NULL, 1, &s), VB_OK);
    if (s)
        one_frame(ctx, s);
    vb_spheres_free(s);
    vb_close(ctx);
    VB_TEST_END();
}
