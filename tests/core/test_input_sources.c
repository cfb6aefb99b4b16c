/* Inputs as users have them (issue 17), on real files of corpus/data:
 * gzip and bzip2 copies read as the plain file, a cut one is E113; the
 * elements of a CHARMM PDB without element columns are inferred (C-alpha,
 * never calcium) and counted, or refused under --strict-elements (E112);
 * GRO coordinates become Angstrom exactly; a PSF or PDB topology with a DCD
 * gives the same frames, a count mismatch is E116; mmCIF biological
 * assemblies are built from their operators (E117 when absent); TIP4P's
 * massless virtual sites (MW) are left out with W727, in a GRO file and
 * under a trajectory alike. */
#include <sys/stat.h>

#include "input_test_util.h"
#include "vb_dcd.h"
#include "vb_frames.h"
#include "vbi_input.h"

static vb_sphere_set *read_corpus(vb_ctx *ctx, const char *rel, const vb_read_options *o, int want)
{
    vb_sphere_set *s = NULL;
    vb_read_options def;
    memset(&def, 0, sizeof def);
    CHECK_INT(vb_spheres_read_file(ctx, corpus_path(rel), o ? o : &def, &s), want);
    return s;
}

/* Every sphere equal: exact decimals, doubles, names. */
static int same_set(const vb_sphere_set *a, const vb_sphere_set *b)
{
    if (!a || !b || a->n != b->n)
        return 0;
    for (size_t i = 0; i < a->n; i++)
        if (a->ex[i].mant != b->ex[i].mant || a->ex[i].exp10 != b->ex[i].exp10 ||
            a->ez[i].mant != b->ez[i].mant || a->x[i] != b->x[i] || a->r[i] != b->r[i] ||
            strcmp(a->info[i].name, b->info[i].name) != 0)
            return 0;
    return 1;
}

static void test_compressed(vb_ctx *ctx)
{
    vb_sphere_set *plain = read_corpus(ctx, "data/1crn.pdb", NULL, VB_OK);
    vb_sphere_set *gz = read_corpus(ctx, "data/1crn.pdb.gz", NULL, VB_OK);
    vb_sphere_set *bz = read_corpus(ctx, "data/1crn.pdb.bz2", NULL, VB_OK);
    CHECK_INT(plain ? plain->n : 0, 327);
    CHECK(same_set(plain, gz));
    CHECK(same_set(plain, bz));
    vb_spheres_free(gz);
    vb_spheres_free(bz);
    vb_spheres_free(plain);

    /* The gzip file cut in half: damaged data, named, never "no spheres". */
    char path[] = "/tmp/vb_cut_XXXXXX";
    int fd = mkstemp(path);
    FILE *in = fopen(corpus_path("data/1crn.pdb.gz"), "rb");
    unsigned char buf[5000];
    size_t n = in ? fread(buf, 1, sizeof buf, in) : 0;
    FILE *out = fdopen(fd, "wb");
    fwrite(buf, 1, n, out);
    fclose(out);
    if (in)
        fclose(in);
    vb_sphere_set *s = NULL;
    vb_read_options o;
    memset(&o, 0, sizeof o);
    CHECK_INT(vb_spheres_read_file(ctx, path, &o, &s), VB_EINPUT_COMPRESSED);
    CHECK(s == NULL);
    CHECK(strstr(vb_errmsg(ctx), path) != NULL);
    remove(path);
}

/* adk_open.pdb: CHARMM output, columns 77-78 blank, names left-justified
 * ("CA  " is the C-alpha): 3341 atoms, each element inferred. */
