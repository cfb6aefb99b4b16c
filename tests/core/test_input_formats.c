/* Unit tests of the input layer, part 2: PDB, PQR and mmCIF readers on small
 * inline samples (values as exact decimals), detection, the read options
 * (altloc, model, water, hydrogens, elements, radii files), frames, and the
 * real structures in corpus/data. */
#include "input_test_util.h"

static const char pdb_sample[] =
    "HEADER    TEST\n" /* 1 */
    "MODEL        1\n" /* 2 */
    "ATOM      1  N   ALA A   1       1.000   2.000   3.000  1.00 10.00           N\n" /* 3 */
    "ATOM      2  CA AALA A   1       2.500   2.000   3.000  1.00 10.00           C\n" /* 4 */
    "ATOM      3  CA BALA A   1       2.600   2.100   3.000  1.00 10.00           C\n" /* 5 */
    "ATOM      4  H   ALA A   1       0.500   2.000   3.000  1.00 10.00           H\n" /* 6 */
    "HETATM    5 FE   HEM A   2      10.000 -11.250  12.125  1.00 10.00          FE\n" /* 7 */
    "HETATM    6  O   HOH A   3      20.000  20.000  20.000  1.00 10.00           O\n" /* 8 */
    "ATOM      7  CB  ALA A   1       3.000   3.000   3.000  1.00 10.00\n"             /* 9 */
    "HETATM    8  XX  UNK A   4      -5.000  -5.000  -5.000  1.00 10.00          XX\n" /* 10 */
    "ENDMDL\n"                                                                       /* 11 */
    "MODEL        2\n"                                                               /* 12 */
    "ATOM      1  N   ALA A   1       7.000   8.000   9.000  1.00 10.00           N\n" /* 13 */
    "ENDMDL\n"                                                                       /* 14 */
    "END\n";                                                                         /* 15 */

