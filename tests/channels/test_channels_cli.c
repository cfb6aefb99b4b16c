/* `vorball channels` end to end on corpus files: gramicidin A gives one
 * through channel along its pore (the y axis of this file) with a bottleneck
 * near HOLE's; every output file is written; the MD trajectory is processed
 * frame by frame; a DCD written from that trajectory gives the same frames;
 * an XTC over its topology is read; a failing run leaves no table; a synthetic
 * ring pore below the probe radius is measured exactly. */
#include <stdlib.h>

#include "cli_env.h"
#include "vb_dcd.h"
#include "vb_spheres.h"
#include "vb_test.h"

static int run(const char *args)
{
    char cmd[16384];
    snprintf(cmd, sizeof cmd, "%s channels %s 2>>%s/stderr.txt", bin, args, dir);
    int st = system(cmd);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static long file_size(const char *name)
{
    char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "rb");
    if (!f)
        return -1;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fclose(f);
    return n;
}

/* Reads line `row` (0 = header) of a CSV in dir into buf. */
static int csv_line(const char *name, int row, char *buf, size_t len)
{
    char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "r");
    if (!f)
        return -1;
    int r = -1;
    for (int i = 0; i <= row; i++)
        if (!fgets(buf, (int)len, f)) {
            fclose(f);
            return -1;
        }
    r = 0;
    fclose(f);
    return r;
}

static void test_gramicidin(void)
{
    char a[8192];
    snprintf(a, sizeof a,
             "%s/corpus/data/1grm_single_hole2.pdb --probe 1.0 --grid 64 -o %s/t.csv "
             "--centerlines %s/c.pdb --pymol %s/c.pml --volume %s/m.mrc --png %s/s.png "
             "--stats-file %s/st.csv",
             src, dir, dir, dir, dir, dir, dir);
    CHECK_INT(run(a), 0);
    char line[4096];
    CHECK_INT(csv_line("t.csv", 1, line, sizeof line), 0);
    long frame, model, id;
    char kind[16];
    int through;
    double len, bott, bx, by, bz, sx, sy, sz, ex, ey, ez;
    int n = sscanf(line, "%ld,%ld,%ld,%15[a-z],%d,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &frame,
                   &model, &id, kind, &through, &len, &bott, &bx, &by, &bz, &sx, &sy, &sz, &ex, &ey, &ez);
    CHECK_INT(n, 16);
    /* Row 1 is the pore, swept along the axis of the two stacked chains. */
    CHECK_STR(kind, "pore");
    CHECK_INT(through, 1);
    /* The pore runs along y from one face (y < -12) to the other (y > 12). */
    CHECK(sy * ey < 0.0 && fabs(sy) > 12.0 && fabs(ey) > 12.0);
    CHECK(len > 26.0 && len < 50.0);
    /* Bondi radii: the sweep's exact radius, 1.34 A at |y| = 9.5 (below the
     * 1.4 A probe, so the discrete channel cannot pass it). */
    CHECK_NEAR(bott, 1.337, 0.01);
    CHECK_NEAR(fabs(by), 9.49, 0.15);
    CHECK(strstr(line, "pore along the axis, open at both ends") != NULL);
    /* Outputs: MRC = 1024-byte header + 64^3 bytes; PDB and script non-empty. */
    CHECK_INT(file_size("m.mrc"), 1024 + 64 * 64 * 64);
    CHECK(file_size("c.pdb") > 100);
    CHECK(file_size("c.pml") > 50);
    CHECK(file_size("s.png") > 1000);
    CHECK_INT(csv_line("st.csv", 2, line, sizeof line), -1); /* one frame */
}

/* The README's example at the defaults (probe 1.4 A, 128^3) with HOLE's
 * radii: the pore and its radius within a voxel of HOLE's 1.198 A (it is
 * within 0.01 A), at HOLE's axial position (|s| = 9.5: the dimer has the
 * constriction twice), and HOLE's Gmacro (274.7 pS with endrad 5 A). */
static void test_readme_default(void)
{
    char a[8192], line[4096];
    snprintf(a, sizeof a,
             "%s/corpus/data/1grm_single_hole2.pdb --radii %s/papers/facet-jfa-and-channels/channels/hole_simple.radii "
             "--end-radius 5 -o %s/d.csv --profile %s/dp.csv",
             src, src, dir, dir);
    CHECK_INT(run(a), 0);
    CHECK_INT(csv_line("d.csv", 1, line, sizeof line), 0);
    long frame, model, id;
    char kind[16];
    int through;
    double len, bott, bx, by, bz;
    int n = sscanf(line, "%ld,%ld,%ld,%15[a-z],%d,%lf,%lf,%lf,%lf,%lf", &frame, &model, &id, kind,
                   &through, &len, &bott, &bx, &by, &bz);
    CHECK_INT(n, 10);
    CHECK_STR(kind, "pore");
    CHECK_NEAR(bott, 1.198, 0.02);
    CHECK_NEAR(fabs(by), 9.5, 0.1);
    const char *g = strrchr(line, ',');
    CHECK(g && fabs(atof(g + 1) - 274.7) < 0.03 * 274.7);
    /* The profile lists the pore's points first, nearest atoms named. */
    CHECK_INT(csv_line("dp.csv", 1, line, sizeof line), 0);
    CHECK(strncmp(line, "0,1,1,pore,0,", 13) == 0);
    CHECK(strstr(line, ":TRP") || strstr(line, ":LEU") || strstr(line, ":VAL") || strstr(line, ":ALA") ||
          strstr(line, ":GLY") || strstr(line, ":ETA") || strstr(line, ":FOR") || strstr(line, ":DLE") ||
          strstr(line, ":DVA"));
}

