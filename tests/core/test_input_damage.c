/* Damaged and unusual input (issue 18, items 1, 4 and 6): each is read
 * correctly or reported with a numbered diagnostic, never silently wrong.
 * Exact duplicates whose decimals differ in padding or spelling; a DCD that
 * claims 2^31 - 1 atoms, DCDs ending in stray bytes; NUL bytes, a UTF-8
 * byte-order mark, CR-only line ends, a truncated last MODEL and an altloc
 * block that comes back after other residues, through the buffer readers and
 * the frame reader. Issue 28: a GRO atom count that disagrees with the atom
 * lines (item 2; the box line is checked, and never read as an atom: no
 * W707, item 9). */
#include <stdint.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "input_test_util.h"
#include "vb_dcd.h"
#include "vb_frames.h"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VB_TEST_HAS_ASAN 1
#endif
#endif

#define ATOM(serial, name, alt, res, seq, x, y, z, el)                                            \
    "ATOM  " serial " " name alt res " A" seq "    " x y z "  1.00 10.00          " el "\n"

/* Four carbons and an oxygen, each line 80 columns. */
#define PDB_C1 ATOM("    1", " C  ", " ", "ALA", "   1", "   0.000", "   0.000", "   0.000", " C")
#define PDB_C2 ATOM("    2", " C  ", " ", "ALA", "   2", "   3.000", "   0.000", "   0.000", " C")
#define PDB_C3 ATOM("    3", " C  ", " ", "ALA", "   3", "   0.000", "   3.000", "   0.000", " C")
#define PDB_C4 ATOM("    4", " C  ", " ", "ALA", "   4", "   0.000", "   0.000", "   3.000", " C")
#define PDB_O5 ATOM("    5", " O  ", " ", "SER", "   5", "   2.000", "   2.000", "   2.000", " O")

static vb_sphere_set *alloc_set(size_t n, unsigned char fill)
{
    vb_sphere_set *s = calloc(1, sizeof *s);
    s->n = n;
    double **d[4] = {&s->x, &s->y, &s->z, &s->r};
    vb_decimal **e[4] = {&s->ex, &s->ey, &s->ez, &s->er};
    for (int k = 0; k < 4; k++) {
        *d[k] = calloc(n, sizeof(double));
        *e[k] = malloc(n * sizeof(vb_decimal));
        memset(*e[k], fill, n * sizeof(vb_decimal));
    }
    s->line = calloc(n, sizeof *s->line);
    s->contained = calloc(n, 1);
    return s;
}

static void set_sphere(vb_sphere_set *s, size_t i, const vb_decimal v[4])
{
    vb_decimal *e[4] = {s->ex, s->ey, s->ez, s->er};
    double *d[4] = {s->x, s->y, s->z, s->r};
    for (int k = 0; k < 4; k++) {
        e[k][i].mant = v[k].mant;       /* the padding keeps the fill byte */
        e[k][i].exp10 = v[k].exp10;
        d[k][i] = (double)v[k].mant * pow(10.0, v[k].exp10);
    }
    s->line[i] = (long)i + 1;
}

/* Item 1: duplicates are equal values, whatever the padding bytes of
 * vb_decimal or the spelling (1.52 and 1.520). */
