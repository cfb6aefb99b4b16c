/* The ray sampling of the seed paper behind the proposer table: the
 * sampling backend on a device (the device layer's sampler_open) or the
 * plain-C reference backend, run by vb_sampler_run. */
#include <stdint.h>
#include <string.h>

#include "vb_sampler.h"

static int sampling_open(vb_ctx *ctx, const vb_device_layer *layer, vb_device *dev, void **state)
{
    vb_sampler_backend *be = NULL;
    int rc = dev ? layer->sampler_open(ctx, dev, &be) : vb_sampler_ref_open(ctx, &be);
    *state = be;
    return rc;
}

static vb_sampler_backend *await_backend(void *user)
{
    const vb_proposer_await *aw = user;
    return aw->state(aw->user);
}

static int backend_ready(void *user)
{
    const vb_proposer_await *aw = user;
    return aw->ready(aw->user);
}

static int sampling_run(vb_ctx *ctx, void *state, const vb_proposer_await *aw,
                        const vb_sphere_set *set, const vb_propose_args *args,
                        vb_proposal *res)
{
    const vb_propose_options *p = &args->opt;
    vb_sampler_options o;
    memset(&o, 0, sizeof o);
    o.samples = p->samples;
    o.tiles = p->tiles;
    o.tol = p->tol;
    o.all_pairs = p->all_pairs;
    o.topology = p->topology;
    o.threads = p->threads;
    if (!state) {
        o.await_backend = await_backend;
        o.backend_ready = backend_ready;
        o.await_user = (void *)aw;
        /* The batch size cannot wait for the device: a GPU unless a CPU
         * device was asked for; the output does not depend on it. */
        if (!o.batch_rays)
            o.batch_rays = vb_sampler_batch_rays(aw->kind != VB_DEVICE_CPU);
    }
    int rc = vb_sampler_run(ctx, set, &o, state, res);
    const vb_sampler_backend *be = state                       ? state
                                   : backend_ready((void *)aw) ? await_backend((void *)aw)
                                                               : NULL;
    res->device_bytes_peak = rc == VB_OK && be ? be->device_bytes_peak : 0;
    return rc;
}

static const char *sampling_backend(const void *state)
{
    return ((const vb_sampler_backend *)state)->name;
}

static const char *sampling_device(const void *state)
{
    return ((const vb_sampler_backend *)state)->device;
}

static void sampling_close(void *state)
{
    vb_sampler_backend_close(state);
}

const vb_proposer vb_proposer_sampling = {
    "sampling", sampling_open, sampling_run, sampling_backend, sampling_device, sampling_close,
};