/* A synthetic pore as a user would give it: a PDB of a tube (10 rings of 16
 * carbons, 6 A from the z axis) in four chains, narrowed at z = 0 by a ring
 * of 8 carbons 2.5 A from the axis; radius 1.5 A for carbon, so the hole
 * is 1.0 A, below the 1.4 A probe. At the defaults the pore is found from
 * the chains (the 4-fold axis, z), passes the constriction, and reports
 * 1.000 A there; the discrete channels cannot pass it. */
static void test_synthetic_ring(void)
{
    char p[512], a[8192], line[4096];
    snprintf(p, sizeof p, "%s/ring.pdb", dir);
    FILE *f = fopen(p, "w");
    CHECK(f != NULL);
    if (!f)
        return;
    const double pi = 3.14159265358979323846;
    int serial = 1;
    for (int k = 0; k < 11; k++) {
        int per = k < 10 ? 16 : 8;
        for (int b = 0; b < per; b++) {
            double phi = 2.0 * pi * (b + (k < 10 ? 0.5 * (k % 2) : 0.0)) / per;
            double rc = k < 10 ? 6.0 : 2.5, z = k < 10 ? (k - 4.5) * 2.6 : 0.0;
            fprintf(f, "ATOM  %5d  C   GLY %c%4d    %8.3f%8.3f%8.3f  1.00  0.00           C\n", serial++,
                    'A' + b / (per / 4), k + 1, rc * cos(phi), rc * sin(phi), z);
        }
    }
    fprintf(f, "END\n");
    fclose(f);
    snprintf(p, sizeof p, "%s/ring.radii", dir);
    f = fopen(p, "w");
    CHECK(f != NULL);
    if (!f)
        return;
    fprintf(f, "C 1.5\n");
    fclose(f);
    snprintf(a, sizeof a, "%s/ring.pdb --radii %s/ring.radii --device ref -o %s/ring.csv", dir, dir, dir);
    CHECK_INT(run(a), 0);
    CHECK_INT(csv_line("ring.csv", 1, line, sizeof line), 0);
    long frame, model, id;
    char kind[16];
    int through;
    double len, bott, bx, by, bz;
    int n = sscanf(line, "%ld,%ld,%ld,%15[a-z],%d,%lf,%lf,%lf,%lf,%lf", &frame, &model, &id, kind,
                   &through, &len, &bott, &bx, &by, &bz);
    CHECK_INT(n, 10);
    CHECK_STR(kind, "pore");
    CHECK_INT(through, 1);
    CHECK_NEAR(bott, 1.0, 0.0011);
    CHECK_NEAR(bx, 0.0, 0.002);
    CHECK_NEAR(by, 0.0, 0.002);
    CHECK_NEAR(bz, 0.0, 0.002);
    /* No discrete channel gets through the 1.0 A hole with the 1.4 A probe. */
    for (int row = 2; csv_line("ring.csv", row, line, sizeof line) == 0; row++) {
        n = sscanf(line, "%ld,%ld,%ld,%15[a-z],%d", &frame, &model, &id, kind, &through);
        CHECK(n == 5 && !(strcmp(kind, "channel") == 0 && through));
    }
}

