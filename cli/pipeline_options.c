/* The options of the commands that run the vertex pipeline. */
#include "pipeline_options.h"

#include <limits.h>
#include <stdio.h>
#include <string.h>

#include "cli_common.h"

/* " sampling ...": the names of the library's proposers. */
static const char *proposer_names(void)
{
    static char buf[256];
    size_t n = 0;
    buf[0] = '\0';
    for (int k = 0; vb_proposers[k] && n < sizeof buf; k++)
        n += (size_t)snprintf(buf + n, sizeof buf - n, " %s", vb_proposers[k]->name);
    return buf;
}

void vb_pipeline_opts_defaults(vb_pipeline_opts *o)
{
    memset(o, 0, sizeof *o);
    vb_cli_input_defaults(&o->in);
    o->cfg.device = VB_DEVICE_AUTO;
}

int vb_pipeline_option(const char *cmd, int argc, char **argv, int *i, vb_pipeline_opts *o,
                       vb_ctx *ctx)
{
    int used = vb_cli_input_option(&o->in, argc, argv, i);
    if (used != 0)
        return used;
    vb_propose_options *so = &o->cfg.propose;
    const char *a = argv[*i];
    int has = *i + 1 < argc;
    if (strcmp(a, "--device") == 0) {
        if (!has || vb_device_kind_parse(ctx, argv[*i + 1], &o->cfg.device) != VB_OK) {
            vb_cli_usage_error(cmd, "--device needs auto, gpu, cpu or ref");
            return -1;
        }
        (*i)++;
        return 1;
    }
    /* The numbers: parsed here, their ranges the library's
     * (vb_propose_options_check). A value that does not parse (or an
     * explicit --threads 0) is stored as one the check refuses, so that its
     * message names the range. */
    unsigned *count = strcmp(a, "--samples") == 0   ? &so->samples
                      : strcmp(a, "--tiles") == 0   ? &so->tiles
                      : strcmp(a, "--threads") == 0 ? &so->threads
                                                    : NULL;
    if (count || strcmp(a, "--tol") == 0) {
        size_t v = 0;
        double t = 0.0;
        if (count && (!has || vb_cli_parse_size(argv[*i + 1], &v) || v == 0 || v > UINT_MAX))
            v = count == &so->samples ? 1u : count == &so->tiles ? 3u : UINT_MAX;
        if (!count && (!has || vb_cli_parse_double(argv[*i + 1], &t) || !(t > 0.0)))
            t = -1.0;
        if (count)
            *count = (unsigned)v;
        else
            so->tol = t;
        if (vb_propose_options_check(ctx, so) != VB_OK) {
            vb_cli_usage_error(cmd, "%s", vb_errmsg(ctx));
            return -1;
        }
        (*i)++;
        return 1;
    }
    if (strcmp(a, "--proposer") == 0) {
        if (!has || !vb_proposer_find(argv[*i + 1])) {
            vb_cli_usage_error(cmd, "--proposer needs one of:%s", proposer_names());
            return -1;
        }
        o->cfg.proposer = argv[++*i];
        return 1;
    }
    if (strcmp(a, "--all-pairs") == 0) {
        so->all_pairs = 1;
        return 1;
    }
    return 0;
}