static void test_inferred_elements(void)
{
    FILE *diag;
    vb_ctx *ctx = open_ctx(&diag);
    vb_sphere_set *s = read_corpus(ctx, "data/adk_open.pdb.gz", NULL, VB_OK);
    size_t ca = 0, calcium = 0;
    for (size_t i = 0; s && i < s->n; i++) {
        if (strcmp(s->info[i].name, "CA") == 0) {
            ca++;
            CHECK(strcmp(s->info[i].element, "C") == 0);
            CHECK(s->r[i] == 1.70);
        }
        calcium += strcmp(s->info[i].element, "CA") == 0;
    }
    CHECK_INT(s ? s->n : 0, 3341);
    CHECK_INT(ca, 214);
    CHECK_INT(calcium, 0);
    const char *t = diag_text(diag);
    CHECK(strstr(t, "W714") != NULL);
    CHECK(strstr(t, "W715") != NULL && strstr(t, "3341 atoms without an element") != NULL);
    CHECK(strstr(t, "W716") == NULL);
    vb_spheres_free(s);

    /* --strict-elements refuses the first atom (line 5 after 4 header lines). */
    vb_read_options o;
    memset(&o, 0, sizeof o);
    o.strict_elements = 1;
    s = read_corpus(ctx, "data/adk_open.pdb.gz", &o, VB_EINPUT_INFERRED);
    CHECK(s == NULL);
    CHECK(strstr(vb_errmsg(ctx), "adk_open.pdb.gz:") != NULL);
    CHECK(strstr(vb_errmsg(ctx), "'N' of residue 'MET'") != NULL);
    vb_close(ctx);
    fclose(diag);

    /* The convention where a file keeps it: " CA " in ALA is carbon, "CA  "
     * in residue CA is calcium, a left-justified "FE  " in HEM is iron. */
    ctx = open_ctx(&diag);
    const char *pdb = "ATOM      1  N   ALA A   1       1.000   2.000   3.000  1.00 10.00\n"
                      "ATOM      2  CA  ALA A   1       2.000   2.000   3.000  1.00 10.00\n"
                      "HETATM    3 CA    CA A   2       5.000   2.000   3.000  1.00 10.00\n"
                      "HETATM    4 FE   HEM A   3       8.000   2.000   3.000  1.00 10.00\n"
                      "HETATM    5 CL   CLA A   4      11.000   2.000   3.000  1.00 10.00\n";
    CHECK_INT(read_text(ctx, "c.pdb", pdb, NULL, &s), VB_OK);
    static const char *const want[] = {"N", "C", "CA", "FE", "CL"};
    for (size_t i = 0; s && i < 5; i++)
        CHECK(strcmp(s->info[i].element, want[i]) == 0);
    t = diag_text(diag);
    CHECK(strstr(t, "W716") != NULL && strstr(t, "c.pdb:4:") != NULL);
    CHECK(strstr(t, "5 atoms without an element") != NULL);
    vb_spheres_free(s);
    vb_close(ctx);
    fclose(diag);
}

static void test_gro(vb_ctx *ctx)
{
    /* MDAnalysis' test.gro (bzip2): nm to Angstrom by the exponent. */
    vb_sphere_set *s = read_corpus(ctx, "data/mda_test.gro.bz2", NULL, VB_OK);
    CHECK_INT(s ? s->n : 0, 5);
    if (s && s->n == 5) {
        CHECK_DEC(s->ex[1], 3, 0); /* 0.300 nm = 3 A */
        CHECK(s->x[1] == 3.0 && s->y[1] == 4.0 && s->z[1] == 5.0);
        CHECK(strcmp(s->info[1].resname, "ARG") == 0 && strcmp(s->info[1].element, "C") == 0);
    }
    vb_spheres_free(s);
    /* Adenylate kinase in OPLS-AA: the protein and four Na+ ions. */
    s = read_corpus(ctx, "data/adk_oplsaa_protein.gro.gz", NULL, VB_OK);
    CHECK_INT(s ? s->n : 0, 3345);
    if (s && s->n == 3345) {
        CHECK_DEC(s->ex[0], 5202, -2); /* 5.202 nm = 52.02 A */
        CHECK(s->x[0] == 52.02 && s->z[0] == 31.55);
        CHECK(strcmp(s->info[0].element, "N") == 0);
        CHECK(strcmp(s->info[3344].element, "NA") == 0);
        CHECK(strcmp(s->info[3340].element, "O") == 0);
    }
    vb_spheres_free(s);
}

