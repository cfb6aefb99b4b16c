/* Unit tests of the context: errors, extended codes, warnings, counters. */
#include <stdio.h>
#include <stdlib.h>

#include "vb.h"
#include "vb_diag.h"
#include "vb_test.h"
#include "vb_vertex.h"

static void test_errors(void)
{
    vb_ctx *ctx;
    CHECK_INT(vb_open(&ctx, NULL), VB_OK);
    CHECK_STR(vb_errmsg(ctx), "");
    int rc = vb_error(ctx, VB_EINPUT_RADIUS, "a.xyzr", 7, "radius %s is not positive", "-1");
    CHECK_INT(rc, VB_EINPUT_RADIUS);
    CHECK_INT(VB_CATEGORY(rc), VB_EINPUT);
    CHECK_INT(vb_diag_number(rc), 103);
    CHECK_INT(vb_diag_number(VB_EDEVICE), 5);
    CHECK_STR(vb_errmsg(ctx), "a.xyzr:7: radius -1 is not positive");
    CHECK_INT(vb_errcode(ctx), VB_EINPUT_RADIUS);
    vb_clear_error(ctx);
    CHECK_INT(vb_errcode(ctx), VB_OK);
    vb_close(ctx);
}

static void test_warnings_counted(void)
{
    FILE *sink = tmpfile();
    vb_config cfg = {.verbosity = 1, .diag = sink};
    vb_ctx *ctx;
    CHECK_INT(vb_open(&ctx, &cfg), VB_OK);
    vb_warn(ctx, VB_W_CONTAINED, "x.pdb", 3, "sphere %d is contained", 2);
    CHECK_INT(vb_ctx_stats(ctx)->warnings, 1);
    rewind(sink);
    char buf[128] = {0};
    CHECK(fgets(buf, sizeof buf, sink) != NULL);
    CHECK_STR(buf, "vorball: W701: x.pdb:3: sphere 2 is contained\n");
    fclose(sink);
    vb_close(ctx);
}

/* Quiet while reading what another process warns about already (MPI ranks
 * reading one input), loud again after; the warnings still count. */
static void test_verbosity(void)
{
    FILE *sink = tmpfile();
    vb_config cfg = {.verbosity = 1, .diag = sink};
    vb_ctx *ctx;
    CHECK_INT(vb_open(&ctx, &cfg), VB_OK);
    int old = vb_set_verbosity(ctx, 0);
    CHECK_INT(old, 1);
    vb_warn(ctx, VB_W_CONTAINED, NULL, 0, "quiet");
    CHECK_INT(vb_set_verbosity(ctx, old), 0);
    vb_warn(ctx, VB_W_CONTAINED, NULL, 0, "loud");
    CHECK_INT(vb_ctx_stats(ctx)->warnings, 2);
    rewind(sink);
    char buf[128] = {0};
    CHECK(fgets(buf, sizeof buf, sink) != NULL);
    CHECK_STR(buf, "vorball: W701: loud\n");
    CHECK(fgets(buf, sizeof buf, sink) == NULL);
    CHECK_INT(vb_set_verbosity(NULL, 1), -1);
    fclose(sink);
    vb_close(ctx);
}

/* The log callback: records (number, severity, file, line, message) in
 * place of the text, nothing on the stream; NULL restores the text. */
typedef struct kept {
    int n;
    char kind[4];
    int number[4];
    long line[4];
    char file[4][32], message[4][64];
} kept;

static void keep(void *arg, const vb_diag_record *r)
{
    kept *k = arg;
    if (k->n == 4)
        return;
    k->kind[k->n] = r->kind;
    k->number[k->n] = r->number;
    k->line[k->n] = r->line;
    snprintf(k->file[k->n], sizeof k->file[0], "%s", r->file ? r->file : "(none)");
    snprintf(k->message[k->n], sizeof k->message[0], "%s", r->message);
    k->n++;
}

