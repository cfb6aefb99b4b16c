/* Format detection is one path for whole files (vertices, Python read())
 * and streams (channels, Python frames()): both read whole records, never
 * a byte budget. Each case puts more than 64 KiB of header before the
 * first record that decides the format (issue 28, items 1 and 4) and
 * checks that the frame reader reads the same spheres as the whole-file
 * reader, with the values the file gives. */
#include "input_test_util.h"

#include "vb_frames.h"

#include <stdio.h>
#include <unistd.h>

/* Writes head (repeated `times`) then body to a temporary file. */
static const char *write_with_header(const char *head, size_t times, const char *body)
{
    static char path[64];
    strcpy(path, "/tmp/vb_detect_testXXXXXX");
    int fd = mkstemp(path);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!f)
        return path;
    for (size_t k = 0; k < times; k++)
        fputs(head, f);
    fputs(body, f);
    fclose(f);
    return path;
}

/* The first frame through vb_frame_source (the path of channels and
 * frames()), checked; NULL on failure (the error left in ctx). */
static vb_sphere_set *first_frame(vb_ctx *ctx, const char *path)
{
    vb_read_options o;
    memset(&o, 0, sizeof o);
    vb_frame_source *F = NULL;
    vb_sphere_set *s = NULL;
    int model = 0;
    if (vb_frame_source_open(ctx, path, NULL, &o, &F) == VB_OK)
        vb_frame_source_next(ctx, F, &s, &model);
    vb_frame_source_close(F);
    return s;
}

static vb_sphere_set *whole_file(vb_ctx *ctx, const char *path)
{
    vb_read_options o;
    memset(&o, 0, sizeof o);
    vb_sphere_set *s = NULL;
    vb_spheres_read_file(ctx, path, &o, &s);
    return s;
}

/* Both paths give n spheres, the same decimals, and r[0] == r0. */
static void check_same(vb_ctx *ctx, const char *path, size_t n, double x0, double r0)
{
    vb_sphere_set *a = whole_file(ctx, path);
    vb_sphere_set *b = first_frame(ctx, path);
    CHECK(a != NULL);
    CHECK(b != NULL);
    if (!b)
        fprintf(stderr, "  %s: %s\n", path, vb_errmsg(ctx));
    if (a && b) {
        CHECK_INT(a->n, n);
        CHECK_INT(b->n, n);
        CHECK(b->x[0] == x0);
        CHECK(b->r[0] == r0);
        CHECK(a->r[0] == r0);
        for (size_t i = 0; i < n && i < a->n && i < b->n; i++) {
            CHECK(a->x[i] == b->x[i] && a->y[i] == b->y[i] && a->z[i] == b->z[i]);
            CHECK(a->r[i] == b->r[i]);
        }
    }
    vb_spheres_free(a);
    vb_spheres_free(b);
    unlink(path);
}

static const char pqr_atoms[] =
    "ATOM      1  N   THR     1      17.047  14.099   3.625 -0.3200 2.0000\n"
    "ATOM      2  CA  THR     1      16.967  12.784   4.338  0.3300 2.0000\n"
    "ATOM      3  C   THR     1      15.685  12.755   5.133  0.5500 1.7000\n"
    "ATOM      4  O   THR     1      15.268  13.825   5.594 -0.5500 1.4000\n"
    "ATOM      5  CB  THR     1      18.170  12.703   5.337  0.0000 2.0000\n";

static const char xyzr_body[] =
    "0 0 0 1.5\n"
    "3 0 0 1\n"
    "0 3 0 1\n"
    "0 0 3 1\n";

static const char cif_body[] =
    "data_t\n"
    "loop_\n"
    "_atom_site.group_PDB\n"
    "_atom_site.id\n"
    "_atom_site.type_symbol\n"
    "_atom_site.label_atom_id\n"
    "_atom_site.label_comp_id\n"
    "_atom_site.label_asym_id\n"
    "_atom_site.label_seq_id\n"
    "_atom_site.Cartn_x\n"
    "_atom_site.Cartn_y\n"
    "_atom_site.Cartn_z\n"
    "ATOM 1 N N ALA A 1 1.000 2.000 3.000\n"
    "ATOM 2 C CA ALA A 1 4.000 2.000 3.000\n"
    "ATOM 3 C C ALA A 1 1.000 5.000 3.000\n"
    "ATOM 4 O O ALA A 1 1.000 2.000 6.000\n";

static const char gro_body[] =
    "    4\n"
    "    1ALA      N    1   0.100   0.200   0.300\n"
    "    1ALA     CA    2   0.400   0.200   0.300\n"
    "    1ALA      C    3   0.100   0.500   0.300\n"
    "    1ALA      O    4   0.100   0.200   0.600\n"
    "   1.00000   1.00000   1.00000\n";

int main(void)
{
    vb_ctx *ctx = open_ctx(NULL);

    /* PQR after 2000 REMARK lines (over 140 KiB): the file's radii (2.0),
     * not nitrogen's 1.55 that a PDB reading would give. */
    check_same(ctx,
               write_with_header("REMARK   1 a long header of a PQR file, as PDB2PQR writes "
                                 "it, padded to seventy\n",
                                 2000, pqr_atoms),
               5, 17.047, 2.0);

    /* XYZR after 80 KiB of comments (E105 before). */
    check_same(ctx, write_with_header("# a comment line of forty characters...\n", 2000, xyzr_body),
               4, 0.0, 1.5);

    /* mmCIF after 80 KiB of comments (E105 before). */
    check_same(ctx, write_with_header("# a comment line of forty characters...\n", 2000, cif_body),
               4, 1.0, 1.55);

    /* GRO with a 10 MB title (E109 before): nm to Angstrom. */
    {
        static char title[10 * 1000 * 1000 + 2];
        memset(title, 't', sizeof title - 2);
        title[sizeof title - 2] = '\n';
        title[sizeof title - 1] = '\0';
        check_same(ctx, write_with_header(title, 1, gro_body), 4, 1.0, 1.55);
    }

    /* A PDB header alone is still PDB (its reader says it has no atoms),
     * however long, and an empty file is still E105 on both paths. */
    {
        const char *p = write_with_header("REMARK   1 only a header\n", 5000, "END\n");
        vb_sphere_set *s = first_frame(ctx, p);
        CHECK(s == NULL);
        CHECK(vb_errcode(ctx) != VB_EINPUT_FORMAT);
        unlink(p);
        p = write_with_header("\n", 100000, "# nothing\n");
        s = first_frame(ctx, p);
        CHECK(s == NULL);
        CHECK_INT(vb_errcode(ctx), VB_EINPUT_EMPTY);
        unlink(p);
    }

    vb_close(ctx);
    VB_TEST_END();
}
