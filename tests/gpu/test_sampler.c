/* The sampling pipeline end to end on sphere sets built here: certified
 * output equals the exact reference, the OpenCL backend on a CPU device
 * (PoCL) equals the reference backend bit for bit, culled equals all-pairs
 * (same raw candidates, same output), and coarse sampling exercises the
 * targeted search (Sec. 5.5) without losing a vertex. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vb_test.h"
#include "vb_sampler.h"
#include "vb_verify.h"
#include "vb_vertices.h"
#include "vbg_runtime.h"
#include "vb_test_device.h"

static uint64_t lcg = 99;

static unsigned rnd(unsigned m)
{
    lcg = lcg * 6364136223846793005ull + 1442695040888963407ull;
    return (unsigned)((lcg >> 33) % m);
}

/* n atoms with 3-decimal coordinates in a 12 A box and protein-like radii. */
static char *random_set(int n)
{
    static const char *radii[] = {"1.7", "1.55", "1.52", "1.8", "1.2"};
    char *buf = malloc((size_t)n * 64 + 1), *p = buf;
    for (int k = 0; k < n; k++)
        p += sprintf(p, "%u.%03u %u.%03u %u.%03u %s\n", rnd(12), rnd(1000), rnd(12), rnd(1000),
                     rnd(12), rnd(1000), radii[rnd(5)]);
    return buf;
}

/* 3x3x3 cubic lattice of equal spheres: degree-8 vertices (Sec. 5.2). */
static char *lattice(void)
{
    char *buf = malloc(27 * 32 + 1), *p = buf;
    for (int i = 0; i < 27; i++)
        p += sprintf(p, "%d %d %d 0.3\n", i % 3, i / 3 % 3, i / 9);
    return buf;
}

static vb_sphere_set *load(vb_ctx *ctx, const char *text)
{
    vb_sphere_set *s = NULL;
    vb_read_options ro;
    memset(&ro, 0, sizeof ro);
    ro.format = VB_FMT_XYZR;
    if (vb_spheres_read_buffer(ctx, "test", text, strlen(text), &ro, &s) != VB_OK ||
        vb_spheres_validate(ctx, s, 4) != VB_OK) {
        fprintf(stderr, "load: %s\n", vb_errmsg(ctx));
        vb_spheres_free(s);
        return NULL;
    }
    return s;
}

static int same_list(const vb_vertex_list *a, const vb_vertex_list *b)
{
    if (a->n != b->n || a->nids != b->nids)
        return 0;
    for (size_t k = 0; k < a->n; k++)
        if (a->start[k + 1] != b->start[k + 1] || a->x[k] != b->x[k] || a->y[k] != b->y[k] ||
            a->z[k] != b->z[k] || a->t[k] != b->t[k])
            return 0;
    return memcmp(a->ids, b->ids, a->nids * sizeof *a->ids) == 0;
}

/* The library's pipeline with the OpenCL device layer and the exact
 * certifier, as the command wires them. */
static const vb_vertices_backends backends = {&vbg_device_layer, &vb_exact_certifier};

static int run(vb_ctx *ctx, vb_sphere_set *s, vb_device_kind kind, unsigned samples,
               int all_pairs, vb_vertices_result *r)
{
    vb_vertices_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.device = kind;
    cfg.proposer = "sampling"; /* these tests are about the ray sampling */
    cfg.propose.samples = samples;
    cfg.propose.all_pairs = all_pairs;
    vb_vertices_result_init(r);
    return vb_vertices_run(ctx, s, &cfg, &backends, r);
}

/* A backend awaited like a device still being set up: not ready for the
 * first `not_ready` polls; counts the batches it runs. */
typedef struct slow_device {
    vb_sampler_backend *ref;
    int polls, not_ready, batches;
    size_t largest;          /* bases of the largest batch */
} slow_device;

static slow_device *slow_of; /* the one the wrapper below forwards to */

static int slow_run(vb_ctx *ctx, vb_sampler_backend *be, const vb_sampler_batch *b,
                    vb_sampler_batch_out *out)
{
    (void)be;
    slow_of->batches++;
    if (b->nbases > slow_of->largest)
        slow_of->largest = b->nbases;
    return slow_of->ref->run_batch(ctx, slow_of->ref, b, out);
}

static vb_sampler_backend slow_be = {"slow", "slow", 0, 0, NULL, slow_run, NULL};

static vb_sampler_backend *slow_await(void *user)
{
    (void)user;
    return &slow_be;
}

static int slow_ready(void *user)
{
    slow_device *d = user;
    return ++d->polls > d->not_ready;
}

/* While the device is being set up, bases are culled an eighth of a batch
 * at a time and join the first batch, which grows past the plain size while
 * the device is not ready (at most VB_SAMPLER_MAX_AHEAD batches); then the
 * batches take the plain size again (the backend's choice), and the
 * candidates are those of batches of the plain size. */