/* Frames of the 2-frame DCD over a topology; returns the frames met. */
static int dcd_frames(vb_ctx *ctx, const char *topo, vb_sphere_set **first)
{
    vb_frame_source *F = NULL;
    vb_read_options o;
    memset(&o, 0, sizeof o);
    o.keep_water = 1;
    char dcd[4096];
    snprintf(dcd, sizeof dcd, "%s", corpus_path("data/adk_dims_2frames.dcd"));
    if (vb_frame_source_open(ctx, corpus_path(topo), dcd, &o, &F) != VB_OK)
        return -1;
    int frames = 0, model;
    vb_sphere_set *s;
    while (vb_frame_source_next(ctx, F, &s, &model) == VB_OK && s) {
        if (frames++ == 0 && first)
            *first = s;
        else
            vb_spheres_free(s);
    }
    vb_frame_source_close(F);
    return frames;
}

static void test_psf_dcd(vb_ctx *ctx)
{
    vb_sphere_set *a = NULL, *b = NULL;
    int fa = 0;
    /* A PSF alone holds no coordinates: E114 naming what to give. */
    vb_frame_source *F = NULL;
    vb_read_options o;
    memset(&o, 0, sizeof o);
    CHECK_INT(vb_frame_source_open(ctx, corpus_path("data/adk_natom.psf.gz"), NULL, &o, &F),
              VB_EINPUT_NOSPHERES);
    char dcd[4096];
    snprintf(dcd, sizeof dcd, "%s", corpus_path("data/adk_dims_2frames.dcd"));
    CHECK_INT(vb_frame_source_open(ctx, corpus_path("data/adk_natom.psf.gz"), dcd, &o, &F), VB_OK);
    int model;
    while (F && vb_frame_source_next(ctx, F, &a, &model) == VB_OK && a) {
        if (fa++ == 0)
            break;
    }
    vb_frame_source_close(F);
    CHECK_INT(fa, 1);
    CHECK_INT(dcd_frames(ctx, "data/adk_open.pdb.gz", &b), 2);
    /* The PSF (elements from masses) and the PDB (inferred) agree. */
    CHECK_INT(a ? a->n : 0, 3341);
    CHECK_INT(b ? b->n : 0, 3341);
    int same = a && b && a->n == b->n;
    for (size_t i = 0; same && i < a->n; i++)
        same = a->x[i] == b->x[i] && a->z[i] == b->z[i] && a->r[i] == b->r[i] &&
               strcmp(a->info[i].element, b->info[i].element) == 0;
    CHECK(same);
    vb_spheres_free(a);
    vb_spheres_free(b);
    /* A 10-atom XTC on the 3341-atom topology: E116. */
    snprintf(dcd, sizeof dcd, "%s", corpus_path("data/xtc_10x10.xtc"));
    F = NULL;
    CHECK_INT(vb_frame_source_open(ctx, corpus_path("data/adk_natom.psf.gz"), dcd, &o, &F),
              VB_EINPUT_TOPOLOGY);
    CHECK(F == NULL);
}