static void test_duplicates(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    const vb_decimal sph[5][4] = {{{0, 0}, {0, 0}, {0, 0}, {152, -2}},
                                  {{3, 0}, {0, 0}, {0, 0}, {17, -1}},
                                  {{0, 0}, {3, 0}, {0, 0}, {17, -1}},
                                  {{0, 0}, {0, 0}, {3, 0}, {17, -1}},
                                  {{0, 0}, {0, 0}, {0, 0}, {1520, -3}}};
    vb_sphere_set *s = alloc_set(5, 0xab);
    for (size_t i = 0; i < 5; i++)
        set_sphere(s, i, sph[i]);
    memset(&s->er[4], 0x00, sizeof s->er[4]); /* other padding, same value */
    s->er[4].mant = 1520;
    s->er[4].exp10 = -3;
    s->source = strdup("dup");
    CHECK_ERROR(ctx, vb_spheres_validate(ctx, s, 4), VB_EINPUT_DUPLICATE, "dup:5:");
    CHECK(strstr(vb_errmsg(ctx), "sphere 4 is identical to sphere 0 at line 1") != NULL);
    vb_spheres_free(s);

    /* As the issue found it: the radius of element Q from a --radii row, the
     * same as O's from the table, at O's coordinates. */
    vb_radii_table *radii = NULL;
    char path[64];
    strcpy(path, temp_file("Q 1.52\n"));
    CHECK_INT(vb_radii_load(ctx, path, &radii), VB_OK);
    remove(path);
    vb_read_options o;
    memset(&o, 0, sizeof o);
    o.radii = radii;
    const char *pdb = PDB_O5 PDB_C1 PDB_C2 PDB_C3 PDB_C4
        ATOM("    6", " Q  ", " ", "ALA", "   6", "   2.000", "   2.000", "   2.000", " Q");
    CHECK_ERROR(ctx, read_validate(ctx, "q.pdb", pdb, &o, 4), VB_EINPUT_DUPLICATE, "q.pdb:6:");
    vb_radii_free(radii);
    vb_close(ctx);
}

static void put_record(FILE *f, const void *p, int32_t len)
{
    fwrite(&len, 4, 1, f);
    fwrite(p, 1, (size_t)len, f);
    fwrite(&len, 4, 1, f);
}

/* A CHARMM DCD header (196 bytes) announcing na atoms and no frame. */
static void write_dcd_header(const char *path, int32_t na)
{
    FILE *f = fopen(path, "wb");
    unsigned char hdr[84];
    memset(hdr, 0, sizeof hdr);
    memcpy(hdr, "CORD", 4);
    int32_t charmm = 24;
    memcpy(hdr + 4 + 19 * 4, &charmm, 4);
    put_record(f, hdr, 84);
    char title[84];
    int32_t nt = 1;
    memcpy(title, &nt, 4);
    memset(title + 4, ' ', 80);
    put_record(f, title, 84);
    put_record(f, &na, 4);
    fclose(f);
}

/* Opens path and reads every frame; returns the frames read, -1 on an error
 * (its code in *rc). */
static long read_dcd_frames(vb_ctx *ctx, const char *path, size_t na, int *rc)
{
    vb_dcd *d = NULL;
    *rc = vb_dcd_open(ctx, path, &d);
    if (*rc != VB_OK)
        return -1;
    double *xyz = malloc(3 * na * sizeof *xyz);
    long frames = 0;
    for (int got = 1; got;) {
        *rc = vb_dcd_next(ctx, d, xyz, xyz + na, xyz + 2 * na, NULL, &got);
        if (*rc != VB_OK) {
            frames = -1;
            break;
        }
        frames += got;
    }
    free(xyz);
    vb_dcd_close(d);
    return frames;
}

/* Item 4: 196 bytes that claim 2^31 - 1 atoms open without a frame buffer
 * (the reader sized it to the claim before, and used the reader after
 * freeing it when that allocation failed). Run with the address space
 * bounded to 2 GiB where no sanitizer needs more, so the old allocation of
 * 8 GiB fails as it would on a small machine. */
static void test_dcd_huge_claim(void)
{
    char path[64];
    strcpy(path, temp_file(""));
    write_dcd_header(path, INT32_MAX);
    pid_t pid = fork();
    if (pid == 0) {
#if !defined(__SANITIZE_ADDRESS__) && !defined(VB_TEST_HAS_ASAN)
        struct rlimit lim = {(rlim_t)2 << 30, (rlim_t)2 << 30};
        setrlimit(RLIMIT_AS, &lim);
#endif
        vb_ctx *ctx = open_ctx(NULL);
        int rc;
        long frames = read_dcd_frames(ctx, path, 0, &rc);
        vb_close(ctx);
        _exit(frames == 0 && rc == VB_OK ? 0 : 1);
    }
    int status = -1;
    waitpid(pid, &status, 0);
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    remove(path);
}