static void test_pdb(void)
{
    FILE *diag;
    vb_ctx *ctx = open_ctx(&diag);
    vb_read_options o;
    memset(&o, 0, sizeof o);
    vb_sphere_set *s = NULL;
    CHECK_INT(read_text(ctx, "s.pdb", pdb_sample, &o, &s), VB_OK);
    CHECK_INT(s->n, 6);
    const long lines[6] = {3, 4, 6, 7, 9, 10};
    for (int i = 0; i < 6 && i < (int)s->n; i++)
        CHECK_INT(s->line[i], lines[i]);
    CHECK_DEC(s->ex[0], 1, 0);
    CHECK_DEC(s->er[0], 155, -2); /* N */
    CHECK(s->r[0] == 1.55);
    CHECK_DEC(s->ex[1], 25, -1);
    CHECK_INT(s->info[1].altloc, 'A');
    CHECK_DEC(s->er[2], 12, -1); /* H */
    CHECK_DEC(s->ey[3], -1125, -2);
    CHECK_DEC(s->ez[3], 12125, -3);
    CHECK_DEC(s->er[3], 14, -1); /* FE */
    CHECK_STR(s->info[3].element, "FE");
    CHECK_STR(s->info[3].name, "FE");
    CHECK_STR(s->info[3].resname, "HEM");
    CHECK_INT(s->info[3].hetatm, 1);
    CHECK_INT(s->info[3].serial, 5);
    CHECK_INT(s->info[3].resseq, 2);
    CHECK_STR(s->info[3].chain, "A");
    CHECK_STR(s->info[4].element, "C"); /* from the name " CB " */
    CHECK_DEC(s->er[4], 17, -1);
    CHECK_STR(s->info[5].element, "XX");
    CHECK_DEC(s->er[5], 17, -1); /* unknown: carbon's radius */
    const char *w = diag_text(diag);
    CHECK(strstr(w, "W707: s.pdb:10: unknown element 'XX'") != NULL);
    CHECK(strstr(w, "W703: s.pdb: 1 water atom dropped") != NULL);
    CHECK(strstr(w, "W704: s.pdb: 1 atom of other alternate locations dropped") != NULL);
    CHECK(strstr(w, "W705: s.pdb: 1 atom of 1 other model ignored") != NULL);
    CHECK(strstr(w, "W706") == NULL);
    vb_spheres_free(s);

    o.keep_water = 1;
    o.drop_hydrogens = 1;
    CHECK_INT(read_text(ctx, "s.pdb", pdb_sample, &o, &s), VB_OK);
    CHECK_INT(s->n, 6);
    CHECK_INT(s->line[2], 7);
    CHECK_INT(s->line[3], 8);
    CHECK_STR(s->info[3].resname, "HOH");
    CHECK(strstr(diag_text(diag), "W706: s.pdb: 1 hydrogen atom dropped") != NULL);
    vb_spheres_free(s);

    memset(&o, 0, sizeof o);
    o.model = 2;
    CHECK_INT(read_text(ctx, "s.pdb", pdb_sample, &o, &s), VB_OK);
    CHECK_INT(s->n, 1);
    CHECK_DEC(s->ex[0], 7, 0);
    CHECK_INT(s->line[0], 13);
    vb_spheres_free(s);
    o.model = 3;
    CHECK_ERROR(ctx, read_text(ctx, "s.pdb", pdb_sample, &o, &s), VB_EINPUT_MODEL, "s.pdb:");
    CHECK(s == NULL);
    o.model = 0;
    o.strict_elements = 1;
    /* Line 9 has no element column: strict mode refuses to infer it; line
     * 10's element is unknown. */
    CHECK_ERROR(ctx, read_text(ctx, "s.pdb", pdb_sample, &o, &s), VB_EINPUT_INFERRED, "s.pdb:9:");
    CHECK(strstr(vb_errmsg(ctx), "'CB' of residue 'ALA'") != NULL);
    static const char cb[] = "ATOM      7  CB  ALA A   1       3.000   3.000   3.000  1.00 10.00\n";
    char no9[sizeof pdb_sample + 16];
    const char *at = strstr(pdb_sample, cb);
    size_t head = (size_t)(at - pdb_sample);
    memcpy(no9, pdb_sample, head);
    memcpy(no9 + head, cb, 66);
    memcpy(no9 + head + 66, "           C\n", 13);
    strcpy(no9 + head + 79, at + strlen(cb));
    CHECK_ERROR(ctx, read_text(ctx, "s.pdb", no9, &o, &s), VB_EINPUT_ELEMENT, "s.pdb:10:");

    /* A single-model file is model 1; model 2 is absent. */
    const char *one = "ATOM      1  N   ALA A   1       1.000   2.000   3.000  1.00 10.00           N\n";
    memset(&o, 0, sizeof o);
    o.model = 1;
    CHECK_INT(read_text(ctx, "one", one, &o, &s), VB_OK);
    CHECK_INT(s->n, 1);
    vb_spheres_free(s);
    o.model = 2;
    CHECK_ERROR(ctx, read_text(ctx, "one", one, &o, &s), VB_EINPUT_MODEL, "one:");

    /* Records after END belong to no entry: counted, not read. */
    char two[256];
    snprintf(two, sizeof two, "%sEND\n%s", one, one);
    CHECK_INT(read_text(ctx, "two", two, NULL, &s), VB_OK);
    CHECK_INT(s->n, 1);
    CHECK(strstr(diag_text(diag), "W710: two: 1 atom record after the END record ignored") != NULL);
    vb_spheres_free(s);

    /* Broken records, each named by line. */
    CHECK_ERROR(ctx, read_text(ctx, "b", "REMARK x\nATOM      1  N   ALA A   1       1.000   2.000\n",
                               NULL, &s),
                VB_EINPUT_MALFORMED, "b:2:");
    CHECK_ERROR(ctx,
                read_text(ctx, "b",
                          "ATOM      1  N   ALA A   1       1.000   2.000   3.000\n"
                          "ATOM      2  N   ALA A   1       1.000   2.0 0   3.000\n",
                          NULL, &s),
                VB_EINPUT_MALFORMED, "b:2:");
    CHECK_ERROR(ctx, read_text(ctx, "b", "ATOM      1  N   ALA A   1         nan   2.000   3.000\n",
                               NULL, &s),
                VB_EINPUT_NONFINITE, "b:1:");
    fclose(diag);
    vb_close(ctx);
}

static const char pqr_sample[] =
    "REMARK   1 PQR file generated by PDB2PQR\n"                              /* 1 */
    "ATOM      1  N   THR     1      17.047  14.099   3.625 -0.3200 2.0000\n" /* 2 */
    "ATOM      2  CA  THR A   1      16.967  12.784   4.338  0.3300 1.9000\n" /* 3 */
    "ATOM      3  HA  THR A   1      16.000  12.000   4.000  0.1000 1.2500\n" /* 4 */
    "HETATM    4  O   HOH     2       1.000   1.000   1.000 -0.8340 1.6000\n" /* 5 */
    "ATOM      5  C   THR A   1  1.5 2.5 3.5 0.55 1.7 C\n"                     /* 6 */
    "TER\n"                                                                    /* 7 */
    "END\n";                                                                   /* 8 */