static void test_assembly(vb_ctx *ctx)
{
    vb_read_options o;
    memset(&o, 0, sizeof o);
    o.assembly = 1;
    /* Crambin: assembly 1 is the identity on chain A. */
    vb_sphere_set *au = read_corpus(ctx, "data/1crn.cif", NULL, VB_OK);
    vb_sphere_set *s = read_corpus(ctx, "data/1crn.cif", &o, VB_OK);
    CHECK(same_set(au, s));
    vb_spheres_free(s);
    /* EV71 capsid: 12 crystal operators on the 15 chains of the asymmetric
     * unit (5 protomers): 60 protomers, 317,160 atoms; copy 1 is the
     * asymmetric unit, copy 2 (x, y, z) -> (-x, -y, z) exactly. */
    vb_sphere_set *cap = read_corpus(ctx, "data/4yvs_ev71_capsid.cif", NULL, VB_OK);
    s = read_corpus(ctx, "data/4yvs_ev71_capsid.cif", &o, VB_OK);
    CHECK_INT(cap ? cap->n : 0, 26430);
    CHECK_INT(s ? s->n : 0, 12 * 26430);
    if (cap && s && s->n == 12 * cap->n) {
        size_t n = cap->n, bad = 0;
        for (size_t i = 0; i < n; i++) {
            bad += s->ex[i].mant != cap->ex[i].mant || s->x[i] != cap->x[i];
            bad += s->ex[n + i].mant != -cap->ex[i].mant || s->y[n + i] != -cap->y[i] ||
                   s->ez[n + i].mant != cap->ez[i].mant || s->r[n + i] != cap->r[i];
        }
        CHECK_INT(bad, 0);
    }
    vb_spheres_free(s);
    vb_spheres_free(cap);
    /* Too many spheres fails before building them. */
    o.max_spheres = 300000;
    s = read_corpus(ctx, "data/4yvs_ev71_capsid.cif", &o, VB_EINPUT_TOOLARGE);
    CHECK(s == NULL);
    o.max_spheres = 0;
    /* Absent assembly; an assembly of a PDB file. */
    o.assembly = 2;
    s = read_corpus(ctx, "data/1crn.cif", &o, VB_EINPUT_ASSEMBLY);
    CHECK(s == NULL && strstr(vb_errmsg(ctx), "1crn.cif") != NULL);
    o.assembly = 1;
    s = read_corpus(ctx, "data/1crn.pdb", &o, VB_EINPUT_ASSEMBLY);
    CHECK(s == NULL);
    vb_spheres_free(au);
}

/* Two TIP4P waters (OW HW1 HW2 MW) beside two protein atoms, in GROMACS'
 * layout (nm). */
static const char tip4p_gro[] =
    "tip4p\n"
    "   10\n"
    "    1ALA      N    1   0.100   0.100   0.100\n"
    "    1ALA     CA    2   0.250   0.100   0.100\n"
    "    2SOL     OW    3   0.600   0.600   0.600\n"
    "    2SOL    HW1    4   0.660   0.600   0.600\n"
    "    2SOL    HW2    5   0.580   0.660   0.600\n"
    "    2SOL     MW    6   0.610   0.610   0.600\n"
    "    3SOL     OW    7   0.900   0.200   0.300\n"
    "    3SOL    HW1    8   0.960   0.200   0.300\n"
    "    3SOL    HW2    9   0.880   0.260   0.300\n"
    "    3SOL     MW   10   0.910   0.210   0.300\n"
    "   1.50000   1.50000   1.50000\n";

/* A water model's virtual site is a point charge: read as an atom of the
 * default radius it swallowed its oxygen (W707, W701). Left out with W727
 * where water is kept, read with keep_virtual_sites = 1; under a trajectory
 * the topology keeps its rows (the frames' atoms must match) and the frame
 * source leaves them out, with W727 and no element warning. */