/* Item 6: stray bytes after the last frame, fewer than 4 (no marker) or more
 * (a marker that does not match), are reported with W801. */
static void test_dcd_stray_bytes(void)
{
    FILE *diag;
    vb_ctx *ctx = open_ctx(&diag);
    char path[64];
    strcpy(path, temp_file(""));
    const size_t na = 3;
    const double x[3] = {1, 2, 3}, y[3] = {4, 5, 6}, z[3] = {7, 8, 9};
    const size_t stray[2] = {3, 10};
    for (int k = 0; k < 2; k++) {
        vb_dcd_writer *w = NULL;
        CHECK_INT(vb_dcd_writer_open(ctx, path, na, 1.0, "stray", &w), VB_OK);
        CHECK_INT(vb_dcd_writer_frame(ctx, w, x, y, z), VB_OK);
        CHECK_INT(vb_dcd_writer_frame(ctx, w, x, y, z), VB_OK);
        CHECK_INT(vb_dcd_writer_close(ctx, w), VB_OK);
        FILE *f = fopen(path, "ab");
        for (size_t i = 0; i < stray[k]; i++)
            fputc(0x5a, f);
        fclose(f);
        int rc;
        CHECK_INT(read_dcd_frames(ctx, path, na, &rc), 2);
        CHECK_INT(rc, VB_OK);
        char want[160];
        snprintf(want, sizeof want, "W801: %s: DCD ends with %zu bytes after frame 2", path,
                 stray[k]);
        CHECK(strstr(diag_text(diag), want) != NULL);
    }
    remove(path);
    vb_close(ctx);
}

/* Item 6: a NUL byte in a coordinate field is an error naming the line; it
 * used to end the field ("   1\0999" read as 1). */
static void test_nul_byte(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    static const char line3[] =
        ATOM("    3", " C  ", " ", "ALA", "   3", "   1\0999", "   0.000", "   0.000", " C");
    const char *head = PDB_C1 PDB_C2;
    size_t nh = strlen(head), n3 = sizeof line3 - 1, len = nh + n3;
    char buf[512];
    memcpy(buf, head, nh);
    memcpy(buf + nh, line3, n3);
    vb_sphere_set *s = NULL;
    CHECK_ERROR(ctx, vb_spheres_read_buffer(ctx, "nul.pdb", buf, len, NULL, &s),
                VB_EINPUT_MALFORMED, "nul.pdb:3: NUL byte in column 35");
    CHECK(s == NULL);

    /* Through the frame reader (streamed PDB) too. */
    char path[64];
    strcpy(path, temp_file(""));
    FILE *f = fopen(path, "wb");
    fwrite(buf, 1, len, f);
    fclose(f);
    vb_frame_reader *rd = NULL;
    CHECK_INT(vb_frame_reader_open(ctx, path, NULL, &rd), VB_OK);
    int model;
    char prefix[96];
    snprintf(prefix, sizeof prefix, "%s:3: NUL byte", path);
    if (rd)
        CHECK_ERROR(ctx, vb_frame_reader_next(ctx, rd, &s, &model), VB_EINPUT_MALFORMED, prefix);
    vb_frame_reader_close(rd);
    remove(path);
    vb_close(ctx);
}

/* Item 6: a byte-order mark does not hide the first atom, in PDB and PQR. */
static void test_bom(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    vb_sphere_set *s = NULL;
    CHECK_INT(read_text(ctx, "bom.pdb", "\xef\xbb\xbf" PDB_C1 PDB_C2 PDB_C3 PDB_C4, NULL, &s),
              VB_OK);
    CHECK_INT(s ? s->n : 0, 4);
    if (s) {
        CHECK_INT(s->line[0], 1);
        CHECK_DEC(s->ex[1], 3, 0);
    }
    vb_spheres_free(s);
    const char *pqr = "\xef\xbb\xbf"
                      "ATOM      1  N   ALA A   1       1.000   2.000   3.000 -0.30 1.55\n"
                      "ATOM      2  CA  ALA A   1       2.000   2.000   3.000  0.10 1.70\n";
    CHECK_INT(read_text(ctx, "bom.pqr", pqr, NULL, &s), VB_OK);
    CHECK_INT(s ? s->n : 0, 2);
    if (s)
        CHECK_DEC(s->er[0], 155, -2);
    vb_spheres_free(s);

    char path[64];
    strcpy(path, temp_file("\xef\xbb\xbf" PDB_C1 PDB_C2 PDB_C3));
    vb_frame_reader *rd = NULL;
    int model;
    CHECK_INT(vb_frame_reader_open(ctx, path, NULL, &rd), VB_OK);
    CHECK_INT(vb_frame_reader_next(ctx, rd, &s, &model), VB_OK);
    CHECK_INT(s ? s->n : 0, 3);
    vb_spheres_free(s);
    vb_frame_reader_close(rd);
    remove(path);
    vb_close(ctx);
}

