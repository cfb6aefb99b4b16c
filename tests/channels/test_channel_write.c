/* #18 (9): the channel tables escape residue and chain names: the JSON
 * through the one JSON writer (quotes and backslashes escaped), the CSV
 * with RFC 4180 quoting of the lining-residues field (a name with a comma
 * or a quote stays one field). #33: each JSON frame carries its per-stage
 * clocks, "ms" and the closing "clock", with exactly their keys in order,
 * and no other byte of the frame depends on what the clocks read. */
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vb_parallel.h"
#include "vb_stage_clock.h"
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

/* The keys of the flat object that follows `name` in json, space-separated,
 * into out (empty when there is no such object). */
static void object_keys(const char *json, const char *name, char *out, size_t len)
{
    out[0] = '\0';
    const char *p = strstr(json, name);
    if (!p || !(p = strchr(p, '{')))
        return;
    const char *end = strchr(p, '}');
    size_t o = 0;
    while (end && (p = strchr(p, '"')) && p < end) {
        const char *q = strchr(p + 1, '"');
        if (!q || o + (size_t)(q - p) + 1 >= len)
            return;
        o += (size_t)snprintf(out + o, len - o, "%s%.*s", o ? " " : "", (int)(q - p - 1), p + 1);
        p = q + 1;
    }
}

/* json without the flat object that follows `name` (in place). */
static void drop_object(char *json, const char *name)
{
    char *p = strstr(json, name), *e = p ? strchr(p, '}') : NULL;
    if (e)
        memmove(p, e + 1, strlen(e + 1) + 1);
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
    vbc_frame_info fi = {.frame = 0, .model = 1, .atoms = 2, .channel_voxels = 10};

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
    char keys[512];
    object_keys(json, "\"ms\":", keys, sizeof keys);
    CHECK_STR(keys, "read prepare upload jfa masks analysis graph voxels clear trace cells refine sweep verdict lining pore beside total");
    CHECK_STR(keys, VBC_JSON_MS_KEYS);
    object_keys(json, "\"clock\":", keys, sizeof keys);
    CHECK_STR(keys, "write frame fps cpu");
    CHECK_STR(keys, VBC_JSON_CLOCK_KEYS);
    /* The clock closes the frame object. */
    const char *clock = json ? strstr(json, "\"clock\":") : NULL;
    CHECK(clock && strcmp(strchr(clock, '}'), "}}") == 0);

    /* Other timings, and a start time: the same bytes besides the clocks. */
    vbc_frame_info fi2 = fi;
    fi2.ms_read = 12.5;
    fi2.ms_jfa = 3.25;
    fi2.ms_verdict = 7.0;
    fi2.ms_total = 99.0;
    fi2.t_start = vb_now() - 0.25;
    fi2.cpu_start = vb_cpu_now();
    f = tmpfile();
    vbc_write_json_frame(f, 1, &fi2, &g, s, &res);
    char *json2 = slurp(f);
    fclose(f);
    CHECK(json2 && strstr(json2, "\"read\": 12.500, \"prepare\": 0.000") != NULL);
    CHECK(json2 && strstr(json2, "\"verdict\": 7.000") != NULL);
    /* End to end from t_start: at least the 250 ms before the call. */
    const char *fr = json2 ? strstr(json2, "\"frame\": ") : NULL;
    fr = fr ? strstr(fr + 1, "\"frame\": ") : NULL; /* the clock's, not the frame index */
    CHECK(fr && atof(fr + 9) >= 250.0 && atof(fr + 9) < 60000.0);
    if (json && json2) {
        CHECK(strcmp(json, json2) != 0);
        drop_object(json, "\"ms\":");
        drop_object(json, "\"clock\":");
        drop_object(json2, "\"ms\":");
        drop_object(json2, "\"clock\":");
        CHECK_STR(json, json2);
    }
    free(json2);
    if (vb_test_failed)
        fprintf(stderr, "csv: %s\njson: %s\n", csv, json);
    free(csv);
    free(json);
    vb_spheres_free(s);
    vb_close(ctx);
    VB_TEST_END();
}