static void test_pqr(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    vb_read_options o;
    memset(&o, 0, sizeof o);
    vb_sphere_set *s = NULL;
    CHECK_INT(read_text(ctx, "s.pqr", pqr_sample, &o, &s), VB_OK);
    CHECK_INT(s->n, 4);
    /* The radius is the last column, the charge never a radius. */
    CHECK_DEC(s->er[0], 2, 0);
    CHECK_DEC(s->ex[0], 17047, -3);
    CHECK_DEC(s->ez[0], 3625, -3);
    CHECK_DEC(s->er[1], 19, -1);
    CHECK_STR(s->info[1].chain, "A");
    CHECK_STR(s->info[0].chain, "");
    CHECK_INT(s->info[1].resseq, 1);
    CHECK_STR(s->info[1].name, "CA");
    CHECK_DEC(s->er[2], 125, -2);
    CHECK_STR(s->info[2].element, "H");
    CHECK_INT(s->line[3], 6);
    CHECK_DEC(s->ex[3], 15, -1);
    CHECK_DEC(s->er[3], 17, -1); /* before the appended element column */
    vb_spheres_free(s);
    o.keep_water = 1;
    o.drop_hydrogens = 1;
    CHECK_INT(read_text(ctx, "s.pqr", pqr_sample, &o, &s), VB_OK);
    CHECK_INT(s->n, 4);
    CHECK_INT(s->line[2], 5);
    CHECK_DEC(s->er[2], 16, -1);
    vb_spheres_free(s);
    /* Two lines, one broken, are too few to detect PQR by: force it. */
    o.format = VB_FMT_PQR;
    CHECK_ERROR(ctx,
                read_text(ctx, "b.pqr",
                          "ATOM      1  N   THR     1      17.047  14.099   3.625 -0.3200 2.0000\n"
                          "ATOM      2  N   THR     1      17.047  14.099   3.625 -0.3200\n",
                          &o, &s),
                VB_EINPUT_MALFORMED, "b.pqr:2:");
    CHECK_ERROR(ctx,
                read_text(ctx, "b.pqr",
                          "ATOM      1  N   THR     1      17.047  14.099   3.625 -0.3200 2.0000\n"
                          "ATOM      2  N   THR     1      17.047  14.099   3.625 -0.3200 inf\n",
                          &o, &s),
                VB_EINPUT_NONFINITE, "b.pqr:2:");
    vb_close(ctx);
}

static const char cif_sample[] =
    "data_test\n"                           /* 1 */
    "# a comment\n"                         /* 2 */
    "_entry.id 'TEST 1'\n"                  /* 3 */
    "loop_\n"                               /* 4 */
    "_atom_site.group_PDB\n"                /* 5 */
    "_atom_site.id\n"                       /* 6 */
    "_atom_site.type_symbol\n"              /* 7 */
    "_atom_site.label_atom_id\n"            /* 8 */
    "_atom_site.label_alt_id\n"             /* 9 */
    "_atom_site.label_comp_id\n"            /* 10 */
    "_atom_site.auth_asym_id\n"             /* 11 */
    "_atom_site.auth_seq_id\n"              /* 12 */
    "_atom_site.Cartn_x\n"                  /* 13 */
    "_atom_site.Cartn_y\n"                  /* 14 */
    "_atom_site.Cartn_z\n"                  /* 15 */
    "_atom_site.pdbx_PDB_model_num\n"       /* 16 */
    "ATOM 1 N N . ALA A 1 1.000 2.000 3.000 1\n"           /* 17 */
    "ATOM 2 C \"C1'\" . ALA A 1 1.5 2.5 3.5 1\n"           /* 18 */
    "ATOM 3 O 'O5'' A ALA A 1 -1.25 0 0 1\n"               /* 19 */
    "ATOM 4 O 'O5'' B ALA A 1 -1.35 0 0 1\n"               /* 20 */
    "HETATM 5 Fe\n"                                        /* 21 */
    ";FE\n"                                                /* 22 */
    ";\n"                                                  /* 23 */
    ". HEM B 2 4 5 6 1\n"                                  /* 24 */
    "HETATM 6 O O . HOH C 3 9 9 9 1\n"                     /* 25 */
    "ATOM 7 N N . ALA A 1 7.0 8.0 9.0 2\n"                 /* 26 */
    "#\n"                                                  /* 27 */
    "loop_\n"                                              /* 28 */
    "_other.a\n"                                           /* 29 */
    "x\n";                                                 /* 30 */