/* Copies text with every "\n" replaced by "\r" (static buffer). */
static const char *cr_only(const char *text)
{
    static char buf[4096];
    size_t n = strlen(text);
    for (size_t i = 0; i <= n; i++)
        buf[i] = text[i] == '\n' ? '\r' : text[i];
    return buf;
}

/* Item 6: CR-only line ends (old Mac OS) keep every atom and line number,
 * in every text format and through the frame reader. */
static void test_cr_only(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    vb_sphere_set *s = NULL;
    CHECK_INT(read_text(ctx, "cr.pdb", cr_only(PDB_C1 PDB_C2 PDB_C3 PDB_C4 PDB_O5), NULL, &s),
              VB_OK);
    CHECK_INT(s ? s->n : 0, 5);
    if (s && s->n == 5) {
        CHECK_INT(s->line[4], 5);
        CHECK_DEC(s->ez[3], 3, 0);
        CHECK_DEC(s->er[4], 152, -2);
    }
    vb_spheres_free(s);
    CHECK_INT(read_text(ctx, "cr.xyzr", cr_only("0 0 0 1\n1 0 0 1\n0 1 0 1\n0 0 1 1.5\n"), NULL,
                        &s),
              VB_OK);
    CHECK_INT(s ? s->n : 0, 4);
    if (s && s->n == 4)
        CHECK_DEC(s->er[3], 15, -1);
    vb_spheres_free(s);
    const char *cif = "data_x\nloop_\n_atom_site.group_PDB\n_atom_site.type_symbol\n"
                      "_atom_site.Cartn_x\n_atom_site.Cartn_y\n_atom_site.Cartn_z\n"
                      "# a comment\nATOM C 0 0 0\nATOM C 3 0 0\nATOM O 0 3 0\n";
    CHECK_INT(read_text(ctx, "cr.cif", cr_only(cif), NULL, &s), VB_OK);
    CHECK_INT(s ? s->n : 0, 3);
    if (s && s->n == 3) {
        CHECK_INT(s->line[2], 11);
        CHECK_DEC(s->er[2], 152, -2);
    }
    vb_spheres_free(s);

    /* Two models, streamed. */
    char path[64];
    strcpy(path, temp_file(cr_only("MODEL        1\n" PDB_C1 PDB_C2 "ENDMDL\n"
                                   "MODEL        2\n" PDB_C3 PDB_C4 PDB_O5 "ENDMDL\nEND\n")));
    vb_frame_reader *rd = NULL;
    int model = 0;
    CHECK_INT(vb_frame_reader_open(ctx, path, NULL, &rd), VB_OK);
    const size_t want[3] = {2, 3, 0};
    const long first_line[2] = {2, 6};
    for (int k = 0; rd && k < 3; k++) {
        CHECK_INT(vb_frame_reader_next(ctx, rd, &s, &model), VB_OK);
        CHECK_INT(s ? s->n : 0, want[k]);
        if (s && k < 2) {
            CHECK_INT(model, k + 1);
            CHECK_INT(s->line[0], first_line[k]);
        }
        vb_spheres_free(s);
    }
    vb_frame_reader_close(rd);
    remove(path);
    vb_close(ctx);
}