static void test_virtual_sites(void)
{
    FILE *diag;
    vb_ctx *ctx = open_ctx(&diag);
    vb_read_options o;
    memset(&o, 0, sizeof o);
    vb_sphere_set *s = NULL;
    CHECK_INT(read_text(ctx, "w.gro", tip4p_gro, &o, &s), VB_OK);
    CHECK_INT(s ? s->n : 0, 2); /* water (MW included) dropped */
    vb_spheres_free(s);
    o.keep_water = 1;
    CHECK_INT(read_text(ctx, "w.gro", tip4p_gro, &o, &s), VB_OK);
    CHECK_INT(s ? s->n : 0, 8);
    int no_site = 1;
    for (size_t i = 0; s && i < s->n; i++)
        no_site &= strcmp(s->info[i].name, "MW") != 0;
    CHECK(no_site);
    CHECK(s && s->n == 8 && strcmp(s->info[6].name, "HW1") == 0 && s->line[6] == 10);
    vb_spheres_free(s);
    const char *w = diag_text(diag);
    CHECK(strstr(w, "W727: w.gro: 2 massless virtual sites of a water model") != NULL);
    CHECK(strstr(w, "W707") == NULL);
    o.keep_virtual_sites = 1;
    CHECK_INT(read_text(ctx, "w.gro", tip4p_gro, &o, &s), VB_OK);
    CHECK_INT(s ? s->n : 0, 10);
    CHECK(s && s->n == 10 && strcmp(s->info[5].name, "MW") == 0);
    vb_spheres_free(s);
    vb_close(ctx);

    /* The same under a 1-frame DCD (Angstrom, the GRO's positions). */
    ctx = open_ctx(&diag);
    char top[64], dcd[64];
    strcpy(top, temp_file(tip4p_gro));
    char gro[80];
    snprintf(gro, sizeof gro, "%s.gro", top);
    CHECK_INT(rename(top, gro), 0);
    strcpy(dcd, temp_file(""));
    const double x[10] = {1, 2.5, 6, 6.6, 5.8, 6.1, 9, 9.6, 8.8, 9.1};
    const double y[10] = {1, 1, 6, 6, 6.6, 6.1, 2, 2, 2.6, 2.1};
    const double z[10] = {1, 1, 6, 6, 6, 6, 3, 3, 3, 3};
    vb_dcd_writer *wr = NULL;
    CHECK_INT(vb_dcd_writer_open(ctx, dcd, 10, 1.0, "tip4p", &wr), VB_OK);
    CHECK_INT(vb_dcd_writer_frame(ctx, wr, x, y, z), VB_OK);
    CHECK_INT(vb_dcd_writer_close(ctx, wr), VB_OK);
    memset(&o, 0, sizeof o);
    o.keep_water = 1;
    vb_frame_source *F = NULL;
    int model = 0;
    CHECK_INT(vb_frame_source_open(ctx, gro, dcd, &o, &F), VB_OK);
    CHECK_INT(F ? vb_frame_source_next(ctx, F, &s, &model) : -1, VB_OK);
    CHECK_INT(s ? s->n : 0, 8);
    CHECK(s && s->n == 8 && s->x[5] == 9.0 && s->y[4] == 6.599999904632568 &&
          strcmp(s->info[5].name, "OW") == 0);
    vb_spheres_free(s);
    vb_frame_source_close(F);
    w = diag_text(diag);
    CHECK(strstr(w, "2 massless virtual sites of a water model") != NULL);
    CHECK(strstr(w, "W707") == NULL && strstr(w, "W701") == NULL);
    remove(gro);
    remove(dcd);
    vb_close(ctx);
}

/* Elements of metal atoms named as their element in residues that are no
 * ion of the table (YiiP's ZN in ZNM read as "Z" before, heme's FE in a GRO
 * as fluorine) and a C-alpha in a modified residue whose name begins with
 * CA (CAS: carbon, not calcium). */
static void test_metal_names(void)
{
    static const char gro[] =
        "metals\n"
        "    4\n"
        "    1ZNM     ZN    1   0.100   0.100   0.100\n"
        "    2MGX     MG    2   0.500   0.100   0.100\n"
        "    3CAS     CA    3   0.900   0.100   0.100\n"
        "    4HEM     FE    4   1.300   0.100   0.100\n"
        "   2.00000   2.00000   2.00000\n";
    FILE *diag;
    vb_ctx *ctx = open_ctx(&diag);
    vb_read_options o;
    memset(&o, 0, sizeof o);
    vb_sphere_set *s = NULL;
    CHECK_INT(read_text(ctx, "m.gro", gro, &o, &s), VB_OK);
    CHECK_INT(s ? s->n : 0, 4);
    if (s && s->n == 4) {
        CHECK_STR(s->info[0].element, "ZN");
        CHECK_STR(s->info[1].element, "MG");
        CHECK_STR(s->info[2].element, "C");
        CHECK_STR(s->info[3].element, "FE"); /* was F, fluorine, without columns */
    }
    CHECK(strstr(diag_text(diag), "W707") == NULL);
    CHECK(strstr(diag_text(diag), "W715: m.gro: 4 atoms without an element") != NULL);
    vb_spheres_free(s);
    vb_close(ctx);
}