static void check_cull_ahead(vb_ctx *ctx)
{
    char *text = random_set(60);
    vb_sphere_set *s = load(ctx, text);
    free(text);
    CHECK(s != NULL);
    if (!s)
        return;
    slow_device d = {NULL, 0, 5, 0, 0};
    CHECK_INT(vb_sampler_ref_open(ctx, &d.ref), VB_OK);
    slow_of = &d;
    vb_sampler_options o;
    memset(&o, 0, sizeof o);
    o.samples = 8;
    o.batch_rays = 6u * 8u * 8u * 4u; /* four bases per batch: 15 batches */
    vb_proposal plain, ahead;
    vb_proposal_init(&plain);
    vb_proposal_init(&ahead);
    CHECK_INT(vb_sampler_run(ctx, s, &o, d.ref, &plain), VB_OK);
    o.await_backend = slow_await;
    o.backend_ready = slow_ready;
    o.await_user = &d;
    CHECK_INT(vb_sampler_run(ctx, s, &o, NULL, &ahead), VB_OK);
    /* Polls 1-5 say "not ready": bases 0-5, culled one at a time, go to the
     * device as one batch; base 6 (culled one at a time too, while that
     * batch ran) is a batch of its own; the other 53 come four at a time. */
    CHECK_INT(d.largest, 6);
    CHECK_INT(d.batches, 1 + 1 + 14);
    CHECK_INT(ahead.raw_candidates, plain.raw_candidates);
    CHECK_INT(ahead.bisectors, plain.bisectors);
    CHECK(same_list(&plain.candidates, &ahead.candidates));
    /* A device that never gets ready: the first batch stops growing at
     * VB_SAMPLER_MAX_AHEAD batches. */
    d = (slow_device){d.ref, 0, 1000, 0, 0};
    vb_proposal_free(&ahead);
    CHECK_INT(vb_sampler_run(ctx, s, &o, NULL, &ahead), VB_OK);
    CHECK_INT(d.largest, 4 * VB_SAMPLER_MAX_AHEAD);
    CHECK(same_list(&plain.candidates, &ahead.candidates));
    vb_proposal_free(&plain);
    vb_proposal_free(&ahead);
    vb_sampler_backend_close(d.ref);
    vb_spheres_free(s);
}

static void check_set(vb_ctx *ctx, const char *name, char *text, int have_cpu)
{
    vb_sphere_set *s = load(ctx, text);
    free(text);
    CHECK(s != NULL);
    if (!s)
        return;
    vb_vertex_list ref;
    vb_vertex_list_init(&ref);
    CHECK_INT(vb_reference(ctx, s, &ref), VB_OK);
    vb_vertices_result a, b, c;
    CHECK_INT(run(ctx, s, VB_DEVICE_REF, 0, 0, &a), VB_OK);
    CHECK_INT(a.rejected.n, 0);
    CHECK(ref.n > 0);
    if (!same_list(&ref, &a.certified))
        fprintf(stderr, "%s: pipeline %zu vertices, reference %zu\n", name, a.certified.n, ref.n);
    CHECK(same_list(&ref, &a.certified));
    /* Culling is conservative: identical envelopes, so identical candidates. */
    CHECK_INT(run(ctx, s, VB_DEVICE_REF, 0, 1, &b), VB_OK);
    CHECK_INT(b.proposal.raw_candidates, a.proposal.raw_candidates);
    CHECK(b.proposal.bisectors > a.proposal.bisectors);
    CHECK(same_list(&a.certified, &b.certified));
    if (have_cpu) {
        CHECK_INT(run(ctx, s, VB_DEVICE_CPU, 0, 0, &c), VB_OK);
        CHECK_STR(c.backend, "opencl");
        CHECK_INT(c.proposal.raw_candidates, a.proposal.raw_candidates);
        CHECK(same_list(&a.certified, &c.certified));
        vb_vertices_result_free(&c);
    }
    vb_vertices_result_free(&b);
    /* Coarse sampling: cells miss vertices, the targeted search and the
     * completion recover them. */
    CHECK_INT(run(ctx, s, VB_DEVICE_REF, 6, 0, &b), VB_OK);
    CHECK(same_list(&ref, &b.certified));
    if (strcmp(name, "random") == 0)
        CHECK(b.proposal.targeted_found > 0);
    vb_vertices_result_free(&b);
    vb_vertices_result_free(&a);
    vb_vertex_list_free(&ref);
    vb_spheres_free(s);
}

int main(void)
{
    vb_config cfg = {0, NULL};
    vb_ctx *ctx;
    if (vb_open(&ctx, &cfg))
        return 1;
    int have_cpu = vb_test_have_cpu_device(ctx);
    if (!have_cpu)
        printf("no OpenCL CPU device: backend identity not tested here\n");
    check_set(ctx, "random", random_set(40), have_cpu);
    check_set(ctx, "lattice", lattice(), have_cpu);
    check_cull_ahead(ctx);
    /* Without a device the OpenCL request falls back to ref (W760). */
    vb_close(ctx);
    VB_TEST_END();
}