/* Item 6: a last MODEL that the input ends inside (no ENDMDL, no END) is
 * read with warning W735 naming its MODEL line; a MODEL closed by the next
 * MODEL, or by END, is not. */
static void test_truncated_model(void)
{
    FILE *diag;
    vb_ctx *ctx = open_ctx(&diag);
    char path[64];
    strcpy(path, temp_file("MODEL        1\n" PDB_C1 PDB_C2 PDB_C3 "ENDMDL\n"
                           "MODEL        2\n" PDB_C1 PDB_C2));
    vb_frame_reader *rd = NULL;
    vb_sphere_set *s = NULL;
    int model;
    CHECK_INT(vb_frame_reader_open(ctx, path, NULL, &rd), VB_OK);
    size_t sizes[3] = {3, 2, 0};
    for (int k = 0; k < 3; k++) {
        CHECK_INT(vb_frame_reader_next(ctx, rd, &s, &model), VB_OK);
        CHECK_INT(s ? s->n : 0, sizes[k]);
        vb_spheres_free(s);
    }
    vb_frame_reader_close(rd);
    char want[128];
    snprintf(want, sizeof want, "W735: %s:6: the input ends inside this MODEL", path);
    CHECK(strstr(diag_text(diag), want) != NULL);

    /* The same file read whole for --model 2. */
    vb_read_options o;
    memset(&o, 0, sizeof o);
    o.model = 2;
    CHECK_INT(vb_spheres_read_file(ctx, path, &o, &s), VB_OK);
    CHECK_INT(s ? s->n : 0, 2);
    vb_spheres_free(s);
    CHECK(strstr(diag_text(diag), want) != NULL);
    remove(path);

    /* MODELs closed by the next MODEL and by END: no W735. */
    FILE *clean;
    vb_ctx *c2 = open_ctx(&clean);
    strcpy(path, temp_file("MODEL        1\n" PDB_C1 PDB_C2 "MODEL        2\n" PDB_C3 "END\n"));
    CHECK_INT(vb_frame_reader_open(c2, path, NULL, &rd), VB_OK);
    for (int k = 0; k < 3; k++) {
        CHECK_INT(vb_frame_reader_next(c2, rd, &s, &model), VB_OK);
        CHECK_INT(s ? s->n : 0, k == 0 ? 2 : k == 1 ? 1 : 0);
        vb_spheres_free(s);
    }
    vb_frame_reader_close(rd);
    CHECK(strstr(diag_text(clean), "W735") == NULL);
    remove(path);
    vb_close(c2);
    vb_close(ctx);
}

/* Item 6: the B block of residue 1 that comes back after residue 2 is
 * dropped like the contiguous one (it was kept beside A). */
static void test_altloc_split(void)
{
    FILE *diag;
    vb_ctx *ctx = open_ctx(&diag);
    const char *pdb =
        ATOM("    1", " N  ", "A", "SER", "   1", "   1.000", "   0.000", "   0.000", " N")
        ATOM("    2", " CA ", "A", "SER", "   1", "   2.000", "   0.000", "   0.000", " C")
        ATOM("    3", " N  ", " ", "ALA", "   2", "   5.000", "   0.000", "   0.000", " N")
        ATOM("    4", " C  ", " ", "ALA", "   2", "   6.000", "   0.000", "   0.000", " C")
        ATOM("    5", " N  ", "B", "SER", "   1", "   1.100", "   0.000", "   0.000", " N")
        ATOM("    6", " CA ", "B", "SER", "   1", "   2.100", "   0.000", "   0.000", " C")
        ATOM("    7", " N  ", "A", "GLY", "   3", "   9.000", "   0.000", "   0.000", " N");
    vb_sphere_set *s = NULL;
    CHECK_INT(read_text(ctx, "alt.pdb", pdb, NULL, &s), VB_OK);
    CHECK_INT(s ? s->n : 0, 5);
    if (s && s->n == 5) {
        const long lines[5] = {1, 2, 3, 4, 7};
        for (int i = 0; i < 5; i++)
            CHECK_INT(s->line[i], lines[i]);
    }
    vb_spheres_free(s);
    CHECK(strstr(diag_text(diag), "W704: alt.pdb: 2 atoms of other alternate locations") != NULL);
    vb_close(ctx);
}