static void test_log_callback(void)
{
    FILE *sink = tmpfile();
    vb_config cfg = {.verbosity = 2, .diag = sink};
    vb_ctx *ctx;
    kept k = {0};
    CHECK_INT(vb_open(&ctx, &cfg), VB_OK);
    CHECK_INT(vb_set_log(ctx, keep, &k), VB_OK);
    vb_warn(ctx, VB_W_CONTAINED, "x.pdb", 3, "sphere %d is contained", 2);
    vb_warn(ctx, VB_W_CERT_REJECTED, NULL, 0, "rejected %d", 5);
    vb_warn(ctx, VB_W_CONTAINED, "y.pdb", 0, "no line");
    vb_info(ctx, "info %s", "line");
    CHECK_INT(k.n, 4);
    CHECK_INT(k.kind[0], 'W');
    CHECK_INT(k.number[0], 701);
    CHECK_STR(k.file[0], "x.pdb");
    CHECK_INT(k.line[0], 3);
    CHECK_STR(k.message[0], "sphere 2 is contained");
    CHECK_INT(k.number[1], 763);
    CHECK_STR(k.file[1], "(none)");
    CHECK_STR(k.message[1], "rejected 5");
    CHECK_STR(k.file[2], "y.pdb");
    CHECK_INT(k.line[2], 0);
    CHECK_INT(k.kind[3], 'I');
    CHECK_INT(k.number[3], 0);
    CHECK_STR(k.message[3], "info line");
    CHECK_INT(vb_ctx_stats(ctx)->warnings, 3);
    CHECK_INT(ftell(sink), 0); /* nothing printed */
    CHECK_INT(vb_set_log(ctx, NULL, NULL), VB_OK);
    vb_warn(ctx, VB_W_CONTAINED, NULL, 0, "text again");
    CHECK_INT(k.n, 4);
    rewind(sink);
    char buf[128] = {0};
    CHECK(fgets(buf, sizeof buf, sink) != NULL);
    CHECK_STR(buf, "vorball: W701: text again\n");
    CHECK_INT(vb_set_log(NULL, keep, &k), VB_EMISUSE);
    /* The error as a record: its number, location and message apart. */
    vb_diag_record er;
    vb_error(ctx, VB_EINPUT_RADIUS, "a.xyzr", 7, "radius %s is not positive", "-1");
    CHECK_INT(vb_error_record(ctx, &er), VB_OK);
    CHECK_INT(er.kind, 'E');
    CHECK_INT(er.number, 103);
    CHECK_STR(er.file, "a.xyzr");
    CHECK_INT(er.line, 7);
    CHECK_STR(er.message, "radius -1 is not positive");
    CHECK_STR(vb_errmsg(ctx), "a.xyzr:7: radius -1 is not positive");
    vb_error(ctx, VB_EIO, NULL, 0, "plain");
    CHECK_INT(vb_error_record(ctx, &er), VB_OK);
    CHECK(er.file == NULL && er.line == 0);
    CHECK_STR(er.message, "plain");
    vb_clear_error(ctx);
    CHECK_INT(vb_error_record(ctx, &er), VB_OK);
    CHECK_INT(er.number, 0);
    CHECK_STR(er.message, "");
    CHECK_INT(vb_error_record(NULL, &er), VB_EMISUSE);
    fclose(sink);
    vb_close(ctx);
}

/* The misuse guard: a NULL context is caught, never dereferenced. */
/* What a progress callback saw. */
typedef struct seen {
    int calls, last_stage_b;
    uint64_t done[4096], total;
} seen;

static void keep_progress(void *user, const char *stage, uint64_t done, uint64_t total)
{
    seen *s = user;
    if (stage[0] == 'b')
        s->last_stage_b = 1;
    if (s->calls < 4096 && stage[0] == 'a')
        s->done[s->calls++] = done;
    s->total = total;
}

/* vb_progress: at most one call per new 1/1000 of total and the last one
 * always; never backwards; a worker context forwards to its owner; no
 * callback, no call. */
