/* The --stats table (core/vb_stat_field.h): a vertex run's and its arc
 * closure's counters fit one table, in the command's order, typed, and the
 * one loop prints each as its line. */
#include "vb_arc.h"
#include "vb_test.h"
#include "vb_vertices.h"

/* The text vb_stat_fields_write gives for fields [from, n). */
static char *written(const vb_stat_fields *fs, size_t from)
{
    static char buf[8192];
    FILE *f = tmpfile();
    if (!f)
        return NULL;
    vb_stat_fields_write(f, fs, from);
    rewind(f);
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

int main(void)
{
    vb_vertices_result r;
    vb_vertices_result_init(&r);
    snprintf(r.backend, sizeof r.backend, "ref");
    snprintf(r.device, sizeof r.device, "host");
    r.proposal.samples = 7;
    r.proposal.tol = 0.05;
    r.proposal.device_bytes_peak = 123456789012ull;
    r.proposal.t_cert_filter = 0.25;
    r.certify_parts = 3;
    r.max_dist = 1.23456;
    vb_arc_report a;
    memset(&a, 0, sizeof a);
    a.half_arcs = 720024;
    a.trace_s = 1.7774;
    a.threads = 2;

    vb_stat_fields fs;
    fs.n = 0;
    vb_vertices_stats(NULL, &r, &fs); /* no context: zero filter counters */
    size_t nv = fs.n;
    vb_arc_stats(&a, &fs);
    CHECK_INT(nv, 104); /* 43, the cover's device timers (21), its steps' work (20),
                         * what its first tier's arenas held (4) and host steps (8), the
                         * run's clock (6: its host work before the device, set-up, wait,
                         * proposer, run, release) and its neighbour records (2) */
    CHECK_INT(fs.n, nv + 19);
    CHECK(fs.n < VB_STAT_FIELDS_MAX); /* room left: nothing was dropped */

    CHECK(strcmp(fs.f[0].name, "backend") == 0 && fs.f[0].kind == VB_STAT_TEXT &&
          strcmp(fs.f[0].s, "ref") == 0);
    CHECK(strcmp(fs.f[2].name, "samples") == 0 && fs.f[2].kind == VB_STAT_UINT &&
          fs.f[2].u == 7);
    CHECK(strcmp(fs.f[4].name, "tol") == 0 && fs.f[4].kind == VB_STAT_REAL &&
          fs.f[4].x == 0.05);
    CHECK(strcmp(fs.f[nv - 1].name, "judge_s") == 0 && fs.f[nv - 1].x == 0.25);
    CHECK(strcmp(fs.f[nv].name, "arc_half_arcs") == 0 && fs.f[nv].u == 720024);

    const char *t = written(&fs, 0);
    CHECK(t && strncmp(t, "backend\tref\ndevice\thost\nsamples\t7\ntiles\t0\ntol\t0.05\n", 50) == 0);
    CHECK(t && strstr(t, "\nmax_candidate_distance\t1.23\n"));
    CHECK(t && strstr(t, "\ndevice_bytes_peak\t123456789012\n"));
    CHECK(t && strstr(t, "\ncertify_parts\t3\ncertify_overlap_s\t0.000000\n"));
    CHECK(t && strstr(t, "\njudge_s\t0.250000\narc_half_arcs\t720024\n"));
    CHECK(t && strstr(t, "\narc_threads\t2\n") && strstr(t, "\narc_trace_s\t1.777\n"));
    /* from: the arc lines alone, as vb_arc_write_stats prints them */
    t = written(&fs, nv);
    CHECK(t && strncmp(t, "arc_half_arcs\t720024\narc_closed\t0\n", 33) == 0);

    /* a full table keeps its first entries */
    vb_stat_fields full;
    full.n = 0;
    for (int i = 0; i < VB_STAT_FIELDS_MAX + 5; i++)
        vb_stat_uint(&full, "x", (uint64_t)i);
    CHECK_INT(full.n, VB_STAT_FIELDS_MAX);
    CHECK_INT(full.f[VB_STAT_FIELDS_MAX - 1].u, VB_STAT_FIELDS_MAX - 1);
    vb_vertices_result_free(&r);
    VB_TEST_END();
}