/* Issue 28, item 2: a GRO whose count says fewer atoms than its lines
 * hold was read short, exit 0; one that says more read the box line as an
 * atom of unknown element (W707). Both are E101 at the line, through the
 * buffer reader (vertices, read()) and the frame reader (channels). */
#define GRO_ATOM(k, x) "    1ALA     CA    " k "   " x "   0.100   0.100\n"
static void test_gro_count(void)
{
    FILE *diag;
    vb_ctx *ctx = open_ctx(&diag);
    static const char atoms6[] = GRO_ATOM("1", "0.100") GRO_ATOM("2", "0.400")
        GRO_ATOM("3", "0.700") GRO_ATOM("4", "1.000") GRO_ATOM("5", "1.300") GRO_ATOM("6", "1.600");
    char text[1024];
    vb_sphere_set *s = NULL;
    /* Right: 6 atoms, and a triclinic box (9 numbers) is a box too. */
    snprintf(text, sizeof text, "t\n6\n%s   1.0 1.0 1.0 0 0 0 0 0 0\n", atoms6);
    CHECK_INT(read_text(ctx, "ok.gro", text, NULL, &s), VB_OK);
    CHECK_INT(s ? s->n : 0, 6);
    CHECK(s && s->x[5] == 16.0);
    vb_spheres_free(s);
    s = NULL;
    /* The count says 3 of 6: line 6 (atom 4) is not the box. */
    snprintf(text, sizeof text, "t\n3\n%s   1.0 1.0 1.0\n", atoms6);
    CHECK_ERROR(ctx, read_text(ctx, "short.gro", text, NULL, &s), VB_EINPUT_MALFORMED,
                "short.gro:6:");
    CHECK(s == NULL);
    CHECK(strstr(vb_errmsg(ctx), "count on line 2 says 3") != NULL);
    /* The same through the frame reader, and for a later frame. */
    const char *path = temp_file(text);
    vb_read_options o;
    memset(&o, 0, sizeof o);
    vb_frame_reader *rd = NULL;
    int model = 0;
    CHECK_INT(vb_frame_reader_open(ctx, path, &o, &rd), VB_OK);
    CHECK_INT(vb_frame_reader_next(ctx, rd, &s, &model), VB_EINPUT_MALFORMED);
    CHECK(s == NULL);
    vb_frame_reader_close(rd);
    unlink(path);
    char two[2048];
    snprintf(two, sizeof two, "t\n6\n%s   1.0 1.0 1.0\nt\n3\n%s   1.0 1.0 1.0\n", atoms6, atoms6);
    o.model = 2;
    CHECK_ERROR(ctx, read_text(ctx, "two.gro", two, &o, &s), VB_EINPUT_MALFORMED, "two.gro:15:");
    CHECK(strstr(vb_errmsg(ctx), "count on line 11 says 3") != NULL);
    /* The count says 8 of 6: the box line comes early, E101 there, no W707. */
    snprintf(text, sizeof text, "t\n8\n%s   1.0 1.0 1.0\n", atoms6);
    CHECK_ERROR(ctx, read_text(ctx, "long.gro", text, NULL, &s), VB_EINPUT_MALFORMED,
                "long.gro:9:");
    CHECK(strstr(vb_errmsg(ctx), "box line after 6 atoms") != NULL);
    CHECK(strstr(diag_text(diag), "W707") == NULL);
    vb_close(ctx);
}

/* A topology of na spheres (top, radius 1 each at frame 0's places) and a
 * two-frame DCD: frame 0 is read, frame 1 is E104 naming atom b as
 * identical to atom a. */