static void test_progress(void)
{
    vb_ctx *ctx, *worker;
    CHECK_INT(vb_open(&ctx, NULL), VB_OK);
    CHECK_INT(vb_open(&worker, NULL), VB_OK);
    vb_progress(ctx, "a", 1, 10); /* nothing installed: nothing happens */
    static seen s;
    CHECK_INT(vb_set_progress(ctx, keep_progress, &s), VB_OK);
    vb_progress_forward(worker, ctx);
    const uint64_t total = 1000000;
    vb_progress(ctx, "a", 0, total);
    for (uint64_t d = 1; d <= total; d++)
        vb_progress(d % 2 ? worker : ctx, "a", d, total);
    CHECK(s.calls >= 1000 && s.calls <= 1002);
    CHECK_INT((long)s.done[0], 0);
    CHECK_INT((long)s.done[s.calls - 1], (long)total);
    int up = 1;
    for (int k = 1; k < s.calls; k++)
        up &= s.done[k] > s.done[k - 1];
    CHECK(up);
    int before = s.calls;
    vb_progress(worker, "a", 5, total); /* backwards: dropped */
    CHECK_INT(s.calls, before);
    vb_progress(ctx, "b", 1, 2);        /* another stage is reported */
    CHECK(s.last_stage_b);
    vb_progress(ctx, "a", 0, 7);        /* 0 starts a run of the stage again */
    CHECK_INT(s.calls, before + 1);
    CHECK_INT((long)s.total, 7);
    CHECK_INT(vb_set_progress(ctx, NULL, NULL), VB_OK);
    vb_progress(ctx, "a", 7, 7);
    CHECK_INT(s.calls, before + 1);
    CHECK_INT(vb_set_progress(NULL, keep_progress, &s), VB_EMISUSE);
    vb_close(worker);
    vb_close(ctx);
}

static void test_misuse(void)
{
    CHECK_INT(vb_ctx_check(NULL), VB_EMISUSE);
    CHECK_INT(vb_warn(NULL, VB_W_CONTAINED, "x.pdb", 3, "sphere %d", 2), VB_EMISUSE);
    CHECK_INT(vb_errcode(NULL), VB_EMISUSE);
    CHECK_INT(vb_error(NULL, VB_EINPUT, NULL, 0, "no context"), VB_EINPUT);
    CHECK(vb_ctx_stats(NULL) == NULL);
    CHECK(vb_errmsg(NULL)[0] != '\0');
    vb_clear_error(NULL);
    vb_info(NULL, "nothing");
    vb_close(NULL);
    vb_ctx *ctx;
    CHECK_INT(vb_open(&ctx, NULL), VB_OK);
    CHECK_INT(vb_ctx_check(ctx), VB_OK);
    vb_close(ctx);
}

static void test_vertex_sort(void)
{
    vb_vertex_list v;
    vb_vertex_list_init(&v);
    uint32_t a[] = {4, 1, 3, 2}, b[] = {0, 1, 2, 3, 9}, c[] = {1, 2, 3, 4};
    CHECK_INT(vb_vertex_list_push(&v, a, 4, 2.0, 0, 0, 0, 0, VB_VERTEX_CERTIFIED), VB_OK);
    CHECK_INT(vb_vertex_list_push(&v, b, 5, 0, 0, 0, 0, 0, VB_VERTEX_CERTIFIED), VB_OK);
    CHECK_INT(vb_vertex_list_push(&v, c, 4, 1.0, 0, 0, 0, 0, VB_VERTEX_CERTIFIED), VB_OK);
    CHECK_INT(vb_vertex_list_sort(&v), VB_OK);
    CHECK_INT(v.n, 3);
    CHECK_INT(v.ids[0], 0);
    CHECK_INT(v.start[1], 5);
    CHECK_INT(v.ids[5], 1);
    CHECK_INT(v.ids[8], 4);
    CHECK(v.x[1] == 1.0 && v.x[2] == 2.0);
    vb_vertex_list_free(&v);
}

int main(void)
{
    test_errors();
    test_warnings_counted();
    test_verbosity();
    test_log_callback();
    test_progress();
    test_misuse();
    test_vertex_sort();
    VB_TEST_END();
}