static void test_mmcif(void)
{
    FILE *diag;
    vb_ctx *ctx = open_ctx(&diag);
    vb_read_options o;
    memset(&o, 0, sizeof o);
    vb_sphere_set *s = NULL;
    CHECK_INT(read_text(ctx, "s.cif", cif_sample, &o, &s), VB_OK);
    CHECK_INT(s->n, 4);
    CHECK_INT(s->line[0], 17);
    CHECK_DEC(s->ex[0], 1, 0);
    CHECK_DEC(s->er[0], 155, -2);
    CHECK_STR(s->info[1].name, "C1'");
    CHECK_DEC(s->ey[1], 25, -1);
    CHECK_STR(s->info[2].name, "O5'");
    CHECK_INT(s->info[2].altloc, 'A');
    CHECK_DEC(s->ex[2], -125, -2);
    CHECK_DEC(s->er[2], 152, -2);
    CHECK_STR(s->info[3].name, "FE");
    CHECK_STR(s->info[3].element, "FE");
    CHECK_DEC(s->er[3], 14, -1);
    CHECK_STR(s->info[3].chain, "B");
    CHECK_INT(s->info[3].hetatm, 1);
    CHECK_INT(s->line[3], 21);
    const char *w = diag_text(diag);
    CHECK(strstr(w, "W703: s.cif: 1 water atom dropped") != NULL);
    CHECK(strstr(w, "W704: s.cif: 1 atom of other alternate locations dropped") != NULL);
    CHECK(strstr(w, "W705: s.cif: 1 atom of 1 other model ignored") != NULL);
    vb_spheres_free(s);
    o.model = 2;
    CHECK_INT(read_text(ctx, "s.cif", cif_sample, &o, &s), VB_OK);
    CHECK_INT(s->n, 1);
    CHECK_DEC(s->ez[0], 9, 0);
    CHECK_INT(s->line[0], 26);
    vb_spheres_free(s);
    o.model = 5;
    CHECK_ERROR(ctx, read_text(ctx, "s.cif", cif_sample, &o, &s), VB_EINPUT_MODEL, "s.cif:");
    /* A second data block with atoms is another structure: warned, not read. */
    char twice[2 * sizeof cif_sample + 16];
    snprintf(twice, sizeof twice, "%sdata_again\n%s", cif_sample, cif_sample + 10);
    o.model = 0;
    CHECK_INT(read_text(ctx, "t.cif", twice, &o, &s), VB_OK);
    CHECK_INT(s->n, 4);
    CHECK(strstr(diag_text(diag), "W711: t.cif:35: a further _atom_site loop") != NULL);
    vb_spheres_free(s);

    const char *head = "data_x\nloop_\n_atom_site.id\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n"
                       "_atom_site.Cartn_z\n_atom_site.type_symbol\n";
    char buf[512];
    snprintf(buf, sizeof buf, "%s1 0 0 0 C\n2 1 1 'C\n", head);
    CHECK_ERROR(ctx, read_text(ctx, "q.cif", buf, NULL, &s), VB_EINPUT_MALFORMED, "q.cif:9:");
    snprintf(buf, sizeof buf, "%s1 0 0 0 C\n2 1 1 ? C\n", head);
    CHECK_ERROR(ctx, read_text(ctx, "q.cif", buf, NULL, &s), VB_EINPUT_MALFORMED, "q.cif:9:");
    snprintf(buf, sizeof buf, "%s1 0 0 0 C\n2 1 1 1\n", head);
    CHECK_ERROR(ctx, read_text(ctx, "q.cif", buf, NULL, &s), VB_EINPUT_MALFORMED, "q.cif:");
    snprintf(buf, sizeof buf, "%s1 0 0 0 C\n2 1 1 1e999 C\n", head);
    CHECK_ERROR(ctx, read_text(ctx, "q.cif", buf, NULL, &s), VB_EINPUT_MAGNITUDE, "q.cif:9:");
    snprintf(buf, sizeof buf, "%s1 0 0 0 C\n;text\n", head);
    CHECK_ERROR(ctx, read_text(ctx, "q.cif", buf, NULL, &s), VB_EINPUT_MALFORMED, "q.cif:9:");
    CHECK_ERROR(ctx,
                read_text(ctx, "q.cif", "data_x\nloop_\n_atom_site.id\n_atom_site.Cartn_x\n1 2\n",
                          NULL, &s),
                VB_EINPUT_MALFORMED, "q.cif:");
    CHECK_ERROR(ctx, read_text(ctx, "n.cif", "data_x\n_entry.id X\n", NULL, &s), VB_EINPUT_EMPTY,
                "n.cif:");
    fclose(diag);
    vb_close(ctx);
}