static void check_traj_duplicate(const char *top_text, size_t na, const double *x0,
                                 const double *y0, const double *z0, const double *x1,
                                 const double *y1, const double *z1, int b, int a)
{
    vb_ctx *ctx = open_ctx(NULL);
    char top[64], dcd[64];
    strcpy(top, temp_file(top_text));
    strcpy(dcd, temp_file(""));
    vb_dcd_writer *w = NULL;
    CHECK_INT(vb_dcd_writer_open(ctx, dcd, na, 1.0, "dup", &w), VB_OK);
    CHECK_INT(vb_dcd_writer_frame(ctx, w, x0, y0, z0), VB_OK);
    CHECK_INT(vb_dcd_writer_frame(ctx, w, x1, y1, z1), VB_OK);
    CHECK_INT(vb_dcd_writer_close(ctx, w), VB_OK);
    vb_read_options o;
    memset(&o, 0, sizeof o);
    vb_frame_source *F = NULL;
    vb_sphere_set *s = NULL;
    int model = 0;
    CHECK_INT(vb_frame_source_open(ctx, top, dcd, &o, &F), VB_OK);
    CHECK_INT(vb_frame_source_next(ctx, F, &s, &model), VB_OK);
    CHECK_INT(s ? s->n : 0, (long)na);
    CHECK(s && s->x[3] == x0[3] && s->z[3] == z0[3]);
    vb_spheres_free(s);
    s = NULL;
    char want[200];
    snprintf(want, sizeof want, "%s: frame 1: atom %d (topology line %d) is identical to atom %d "
             "(topology line %d)", dcd, b, b, a, a);
    CHECK_ERROR(ctx, vb_frame_source_next(ctx, F, &s, &model), VB_EINPUT_DUPLICATE, want);
    CHECK(s == NULL);
    vb_frame_source_close(F);
    remove(top);
    remove(dcd);
    vb_close(ctx);
}

/* Issue 28, item 8: two atoms of a trajectory frame at the same place with
 * the same radius are E104, as in a GRO or PDB frame (they were accepted),
 * naming the trajectory, the frame and both atoms. */
static void test_traj_duplicates(void)
{
    const double x0[5] = {0, 3, 0, 0, 5}, y0[5] = {0, 0, 3, 0, 5}, z0[5] = {0, 0, 0, 3, 5};
    /* Frame 1: atom 4 moves onto atom 2 (same radius: the same sphere). */
    const double x1[5] = {0, 3, 0, 3, 5}, y1[5] = {0, 0, 3, 0, 5}, z1[5] = {0, 0, 0, 0, 5};
    check_traj_duplicate("0 0 0 1\n3 0 0 1\n0 3 0 1\n0 0 3 1\n5 5 5 1\n", 5, x0, y0, z0, x1, y1,
                         z1, 4, 2);
}

/* Issue 33: the duplicate check of a trajectory frame goes by a hash, not a
 * sort: of three copies of one sphere (-0 and 0 one number, as a text
 * frame's decimals compare) the smallest later atom is named beside the
 * earliest copy, also when a later pair (atoms 5, 6) comes first in
 * coordinate order. */
static void test_traj_duplicates_three(void)
{
    const double x0[7] = {0, 3, 0, 0, 5, -4, 7}, y0[7] = {0, 0, 3, 0, 5, 0, 7},
                 z0[7] = {0, 0, 0, 3, 5, 0, 7};
    /* Frame 1: atoms 4 and 7 move onto atom 2 (one with -0), atom 6 onto 5. */
    const double x1[7] = {0, 3, 0, 3, -4, -4, 3}, y1[7] = {0, 0, 3, -0.0, 0, 0, 0},
                 z1[7] = {0, 0, 0, 0, 0, 0, -0.0};
    check_traj_duplicate("0 0 0 1\n3 0 0 1\n0 3 0 1\n0 0 3 1\n5 5 5 1\n-4 0 0 1\n7 7 7 1\n", 7,
                         x0, y0, z0, x1, y1, z1, 4, 2);
}

/* Issue 28, item 9: of a residue's alternate locations the most occupied
 * is kept (A 0.44 against B 0.56: B; the first, A, was kept), ties to the
 * first met; without occupancies the first. */
#define ATOM_OCC(serial, name, alt, seq, x, occ, el)                                              \
    "ATOM  " serial " " name alt "SER A" seq "    " x "   0.000   0.000" occ " 10.00          " el \
    "\n"
