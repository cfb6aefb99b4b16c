/* DCD round trip through our writer and reader; a big-endian CHARMM file
 * with unit cells and a fixed atom, built byte by byte; a truncated file;
 * a file that is no DCD. */
#include <stdint.h>
#include <stdlib.h>
#include <unistd.h>

#include "vb_dcd.h"
#include "vb_test.h"

/* A fresh temporary file name (the file exists, empty). */
static void tmp_name(char *buf, size_t len)
{
    const char *dir = getenv("TMPDIR");
    snprintf(buf, len, "%s/vbc_dcd_XXXXXX", dir && *dir ? dir : "/tmp");
    int fd = mkstemp(buf);
    if (fd >= 0)
        close(fd);
}

static void test_round_trip(vb_ctx *ctx)
{
    char path[256];
    tmp_name(path, sizeof path);
    enum { NA = 5, NF = 3 };
    double x[NA], y[NA], z[NA];
    vb_dcd_writer *w;
    CHECK_INT(vb_dcd_writer_open(ctx, path, NA, 0.002, "vorball test", &w), VB_OK);
    for (int f = 0; f < NF; f++) {
        for (int i = 0; i < NA; i++) {
            x[i] = 1.25 * i + f;
            y[i] = -3.5 + 0.1 * i * f;
            z[i] = 1000.0 / (i + 1) - f;
        }
        CHECK_INT(vb_dcd_writer_frame(ctx, w, x, y, z), VB_OK);
    }
    CHECK_INT(vb_dcd_writer_close(ctx, w), VB_OK);

    vb_dcd *d;
    CHECK_INT(vb_dcd_open(ctx, path, &d), VB_OK);
    CHECK_INT(vb_dcd_atoms(d), NA);
    CHECK_INT(vb_dcd_header_frames(d), NF);
    CHECK_NEAR(vb_dcd_delta(d), 0.002, 1e-9);
    int got, frames = 0;
    double err = 0.0;
    for (;;) {
        CHECK_INT(vb_dcd_next(ctx, d, x, y, z, NULL, &got), VB_OK);
        if (!got)
            break;
        for (int i = 0; i < NA; i++) {
            /* Stored as float32: exact for these values up to float rounding. */
            err = fmax(err, fabs(x[i] - (float)(1.25 * i + frames)));
            err = fmax(err, fabs(y[i] - (float)(-3.5 + 0.1 * i * frames)));
            err = fmax(err, fabs(z[i] - (float)(1000.0 / (i + 1) - frames)));
        }
        frames++;
    }
    CHECK_INT(frames, NF);
    CHECK(err == 0.0);
    vb_dcd_close(d);

    /* Cut inside the last frame: two frames and warning W801. */
    FILE *f = fopen(path, "r+b");
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fclose(f);
    CHECK(truncate(path, size - 10) == 0);
    CHECK_INT(vb_dcd_open(ctx, path, &d), VB_OK);
    uint64_t warned = vb_ctx_stats(ctx)->warnings;
    frames = 0;
    while (vb_dcd_next(ctx, d, x, y, z, NULL, &got) == VB_OK && got)
        frames++;
    CHECK_INT(frames, NF - 1);
    CHECK_INT(vb_ctx_stats(ctx)->warnings, warned + 1);
    vb_dcd_close(d);
    remove(path);
}

/* Big-endian writers for the hand-built file. */
static void be32(FILE *f, uint32_t v)
{
    unsigned char b[4] = {(unsigned char)(v >> 24), (unsigned char)(v >> 16), (unsigned char)(v >> 8),
                          (unsigned char)v};
    fwrite(b, 1, 4, f);
}

static void be_float(FILE *f, float v)
{
    uint32_t u;
    memcpy(&u, &v, 4);
    be32(f, u);
}

static void be_double(FILE *f, double v)
{
    uint64_t u;
    memcpy(&u, &v, 8);
    be32(f, (uint32_t)(u >> 32));
    be32(f, (uint32_t)u);
}