static void test_detect(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    vb_sphere_set *s = NULL;
    vb_read_options o;
    memset(&o, 0, sizeof o);
    /* The same PQR text read as PDB puts charge/radius columns in the wrong
     * place: detection must pick PQR. */
    CHECK_INT(read_text(ctx, "a", pqr_sample, NULL, &s), VB_OK);
    CHECK_DEC(s->er[0], 2, 0);
    vb_spheres_free(s);
    CHECK_INT(read_text(ctx, "a", pdb_sample, NULL, &s), VB_OK);
    CHECK_STR(s->info[3].element, "FE");
    vb_spheres_free(s);
    CHECK_INT(read_text(ctx, "a", cif_sample, NULL, &s), VB_OK);
    CHECK_STR(s->info[1].name, "C1'");
    vb_spheres_free(s);
    CHECK_INT(read_text(ctx, "a", "\n# balls\n-1 2 3 4 # x\n", NULL, &s), VB_OK);
    CHECK_INT(s->n, 1);
    vb_spheres_free(s);
    /* PDB records without atoms: a PDB file with no atoms, said so. */
    CHECK_ERROR(ctx, read_text(ctx, "a", "COMPND x\nREMARK y\n", NULL, &s), VB_EINPUT_EMPTY, "a:");
    CHECK(strstr(vb_errmsg(ctx), "no atoms") != NULL);
    CHECK_ERROR(ctx, read_text(ctx, "a", "hello\nworld\n", NULL, &s), VB_EINPUT_FORMAT, "a:");
    /* Forcing a format: PDB text read as XYZR is malformed at line 1. */
    o.format = VB_FMT_XYZR;
    CHECK_ERROR(ctx, read_text(ctx, "a", pdb_sample, &o, &s), VB_EINPUT_MALFORMED, "a:1:");
    vb_format f;
    CHECK_INT(vb_format_parse(ctx, "cif", &f), VB_OK);
    CHECK_INT(f, VB_FMT_MMCIF);
    CHECK_INT(vb_format_parse(ctx, "pqr", &f), VB_OK);
    CHECK_INT(f, VB_FMT_PQR);
    CHECK_INT(vb_format_parse(ctx, "gro", &f), VB_OK);
    CHECK_INT(f, VB_FMT_GRO);
    CHECK_INT(vb_format_parse(ctx, "xtc", &f), VB_EMISUSE);
    vb_close(ctx);
}

/* One number of the read options set to v, checked: VB_OK, or VB_EMISUSE
 * with message `msg`. */
static void read_edge(vb_ctx *ctx, int assembly, int v, const char *msg)
{
    vb_read_options o;
    memset(&o, 0, sizeof o);
    *(assembly ? &o.assembly : &o.model) = v;
    CHECK_INT(vb_read_options_check(ctx, &o), msg ? VB_EMISUSE : VB_OK);
    if (msg)
        CHECK(strcmp(vb_errmsg(ctx), msg) == 0);
}

/* The read options' ranges at their edges (vb_read_options_check, the
 * check of --model, --assembly and vorball.read's model). */
static void test_read_options_check(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    const char *model = "--model needs a model number >= 1";
    const char *assembly = "--assembly needs an assembly number >= 1";
    CHECK_INT(VB_MODEL_MAX, 999999999);
    CHECK_INT(VB_ASSEMBLY_MAX, 999999);
    read_edge(ctx, 0, 0, NULL);
    read_edge(ctx, 0, 1, NULL);
    read_edge(ctx, 0, VB_MODEL_MAX, NULL);
    read_edge(ctx, 0, VB_MODEL_MAX + 1, model);
    read_edge(ctx, 0, -1, model);
    read_edge(ctx, 1, 0, NULL);
    read_edge(ctx, 1, 1, NULL);
    read_edge(ctx, 1, VB_ASSEMBLY_MAX, NULL);
    read_edge(ctx, 1, VB_ASSEMBLY_MAX + 1, assembly);
    read_edge(ctx, 1, -1, assembly);
    vb_close(ctx);
}

