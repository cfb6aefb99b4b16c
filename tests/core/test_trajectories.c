/* XTC and TRR readers against the coordinates MDAnalysis reads from the same
 * files (corpus/golden/trajectories/, one .expect per file, written once by its
 * make_fixtures.py): every header value and every listed coordinate equal
 * bit for bit, the per-frame sums too; compressed copies read the same;
 * damaged files give E115, never a crash or E101. */
#include <stdint.h>
#include <zlib.h>

#include "input_test_util.h"
#include "vb_xdr.h"

/* Reads `traj` and compares it with `expect`; returns the frames met. */
static int compare(vb_ctx *ctx, const char *traj, const char *expect)
{
    FILE *e = fopen(corpus_path(expect), "r");
    CHECK(e != NULL);
    if (!e)
        return 0;
    vb_xdr_traj *t = NULL;
    CHECK_INT(vb_xdr_open(ctx, corpus_path(traj), &t), VB_OK);
    if (!t) {
        fclose(e);
        return 0;
    }
    size_t na = vb_xdr_atoms(t);
    double *xyz = malloc(3 * na * sizeof *xyz);
    char line[512];
    int frames = 0, got = 0, mismatches = 0;
    vb_xdr_frame fr;
    while (fgets(line, sizeof line, e)) {
        long k, n, step;
        double time, prec, v[9];
        int i;
        if (sscanf(line, "frame %ld natoms %ld step %ld time %lf precision %lf", &k, &n, &step,
                   &time, &prec) == 5) {
            CHECK_INT(vb_xdr_next(ctx, t, xyz, &fr, &got), VB_OK);
            CHECK_INT(got, 1);
            CHECK_INT((long)na, n);
            CHECK_INT(fr.step, step);
            CHECK(fr.time == time);
            CHECK(fr.precision == prec);
            frames++;
        } else if (sscanf(line, "box %lf %lf %lf %lf %lf %lf %lf %lf %lf", &v[0], &v[1], &v[2],
                          &v[3], &v[4], &v[5], &v[6], &v[7], &v[8]) == 9) {
            for (int a = 0; a < 9; a++)
                CHECK(fr.box[a] == v[a]);
        } else if (sscanf(line, "atom %d %lf %lf %lf", &i, &v[0], &v[1], &v[2]) == 4) {
            for (int a = 0; a < 3; a++)
                if (xyz[3 * i + a] != v[a] && mismatches++ < 5)
                    fprintf(stderr, "%s frame %d atom %d axis %d: %.17g, MDAnalysis %.17g\n",
                            traj, frames - 1, i, a, xyz[3 * i + a], v[a]);
        } else if (sscanf(line, "sum %lf %lf %lf", &v[0], &v[1], &v[2]) == 3) {
            double s[3] = {0, 0, 0};
            for (size_t j = 0; j < na; j++)
                for (int a = 0; a < 3; a++)
                    s[a] += xyz[3 * j + a];
            for (int a = 0; a < 3; a++)
                CHECK(s[a] == v[a]);
        }
    }
    CHECK_INT(mismatches, 0);
    /* And nothing after the last frame. */
    CHECK_INT(vb_xdr_next(ctx, t, xyz, &fr, &got), VB_OK);
    CHECK_INT(got, 0);
    free(xyz);
    vb_xdr_close(t);
    fclose(e);
    return frames;
}

/* A copy of a corpus file at a temporary path, gzip-compressed when gz. */
static const char *copy_of(const char *rel, int gz, size_t cut)
{
    static char path[64];
    FILE *in = fopen(corpus_path(rel), "rb");
    strcpy(path, "/tmp/vb_traj_testXXXXXX");
    int fd = mkstemp(path);
    if (!in || fd < 0)
        return path;
    unsigned char buf[1 << 16];
    size_t n, total = 0;
    gzFile z = gz ? gzdopen(fd, "wb9") : NULL;
    FILE *out = gz ? NULL : fdopen(fd, "wb");
    while ((n = fread(buf, 1, sizeof buf, in)) > 0) {
        if (cut && total + n > cut)
            n = cut - total;
        if (gz)
            gzwrite(z, buf, (unsigned)n);
        else
            fwrite(buf, 1, n, out);
        total += n;
        if (cut && total >= cut)
            break;
    }
    if (gz)
        gzclose(z);
    else
        fclose(out);
    fclose(in);
    return path;
}

static void test_against_mdanalysis(vb_ctx *ctx)
{
    CHECK_INT(compare(ctx, "data/xtc_10x10.xtc", "golden/trajectories/xtc_10x10.xtc.expect"), 10);
    CHECK_INT(compare(ctx, "data/trr_10x10.trr", "golden/trajectories/trr_10x10.trr.expect"), 10);
    CHECK_INT(compare(ctx, "data/cobrotoxin_frame1.xtc",
                      "golden/trajectories/cobrotoxin_frame1.xtc.expect"), 1);
    CHECK_INT(compare(ctx, "data/ngl_md_10frames.xtc",
                      "golden/trajectories/ngl_md_10frames.xtc.expect"), 10);
    CHECK_INT(compare(ctx, "data/ngl_md_10frames.trr",
                      "golden/trajectories/ngl_md_10frames.trr.expect"), 10);
}