static void test_altloc_occupancy(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    const char *pdb =
        ATOM_OCC("    1", " N  ", "A", "   1", "   1.000", "  0.44", " N")
        ATOM_OCC("    2", " CA ", "A", "   1", "   2.000", "  0.44", " C")
        ATOM_OCC("    3", " N  ", "B", "   1", "   1.100", "  0.56", " N")
        ATOM_OCC("    4", " CA ", "B", "   1", "   2.100", "  0.56", " C")
        ATOM_OCC("    5", " N  ", "A", "   2", "   5.000", "  0.50", " N")
        ATOM_OCC("    6", " N  ", "B", "   2", "   5.100", "  0.50", " N")
        ATOM_OCC("    7", " N  ", "A", "   3", "   9.000", "      ", " N")
        ATOM_OCC("    8", " N  ", "B", "   3", "   9.100", "      ", " N");
    vb_sphere_set *s = NULL;
    CHECK_INT(read_text(ctx, "occ.pdb", pdb, NULL, &s), VB_OK);
    CHECK_INT(s ? s->n : 0, 4);
    if (s && s->n == 4) {
        const long lines[4] = {3, 4, 5, 7};
        for (int i = 0; i < 4; i++)
            CHECK_INT(s->line[i], lines[i]);
        CHECK(s->x[0] == 1.1 && s->info[0].altloc == 'B');
        CHECK(s->x[2] == 5.0 && s->info[2].altloc == 'A');
    }
    vb_spheres_free(s);
    vb_close(ctx);
}

/* Issue 28, item 9: a sphere inside another in every model of an NMR file
 * is named (W701) for the first model only, and the other models counted
 * on one line (W702), not repeated per model. */
static void test_contained_once(void)
{
    FILE *diag;
    vb_ctx *ctx = open_ctx(&diag);
    char text[4096] = "";
    for (int m = 1; m <= 3; m++) {
        char model[64];
        snprintf(model, sizeof model, "MODEL     %4d\n", m);
        strcat(text, model);
        strcat(text, PDB_C1 PDB_C2 PDB_C3 PDB_C4);
        /* An oxygen (1.52) at the first carbon's centre (1.70): inside it. */
        strcat(text, ATOM("    5", " O  ", " ", "SER", "   5", "   0.000", "   0.000", "   0.100", " O"));
        strcat(text, "ENDMDL\n");
    }
    const char *path = temp_file(text);
    vb_read_options o;
    memset(&o, 0, sizeof o);
    vb_frame_source *F = NULL;
    vb_sphere_set *s = NULL;
    int model = 0, frames = 0;
    CHECK_INT(vb_frame_source_open(ctx, path, NULL, &o, &F), VB_OK);
    while (vb_frame_source_next(ctx, F, &s, &model) == VB_OK && s) {
        CHECK_INT(s->n, 5);
        CHECK_INT(s->contained[4], 1);
        vb_spheres_free(s);
        frames++;
    }
    vb_frame_source_close(F);
    CHECK_INT(frames, 3);
    const char *w = diag_text(diag);
    size_t named = 0;
    for (const char *p = w; (p = strstr(p, "W701")); p++)
        named++;
    CHECK_INT(named, 2); /* the W701 line, and the W702 line naming it */
    CHECK(strstr(w, "W701: ") != NULL && strstr(strstr(w, "W701: ") + 1, "W701: ") == NULL);
    char want[200];
    snprintf(want, sizeof want, "W702: %s: spheres inside others in 2 more frames (W701 named "
             "them for frame 0 only)", path);
    CHECK(strstr(w, want) != NULL);
    unlink(path);
    vb_close(ctx);
}

int main(void)
{
    test_duplicates();
    test_dcd_huge_claim();
    test_dcd_stray_bytes();
    test_nul_byte();
    test_bom();
    test_cr_only();
    test_truncated_model();
    test_altloc_split();
    test_altloc_occupancy();
    test_gro_count();
    test_traj_duplicates();
    test_traj_duplicates_three();
    test_contained_once();
    VB_TEST_END();
}