static void test_radii_file(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    char path[64];
    strcpy(path, temp_file("# my radii\nC 1.9\nfe 1.25 # iron\n\n"));
    vb_radii_table *t = NULL;
    CHECK_INT(vb_radii_load(ctx, path, &t), VB_OK);
    remove(path);
    vb_read_options o;
    memset(&o, 0, sizeof o);
    o.radii = t;
    vb_sphere_set *s = NULL;
    CHECK_INT(read_text(ctx, "s.pdb", pdb_sample, &o, &s), VB_OK);
    CHECK_DEC(s->er[1], 19, -1);  /* C from the file */
    CHECK_DEC(s->er[3], 125, -2); /* FE from the file */
    CHECK_DEC(s->er[0], 155, -2); /* N: built-in */
    vb_spheres_free(s);
    vb_radii_free(t);

    const char *bad[] = {"C 1.7\nN\n", "C 1.7\n\nN -1.5\n", "C 1.5 2\n", "LONGNAME 1.5\n"};
    const int code[] = {VB_EINPUT_MALFORMED, VB_EINPUT_RADIUS, VB_EINPUT_MALFORMED,
                        VB_EINPUT_MALFORMED};
    const long line[] = {2, 3, 1, 1};
    for (int k = 0; k < 4; k++) {
        strcpy(path, temp_file(bad[k]));
        char prefix[80];
        snprintf(prefix, sizeof prefix, "%s:%ld:", path, line[k]);
        CHECK_ERROR(ctx, vb_radii_load(ctx, path, &t), code[k], prefix);
        CHECK(t == NULL);
        remove(path);
    }
    vb_close(ctx);
}

static void test_frames_inline(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    char path[64];
    /* MODEL 4 lacks its ENDMDL: the next MODEL closes it. MODEL 9 carries an
     * identifier in columns 73-80, as 1grm does. */
    strcpy(path, temp_file("REMARK x\n"
                           "MODEL        4\n"
                           "ATOM      1  N   ALA A   1       1.000   2.000   3.000  1.00 10.00           N\n"
                           "MODEL        9                                                          1GRM 124\n"
                           "ATOM      1  N   ALA A   1       1.500   2.000   3.000  1.00 10.00           N\n"
                           "ATOM      2  C   ALA A   1       2.500   2.000   3.000  1.00 10.00           C\n"
                           "ENDMDL\n"));
    vb_frame_reader *rd = NULL;
    CHECK_INT(vb_frame_reader_open(ctx, path, NULL, &rd), VB_OK);
    vb_sphere_set *s = NULL;
    int model = 0;
    CHECK_INT(vb_frame_reader_next(ctx, rd, &s, &model), VB_OK);
    CHECK(s && s->n == 1 && model == 4 && s->line[0] == 3);
    vb_spheres_free(s);
    CHECK_INT(vb_frame_reader_next(ctx, rd, &s, &model), VB_OK);
    CHECK(s && s->n == 2 && model == 9 && s->line[1] == 6);
    if (s)
        CHECK_DEC(s->ex[0], 15, -1);
    vb_spheres_free(s);
    CHECK_INT(vb_frame_reader_next(ctx, rd, &s, &model), VB_OK);
    CHECK(s == NULL);
    vb_frame_reader_close(rd);

    /* A bad line inside a frame is reported with its line in the file. */
    FILE *f = fopen(path, "w");
    fputs("MODEL        1\n"
          "ATOM      1  N   ALA A   1       1.000   2.000   3.000  1.00 10.00           N\n"
          "ENDMDL\nMODEL        2\n"
          "ATOM      1  N   ALA A   1       1.000   x.000   3.000  1.00 10.00           N\n"
          "ENDMDL\n",
          f);
    fclose(f);
    CHECK_INT(vb_frame_reader_open(ctx, path, NULL, &rd), VB_OK);
    CHECK_INT(vb_frame_reader_next(ctx, rd, &s, &model), VB_OK);
    vb_spheres_free(s);
    char prefix[80];
    snprintf(prefix, sizeof prefix, "%s:5:", path);
    CHECK_ERROR(ctx, vb_frame_reader_next(ctx, rd, &s, &model), VB_EINPUT_MALFORMED, prefix);
    vb_frame_reader_close(rd);

    /* mmCIF frames come from pdbx_PDB_model_num; PQR without MODEL is one. */
    const char *texts[2] = {cif_sample, pqr_sample};
    const size_t sizes[2][2] = {{4, 1}, {4, 0}};
    for (int k = 0; k < 2; k++) {
        f = fopen(path, "w");
        fputs(texts[k], f);
        fclose(f);
        CHECK_INT(vb_frame_reader_open(ctx, path, NULL, &rd), VB_OK);
        for (int fr = 0; fr < 3; fr++) {
            CHECK_INT(vb_frame_reader_next(ctx, rd, &s, &model), VB_OK);
            size_t want = fr < 2 ? sizes[k][fr] : 0;
            CHECK_INT(s ? s->n : 0, want);
            if (s)
                CHECK_INT(model, fr + 1);
            vb_spheres_free(s);
        }
        vb_frame_reader_close(rd);
    }
    remove(path);
    vb_close(ctx);
}