/* A gzip copy decodes to the same frames (through the cookie stream). */
static void test_compressed(vb_ctx *ctx)
{
    const char *gz = copy_of("data/cobrotoxin_frame1.xtc", 1, 0);
    char path[80];
    snprintf(path, sizeof path, "%s", gz);
    vb_xdr_traj *a = NULL, *b = NULL;
    CHECK_INT(vb_xdr_open(ctx, corpus_path("data/cobrotoxin_frame1.xtc"), &a), VB_OK);
    CHECK_INT(vb_xdr_open(ctx, path, &b), VB_OK);
    if (a && b) {
        size_t na = vb_xdr_atoms(a);
        CHECK_INT(vb_xdr_atoms(b), 19385);
        double *x = malloc(3 * na * sizeof *x), *y = malloc(3 * na * sizeof *y);
        int ga, gb;
        CHECK_INT(vb_xdr_next(ctx, a, x, NULL, &ga), VB_OK);
        CHECK_INT(vb_xdr_next(ctx, b, y, NULL, &gb), VB_OK);
        CHECK(ga == 1 && gb == 1 && memcmp(x, y, 3 * na * sizeof *x) == 0);
        free(x);
        free(y);
    }
    vb_xdr_close(a);
    vb_xdr_close(b);
    remove(path);
}

/* Cut files: inside the packed data of the only frame, and a few bytes into
 * a second frame; a TRR cut in its coordinates. */
static void test_damaged(vb_ctx *ctx)
{
    static const struct {
        const char *rel;
        size_t cut;
        int frames_ok;
    } cases[] = {
        {"data/cobrotoxin_frame1.xtc", 30000, 0},
        {"data/xtc_10x10.xtc", 104 + 6, 1},
        {"data/ngl_md_10frames.xtc", 2000, 1},
        {"data/trr_10x10.trr", 480 + 200, 1},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char path[80];
        snprintf(path, sizeof path, "%s", copy_of(cases[c].rel, 0, cases[c].cut));
        vb_xdr_traj *t = NULL;
        CHECK_INT(vb_xdr_open(ctx, path, &t), VB_OK);
        if (!t)
            continue;
        size_t na = vb_xdr_atoms(t);
        double *x = malloc(3 * na * sizeof *x);
        int got = 1, frames = 0, rc = VB_OK;
        while (rc == VB_OK && got) {
            rc = vb_xdr_next(ctx, t, x, NULL, &got);
            frames += rc == VB_OK && got;
        }
        CHECK_INT(rc, VB_EINPUT_TRAJECTORY);
        CHECK(frames >= cases[c].frames_ok);
        CHECK(strstr(vb_errmsg(ctx), "frame") != NULL);
        free(x);
        vb_xdr_close(t);
        remove(path);
    }
    /* Not a trajectory at all. */
    vb_xdr_traj *t = NULL;
    CHECK_INT(vb_xdr_open(ctx, corpus_path("data/1crn.pdb"), &t), VB_EINPUT_FORMAT);
}

/* A binary trajectory handed to the sphere readers is named, not parsed as
 * text: never E101. */
static void test_not_text(vb_ctx *ctx)
{
    static const char *const files[] = {"data/xtc_10x10.xtc", "data/trr_10x10.trr",
                                        "data/adk_dims_2frames.dcd"};
    for (size_t k = 0; k < 3; k++) {
        vb_sphere_set *s = NULL;
        vb_read_options o;
        memset(&o, 0, sizeof o);
        CHECK_INT(vb_spheres_read_file(ctx, corpus_path(files[k]), &o, &s), VB_EINPUT_NOSPHERES);
        CHECK(strstr(vb_errmsg(ctx), "--traj") != NULL);
        /* --format does not make it text either. */
        o.format = VB_FMT_XYZR;
        CHECK_INT(vb_spheres_read_file(ctx, corpus_path(files[k]), &o, &s), VB_EINPUT_NOSPHERES);
        CHECK(s == NULL);
    }
}

/* The decoder on a hand-made stream: 8 atoms, all large, sizes 8 per axis
 * (the mixed-radix number takes the bits of 8^3 = 512: 10), no runs. */
static void test_unpack_large(void)
{
    /* Atom k is (k, k, k) above minint: number = x*64 + y*8 + z, sent as
     * its low byte, then the 2 bits above it. */
    unsigned char data[64] = {0};
    size_t bit = 0;
    for (int k = 0; k < 8; k++) {
        uint32_t num = (uint32_t)(k * 64 + k * 8 + k);
        uint32_t parts[2] = {num & 0xff, num >> 8};
        int widths[2] = {8, 2};
        for (int p = 0; p < 2; p++)
            for (int b = widths[p] - 1; b >= 0; b--, bit++)
                if ((parts[p] >> b) & 1)
                    data[bit / 8] |= (unsigned char)(0x80 >> (bit % 8));
        bit++; /* flag 0: no run */
    }
    int32_t minint[3] = {-3, -3, -3}, maxint[3] = {4, 4, 4}, ints[24];
    CHECK_INT(vb_xtc_unpack(data, (bit + 7) / 8, 8, minint, maxint, 9, ints), 0);
    for (int k = 0; k < 8; k++)
        for (int a = 0; a < 3; a++)
            CHECK_INT(ints[3 * k + a], k - 3);
    /* One atom more than the data hold. */
    CHECK_INT(vb_xtc_unpack(data, (bit + 7) / 8, 9, minint, maxint, 9, ints), -1);
    /* smallidx outside the table. */
    CHECK_INT(vb_xtc_unpack(data, (bit + 7) / 8, 8, minint, maxint, 80, ints), -1);
}

int main(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    test_against_mdanalysis(ctx);
    test_compressed(ctx);
    test_damaged(ctx);
    test_not_text(ctx);
    test_unpack_large();
    vb_close(ctx);
    VB_TEST_END();
}