/* vbi_infer_element_memo answers as vbi_infer_element, without columns and
 * with PDB name columns under each layout (their hydrogens' four-column
 * names, left- and right-justified metals), for the keys met in turn many
 * times (more keys than slots: slots shared and overwritten), ions, metals,
 * water and lipids among them. */
static void test_infer_memo(void)
{
    static const char *const names[] = {"OW", "HW1", "HW2", "MW", "CA", "ZN", "NA", "CL", "FE",
                                        "C1", "P", "O11", "1HG2", "SE", "MG", "N", "OC1", "K"};
    static const char *const res[] = {"SOL", "ALA", "ZN", "NA+", "CLA", "HEM", "POPE",
                                      "MSE", "MG", "LYS", "K", "CAS"};
    vbi_infer_memo *m = calloc(1, sizeof *m);
    size_t bad = 0, hits = 0;
    uint32_t x = 12345;
    for (int t = 0; t < 20000; t++) {
        x = x * 1103515245u + 12345u;
        const char *nm = names[(x >> 8) % 18], *rn = res[(x >> 16) % 12];
        char a[4], b[4];
        /* Without columns; with columns: the name where it starts (column
         * 13 or 14), or as four columns, under the file's layout. */
        const char *n4 = NULL;
        char cols[5];
        int lay = VBI_LAYOUT_UNKNOWN, how4 = (int)((x >> 24) % 4);
        if (how4 > 0) {
            snprintf(cols, sizeof cols, how4 == 1 ? " %-3.3s" : "%-4.4s", nm);
            n4 = cols;
            lay = (int)((x >> 4) % 3); /* VBI_LAYOUT_UNKNOWN, _PDB, _LEFT */
        }
        int ha = vbi_infer_element_memo(m, n4, nm, rn, lay, a);
        int hb = vbi_infer_element(n4, nm, rn, lay, b);
        bad += ha != hb || strcmp(a, b) != 0;
        hits += ha == VBI_INFER_ALIGNMENT;
    }
    CHECK(hits > 100); /* two-letter elements by the columns (FE, ZN, CL) */
    hits = 0;
    for (size_t k = 0; k < sizeof m->e / sizeof m->e[0]; k++)
        hits += m->e[k].used;
    CHECK_INT(bad, 0);
    CHECK(hits > 40);
    free(m);
}

/* vb_spheres_count_hint: an XYZR file's bytes over its longest head line
 * (the spheres, when every line is as long), another text format's bytes
 * over VB_BYTES_PER_SPHERE_MAX, 0 for compressed files and stdin. */
static void test_count_hint(void)
{
    char path[] = "/tmp/vb_hint_XXXXXX";
    int fd = mkstemp(path);
    FILE *out = fdopen(fd, "wb");
    fputs("# 3000 balls\n", out); /* shorter than a sphere's line */
    for (int i = 0; i < 3000; i++)
        fprintf(out, "%6.3f %6.3f %6.3f 1.70\n", 10.0 + i % 9, 20.0 + i % 7, 30.0 + i % 5);
    fclose(out);
    CHECK_INT(vb_spheres_count_hint(path), 3000);
    remove(path);
    struct stat st;
    CHECK(stat(corpus_path("data/1crn.pdb"), &st) == 0);
    CHECK_INT(vb_spheres_count_hint(corpus_path("data/1crn.pdb")),
              (size_t)st.st_size / VB_BYTES_PER_SPHERE_MAX);
    CHECK_INT(vb_spheres_count_hint(corpus_path("data/1crn.pdb.gz")), 0);
    CHECK_INT(vb_spheres_count_hint("-"), 0);
    CHECK_INT(vb_spheres_count_hint("/nonexistent/vb_hint"), 0);
}

int main(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    test_infer_memo();
    test_count_hint();
    test_compressed(ctx);
    test_inferred_elements();
    test_gro(ctx);
    test_psf_dcd(ctx);
    test_assembly(ctx);
    test_virtual_sites();
    test_metal_names();
    vb_close(ctx);
    VB_TEST_END();
}