static vb_sphere_set *read_corpus(vb_ctx *ctx, const char *rel, const vb_read_options *o)
{
    vb_sphere_set *s = NULL;
    int rc = vb_spheres_read_file(ctx, corpus_path(rel), o, &s);
    CHECK_INT(rc, VB_OK);
    if (rc != VB_OK)
        fprintf(stderr, "  %s\n", vb_errmsg(ctx));
    return s;
}

static void test_real_files(void)
{
    vb_ctx *ctx = open_ctx(NULL);
    vb_sphere_set *pdb = read_corpus(ctx, "data/1crn.pdb", NULL);
    vb_sphere_set *cif = read_corpus(ctx, "data/1crn.cif", NULL);
    if (pdb && cif) {
        CHECK_INT(pdb->n, 327);
        CHECK_INT(cif->n, 327);
        size_t same = 0;
        for (size_t i = 0; i < pdb->n && i < cif->n; i++)
            same += vb_decimal_cmp(pdb->ex[i], cif->ex[i]) == 0 &&
                    vb_decimal_cmp(pdb->ey[i], cif->ey[i]) == 0 &&
                    vb_decimal_cmp(pdb->ez[i], cif->ez[i]) == 0 &&
                    vb_decimal_cmp(pdb->er[i], cif->er[i]) == 0 &&
                    strcmp(pdb->info[i].element, cif->info[i].element) == 0;
        CHECK_INT(same, 327);
        CHECK_DEC(pdb->ex[0], 17047, -3);
        CHECK_INT(pdb->line[0], 273);
        CHECK_INT(vb_spheres_validate(ctx, pdb, 4), VB_OK);
    }
    vb_spheres_free(pdb);
    vb_spheres_free(cif);

    vb_sphere_set *s = read_corpus(ctx, "data/1crn_apbs.pqr", NULL);
    if (s) {
        CHECK_INT(s->n, 642);
        CHECK_DEC(s->er[0], 2, 0);
        CHECK_DEC(s->er[2], 17, -1);
        /* PARSE radii give polar hydrogens radius 0 (the first is HG22 of
         * THR 1, line 15): kept as point sites, each inside its heavy atom. */
        CHECK_DEC(s->er[7], 0, 0);
        CHECK_INT(s->line[7], 15);
        CHECK_INT(vb_spheres_validate(ctx, s, 4), VB_OK);
        size_t contained = 0;
        for (size_t i = 0; i < s->n; i++)
            contained += s->contained[i];
        CHECK_INT(contained, 236);
    }
    vb_spheres_free(s);
    s = read_corpus(ctx, "data/3pqr.pqr", NULL);
    CHECK(s && s->n == 5352);
    vb_spheres_free(s);
    s = read_corpus(ctx, "data/4yvs_ev71_capsid.cif", NULL);
    if (s) {
        CHECK_INT(s->n, 26430);
        CHECK_INT(vb_spheres_validate(ctx, s, 4), VB_OK);
    }
    vb_spheres_free(s);
    s = read_corpus(ctx, "data/ngl_md_ascii_trj.pdb", NULL);
    CHECK(s && s->n == 183);
    vb_spheres_free(s);

    vb_frame_reader *rd = NULL;
    CHECK_INT(vb_frame_reader_open(ctx, corpus_path("data/ngl_md_ascii_trj.pdb"), NULL, &rd),
              VB_OK);
    int frames = 0, full = 0, model = 0, rc;
    while ((rc = vb_frame_reader_next(ctx, rd, &s, &model)) == VB_OK && s) {
        frames++;
        full += s->n == 183 && model == frames;
        vb_spheres_free(s);
    }
    CHECK_INT(rc, VB_OK);
    CHECK_INT(frames, 51);
    CHECK_INT(full, 51);
    vb_frame_reader_close(rd);
    vb_read_options o;
    memset(&o, 0, sizeof o);
    o.model = 7;
    CHECK_INT(vb_frame_reader_open(ctx, corpus_path("data/ngl_md_ascii_trj.pdb"), &o, &rd), VB_OK);
    CHECK_INT(vb_frame_reader_next(ctx, rd, &s, &model), VB_OK);
    CHECK(s && s->n == 183 && model == 7 && s->line[0] == 1146);
    vb_spheres_free(s);
    CHECK_INT(vb_frame_reader_next(ctx, rd, &s, &model), VB_OK);
    CHECK(s == NULL);
    vb_frame_reader_close(rd);
    vb_close(ctx);
}