static void test_trajectory_and_dcd(vb_ctx *ctx)
{
    char a[8192], line[4096];
    snprintf(a, sizeof a, "%s/corpus/data/ngl_md_ascii_trj.pdb --grid 32 --frames 0:51:25 -o %s/md.csv --stats-file %s/mds.csv",
             src, dir, dir);
    CHECK_INT(run(a), 0);
    int frames = 0;
    long atoms[3] = {0, 0, 0};
    double vox[3] = {0, 0, 0};
    for (int r = 1; csv_line("mds.csv", r, line, sizeof line) == 0; r++, frames++) {
        long f, m, at, grid;
        double h, cv;
        if (sscanf(line, "%ld,%ld,%ld,%ld,%lf,%lf", &f, &m, &at, &grid, &h, &cv) == 6 && frames < 3) {
            CHECK_INT(f, 25 * frames);
            atoms[frames] = at;
            vox[frames] = cv;
        }
    }
    CHECK_INT(frames, 3);
    CHECK_INT(atoms[0], 183);

    /* The same frames through a DCD we write from the trajectory. */
    char pdb[1200], dcd[512];
    snprintf(pdb, sizeof pdb, "%s/corpus/data/ngl_md_ascii_trj.pdb", src);
    snprintf(dcd, sizeof dcd, "%s/md.dcd", dir);
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    ro.keep_water = 1;
    vb_frame_reader *rd;
    CHECK_INT(vb_frame_reader_open(ctx, pdb, &ro, &rd), VB_OK);
    vb_dcd_writer *w = NULL;
    vb_sphere_set *s;
    int model, written = 0;
    while (vb_frame_reader_next(ctx, rd, &s, &model) == VB_OK && s) {
        if (!w)
            CHECK_INT(vb_dcd_writer_open(ctx, dcd, s->n, 1.0, "ngl md", &w), VB_OK);
        CHECK_INT(vb_dcd_writer_frame(ctx, w, s->x, s->y, s->z), VB_OK);
        written++;
        vb_spheres_free(s);
    }
    vb_frame_reader_close(rd);
    CHECK_INT(vb_dcd_writer_close(ctx, w), VB_OK);
    CHECK_INT(written, 51);
    snprintf(a, sizeof a, "%s --dcd %s --grid 32 --frames 0:51:25 -o %s/dcd.csv --stats-file %s/dcds.csv",
             pdb, dcd, dir, dir);
    CHECK_INT(run(a), 0);
    frames = 0;
    for (int r = 1; csv_line("dcds.csv", r, line, sizeof line) == 0; r++, frames++) {
        long f, m, at, grid;
        double h, cv;
        if (sscanf(line, "%ld,%ld,%ld,%ld,%lf,%lf", &f, &m, &at, &grid, &h, &cv) == 6 && frames < 3) {
            CHECK_INT(at, atoms[frames]);
            /* float32 coordinates move the grid by ~1e-5 A: voxel counts agree closely. */
            CHECK(fabs(cv - vox[frames]) <= 0.02 * vox[frames] + 2);
        }
    }
    CHECK_INT(frames, 3);
    remove(dcd);
}

static void test_usage(void)
{
    char a[4096];
    snprintf(a, sizeof a, "%s/corpus/data/1grm_single_hole2.pdb --grid 100", src);
    CHECK_INT(run(a), 2);
    snprintf(a, sizeof a, "%s/corpus/data/1grm_single_hole2.pdb --frames 5:2", src);
    CHECK_INT(run(a), 2);
    snprintf(a, sizeof a, "%s/corpus/data/1grm_single_hole2.pdb --pymol x.pml", src);
    CHECK_INT(run(a), 2);
    snprintf(a, sizeof a, "%s/corpus/data/1grm_single_hole2.pdb --grid 32 --frames 3: -o /dev/null", src);
    CHECK_INT(run(a), 21); /* no such frame */
    /* A typo of a flag is an unknown option, never "needs a value". */
    snprintf(a, sizeof a, "%s/corpus/data/1grm_single_hole2.pdb --cavity", src);
    CHECK_INT(run(a), 2);
    /* A failing command leaves no partial table: a 10-atom XTC over the
     * 272-atom topology is E116 (exit 26) after -o was opened. */
    snprintf(a, sizeof a,
             "%s/corpus/data/1grm_single_hole2.pdb --traj %s/corpus/data/xtc_10x10.xtc --grid 32 "
             "-o %s/fail.csv",
             src, src, dir);
    CHECK_INT(run(a), 26);
    CHECK_INT(file_size("fail.csv"), -1);
}

/* An XTC (MDAnalysis' writer, 10 frames of the MD trajectory) over the PDB
 * as its topology: frames 0 and 9, in nm read as Angstrom. */
static void test_xtc(void)
{
    char a[8192], line[4096];
    snprintf(a, sizeof a,
             "%s/corpus/data/ngl_md_ascii_trj.pdb --traj %s/corpus/data/ngl_md_10frames.xtc "
             "--grid 32 --frames 0:10:9 -o %s/xtc.csv --stats-file %s/xtcs.csv",
             src, src, dir, dir);
    CHECK_INT(run(a), 0);
    int frames = 0;
    for (int r = 1; csv_line("xtcs.csv", r, line, sizeof line) == 0; r++, frames++) {
        long f, m, at;
        if (sscanf(line, "%ld,%ld,%ld", &f, &m, &at) == 3) {
            CHECK_INT(f, 9 * frames);
            CHECK_INT(at, 183);
        }
    }
    CHECK_INT(frames, 2);
}

int main(void)
{
    if (cli_env_open("vbc_cli") != 0)
        return 1;
    vb_ctx *ctx;
    vb_config cfg = {0, NULL};
    if (vb_open(&ctx, &cfg) != VB_OK)
        return 1;
    test_gramicidin();
    test_readme_default();
    test_synthetic_ring();
    test_trajectory_and_dcd(ctx);
    test_usage();
    test_xtc();
    vb_close(ctx);
    cli_env_close();
    VB_TEST_END();
}
