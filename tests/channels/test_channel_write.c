/* #18 (9): the channel tables escape residue and chain names: the JSON
 * through the one JSON writer (quotes and backslashes escaped), the CSV
 * with RFC 4180 quoting of the lining-residues field (a name with a comma
 * or a quote stays one field). */
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vbc_channel.h"

/* Everything f received, NUL-terminated (caller frees). */
static char *slurp(FILE *f)
{
    long n = ftell(f);
    char *buf = calloc((size_t)n + 1, 1);
    rewind(f);
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n)
        buf[0] = '\0';
    return buf;
}

int main(void)
{
    vb_ctx *ctx;
    if (vb_open(&ctx, NULL) != VB_OK)
        return 1;
    vb_sphere_set *s = NULL;
    CHECK_INT(vb_spheres_new(ctx, "names", 2, 1, &s), VB_OK);
    strcpy(s->info[0].chain, "A");
    strcpy(s->info[0].resname, "G\"Y");
    s->info[0].resseq = 1;
    s->info[0].icode = ' ';
    strcpy(s->info[1].chain, "B,C");
    strcpy(s->info[1].resname, "A\\L");
    s->info[1].resseq = 2;
    s->info[1].icode = ' ';
    vbc_point pts[2] = {{0, 0, 0, 1.0, 0}, {1, 0, 0, 1.5, 1}};
    int32_t lining[2] = {0, 1};
    vbc_channel ch = {VBC_CHANNEL, VBC_WHY_THROUGH, 1, 10, 2, 1.0, 1.0, 0, 0, 2, 0, 2};
    vbc_result res;
    memset(&res, 0, sizeof res);
    res.nchannels = 1;
    res.channels = &ch;
    res.points = pts;
    res.lining = lining;
    res.components = 1;
    vbc_grid g = {16, 16, 16, 3, {0, 0, 0}, 1.0};
    vbc_frame_info fi = {0, 1, 2, 10, 0, 0, 0, 0, 0, 0};

    FILE *f = tmpfile();
    CHECK(f != NULL);
    vbc_write_csv_rows(f, &fi, &g, s, &res);
    char *csv = slurp(f);
    fclose(f);
    /* The last field, quoted, inner quote doubled; 22 fields in all. */
    CHECK(csv && strstr(csv, ",\"A:G\"\"Y1;B,C:A\\L2\",through: openings on opposite faces,,\n") != NULL);

    f = tmpfile();
    vbc_write_json_frame(f, 1, &fi, &g, s, &res);
    char *json = slurp(f);
    fclose(f);
    CHECK(json && strstr(json, "\"lining_residues\": [\"A:G\\\"Y1\",\"B,C:A\\\\L2\"]") != NULL);
    if (vb_test_failed)
        fprintf(stderr, "csv: %s\njson: %s\n", csv, json);
    free(csv);
    free(json);
    vb_spheres_free(s);
    vb_close(ctx);
    VB_TEST_END();
}