/* 3 atoms, atom 2 fixed (NAMNF = 1), unit cell per frame, CHARMM, big endian:
 * frame 1 lists all atoms, frame 2 only the free atoms 1 and 3. */
static void test_big_endian_fixed(vb_ctx *ctx)
{
    char path[256];
    tmp_name(path, sizeof path);
    FILE *f = fopen(path, "wb");
    be32(f, 84);
    fwrite("CORD", 1, 4, f);
    uint32_t ic[20] = {2, 0, 1, 0, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 24};
    for (int i = 0; i < 20; i++) {
        if (i == 9)
            be_float(f, 0.5f);
        else
            be32(f, ic[i]);
    }
    be32(f, 84);
    be32(f, 4 + 80);
    be32(f, 1);
    char title[80];
    memset(title, ' ', sizeof title);
    fwrite(title, 1, 80, f);
    be32(f, 4 + 80);
    be32(f, 4);
    be32(f, 3);
    be32(f, 4);
    be32(f, 8); /* free atoms: 1 and 3 (1-based) */
    be32(f, 1);
    be32(f, 3);
    be32(f, 8);
    for (int frame = 0; frame < 2; frame++) {
        be32(f, 48);
        for (int c = 0; c < 6; c++)
            be_double(f, 10.0 * (c + 1) + frame);
        be32(f, 48);
        int n = frame == 0 ? 3 : 2;
        for (int axis = 0; axis < 3; axis++) {
            be32(f, (uint32_t)(4 * n));
            for (int i = 0; i < n; i++)
                be_float(f, (float)(100 * axis + 10 * frame + i));
            be32(f, (uint32_t)(4 * n));
        }
    }
    fclose(f);

    vb_dcd *d;
    CHECK_INT(vb_dcd_open(ctx, path, &d), VB_OK);
    CHECK_INT(vb_dcd_atoms(d), 3);
    CHECK_NEAR(vb_dcd_delta(d), 0.5, 0.0);
    double x[3], y[3], z[3], cell[6];
    int got;
    CHECK_INT(vb_dcd_next(ctx, d, x, y, z, cell, &got), VB_OK);
    CHECK_INT(got, 1);
    CHECK_NEAR(x[1], 1.0, 0.0);
    CHECK_NEAR(z[2], 202.0, 0.0);
    CHECK_NEAR(cell[5], 60.0, 0.0);
    CHECK_INT(vb_dcd_next(ctx, d, x, y, z, cell, &got), VB_OK);
    CHECK_INT(got, 1);
    /* Free atoms get the second frame's values; the fixed atom keeps frame 1's. */
    CHECK_NEAR(x[0], 10.0, 0.0);
    CHECK_NEAR(x[1], 1.0, 0.0);
    CHECK_NEAR(x[2], 11.0, 0.0);
    CHECK_NEAR(y[2], 111.0, 0.0);
    CHECK_NEAR(cell[0], 11.0, 0.0);
    CHECK_INT(vb_dcd_next(ctx, d, x, y, z, cell, &got), VB_OK);
    CHECK_INT(got, 0);
    vb_dcd_close(d);
    remove(path);
}

static void test_not_dcd(vb_ctx *ctx)
{
    char path[256];
    tmp_name(path, sizeof path);
    FILE *f = fopen(path, "wb");
    fprintf(f, "ATOM      1  CA  ALA A   1       0.000   0.000   0.000  1.00  0.00           C\n"
               "ATOM      2  CA  ALA A   2       1.000   0.000   0.000  1.00  0.00           C\n");
    fclose(f);
    vb_dcd *d;
    CHECK_INT(vb_dcd_open(ctx, path, &d), VB_EINPUT_FORMAT);
    CHECK(d == NULL);
    remove(path);
    CHECK_INT(vb_dcd_open(ctx, "/nonexistent/dir/x.dcd", &d), VB_EIO);
}

int main(void)
{
    vb_ctx *ctx;
    vb_config cfg = {0, NULL};
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 1;
    test_round_trip(ctx);
    test_big_endian_fixed(ctx);
    test_not_dcd(ctx);
    vb_close(ctx);
    VB_TEST_END();
}