/* Radius 0: points by default in PQR (PARSE polar hydrogens), an error by
 * default in XYZR, and --zero-radius error|point|drop overrides both. */
static void test_zero_radius(void)
{
    FILE *diag;
    vb_ctx *ctx = open_ctx(&diag);
    const char *pqr = "ATOM      1  N   GLY A   1       0.000   0.000   0.000 -0.4000 1.5000\n"
                      "ATOM      2  H   GLY A   1       1.000   0.000   0.000  0.4000 0.0000\n"
                      "ATOM      3  CA  GLY A   1       4.000   0.000   0.000  0.0000 1.7000\n"
                      "ATOM      4  C   GLY A   1       0.000   4.000   0.000  0.5500 1.7000\n"
                      "ATOM      5  O   GLY A   1       0.000   0.000   4.000 -0.5500 1.4000\n";
    vb_read_options o = {0};
    vb_sphere_set *s = NULL;
    CHECK_INT(read_text(ctx, "z.pqr", pqr, &o, &s), VB_OK);
    CHECK_INT(s->n, 5);
    CHECK(s->allows_zero_radius);
    CHECK_INT(s->er[1].mant, 0);
    CHECK_INT(vb_spheres_validate(ctx, s, 4), VB_OK);
    CHECK_INT(s->contained[1], 1); /* the point lies inside the nitrogen */
    CHECK(strstr(diag_text(diag), "W713") != NULL);
    vb_spheres_free(s);

    o.zero_radius = VB_ZERO_RADIUS_DROP;
    CHECK_INT(read_text(ctx, "z.pqr", pqr, &o, &s), VB_OK);
    CHECK_INT(s->n, 4);
    CHECK_INT(s->line[1], 3); /* the dropped atom's line is skipped, not renumbered */
    CHECK(strstr(diag_text(diag), "W712") != NULL);
    vb_spheres_free(s);

    o.zero_radius = VB_ZERO_RADIUS_ERROR;
    int rc = read_validate(ctx, "z.pqr", pqr, &o, 4);
    CHECK_ERROR(ctx, rc, VB_EINPUT_RADIUS, "z.pqr:2:");

    const char *xyzr = "0 0 0 1\n3 0 0 0\n0 3 0 1\n0 0 3 1\n";
    o.zero_radius = VB_ZERO_RADIUS_AUTO;
    rc = read_validate(ctx, "z.xyzr", xyzr, &o, 4);
    CHECK_ERROR(ctx, rc, VB_EINPUT_RADIUS, "z.xyzr:2:");
    o.zero_radius = VB_ZERO_RADIUS_POINT;
    CHECK_INT(read_validate(ctx, "z.xyzr", xyzr, &o, 4), VB_OK);
    /* Mostly points: the containment grid must still get a positive cell. */
    const char *points = "0 0 0 0\n3 0 0 0\n0 3 0 0\n0 0 3 1\n9 9 9 0\n";
    CHECK_INT(read_validate(ctx, "p.xyzr", points, &o, 4), VB_OK);
    const char *negative = "0 0 0 1\n3 0 0 -0.5\n0 3 0 1\n0 0 3 1\n";
    rc = read_validate(ctx, "n.xyzr", negative, &o, 4);
    CHECK_ERROR(ctx, rc, VB_EINPUT_RADIUS, "n.xyzr:2:");
    fclose(diag);
    vb_close(ctx);
}

int main(void)
{
    test_pdb();
    test_pqr();
    test_mmcif();
    test_detect();
    test_read_options_check();
    test_radii_file();
    test_frames_inline();
    test_real_files();
    test_zero_radius();
    VB_TEST_END();
}
