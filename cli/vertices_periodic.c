/* `vorball vertices --periodic`: options, the library call, the file. */
#include "vertices_periodic.h"

#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "vb_default.h"
#include "vb_periodic_frames.h"

static int is_number(const char *s)
{
    char *end;
    if (!*s)
        return 0;
    (void)strtod(s, &end);
    return *end == '\0';
}

int vb_cli_periodic_option(const char *cmd, int argc, char **argv, int *i, vb_cli_periodic *p)
{
    const char *a = argv[*i];
    if (strcmp(a, "--periodic") == 0) {
        p->on = 1;
        return 1;
    }
    /* Frames are `vertices`' alone (verify judges one file of one box). */
    if ((strcmp(a, "--traj") == 0 || strcmp(a, "--frames") == 0) && strcmp(cmd, "vertices") == 0) {
        if (*i + 1 >= argc) {
            vb_cli_usage_error(cmd, "%s needs a value", a);
            return -1;
        }
        const char *v = argv[++*i];
        if (a[2] == 't') {
            p->traj = v;
        } else if (vb_frame_range_parse(v, &p->range) != 0) {
            vb_cli_usage_error(cmd, "--frames '%s' is not A:B:S", v);
            return -1;
        } else {
            p->frames = 1;
        }
        p->on = 1;
        return 1;
    }
    if (strcmp(a, "--box") != 0)
        return 0;
    p->nbox = 0;
    while (*i + 1 < argc && p->nbox < 9 && is_number(argv[*i + 1]))
        p->box[p->nbox++] = argv[++*i];
    if (p->nbox != 3 && p->nbox != 6 && p->nbox != 9) {
        vb_cli_usage_error(cmd, "--box needs 3 numbers (a b c), 6 (a b c alpha beta gamma) or 9 "
                                "(the vectors a, b, c)");
        return -1;
    }
    p->on = 1;
    return 1;
}

void vb_cli_periodic_help(FILE *f)
{
    fprintf(f,
            "  --periodic           the periodic diagram of the box's atoms: the box of the\n"
            "                       file (GRO's last line, PDB's CRYST1) or --box; members\n"
            "                       written i@(dx,dy,dz) (atom i moved by dx a + dy b + dz c),\n"
            "                       each vertex once; see README 'Periodic boxes'\n"
            "  --box a b c [alpha beta gamma] | --box ax ay az bx by bz cx cy cz\n"
            "                       the periodic box (implies --periodic), in input units\n"
            "  --traj FILE          periodic, every frame of a DCD, XTC or TRR (the input is\n"
            "                       its topology), each in the box the frame carries\n"
            "  --frames A:B:S       periodic, frames A (from 0) to B (excluded) every S;\n"
            "                       one tsv, each frame after a line '# frame K (model M)'\n");
}

int vb_cli_periodic_box(vb_ctx *ctx, const vb_sphere_set *set, const vb_cli_periodic *p,
                        vb_box *box)
{
    if (p->nbox)
        return vb_box_parse_args(ctx, p->box, p->nbox, box);
    if (set->box) {
        *box = *set->box;
        return VB_OK;
    }
    return vb_error(ctx, VB_EINPUT_BOX, set->source, 0,
                    "--periodic: the input carries no box (GRO box line, PDB CRYST1): give --box");
}

int vb_cli_vertices_periodic(vb_ctx *ctx, const vb_sphere_set *set, const vb_cli_periodic *p,
                             const vb_vertices_config *cfg, const char *input,
                             const char *outpath, int json, int stats)
{
    vb_box box;
    int rc = vb_cli_periodic_box(ctx, set, p, &box);
    vb_periodic_result res;
    vb_periodic_result_init(&res);
    if (rc == VB_OK)
        rc = vb_periodic_vertices_run(ctx, set, &box, cfg, vb_default_backends(), &res);
    if (rc == VB_OK && stats) {
        vb_vertices_write_stats(ctx, stderr, &res.run);
        fprintf(stderr,
                "periodic_atoms\t%zu\nperiodic_spheres\t%zu\nperiodic_rho\t%.9g\n"
                "periodic_reach\t%.9g\nperiodic_vertices\t%zu\nperiodic_translates\t%zu\n"
                "periodic_beyond_rho\t%zu\nperiodic_layer_spheres\t%zu\n",
                res.img.n0, res.img.set->n, res.img.rho, res.img.reach, res.v.n, res.translates,
                res.beyond_rho, res.img.layer_spheres);
    }
    if (rc == VB_OK) {
        char note[1024];
        vb_periodic_certificate(&res, &box, note, sizeof note);
        char opts[4096];
        vb_provenance prov;
        vb_cli_provenance(&prov, opts, sizeof opts, input, set->n);
        FILE *out = vb_cli_open_output(ctx, outpath);
        rc = out ? vb_periodic_write_prov(ctx, out, &res.v, json, &prov, note) : vb_errcode(ctx);
        rc = vb_cli_finish_output(ctx, out, outpath, rc);
    }
    vb_periodic_result_free(&res);
    return rc;
}

typedef struct frames_sink {
    vb_ctx *ctx;
    FILE *out;
    int stats;
} frames_sink;

static int write_frame(void *arg, long frame, int model, const vb_sphere_set *set,
                       const vb_box *box, const vb_periodic_result *res)
{
    frames_sink *S = arg;
    (void)set;
    char note[1024];
    vb_periodic_certificate(res, box, note, sizeof note);
    fprintf(S->out, "# frame %ld (model %d)\n", frame, model);
    if (S->stats)
        fprintf(stderr, "frame\t%ld\tperiodic_spheres\t%zu\tperiodic_vertices\t%zu\n", frame,
                res->img.set ? res->img.set->n : 0, res->v.n);
    return vb_periodic_write(S->ctx, S->out, &res->v, 0, note);
}

int vb_cli_vertices_periodic_frames(vb_ctx *ctx, const char *input, const vb_cli_input_opts *in,
                                    const vb_cli_periodic *p, const vb_vertices_config *cfg,
                                    const char *outpath, int stats)
{
    vb_box box;
    int rc = p->nbox ? vb_box_parse_args(ctx, p->box, p->nbox, &box) : VB_OK;
    vb_radii_table *radii = NULL;
    if (rc == VB_OK && in->radii_path)
        rc = vb_radii_load(ctx, in->radii_path, &radii);
    vb_read_options ro;
    vb_cli_input_read_options(in, radii, &ro);
    vb_frame_range all = {0, -1, 1};
    frames_sink S = {ctx, NULL, stats};
    if (rc == VB_OK && !(S.out = vb_cli_open_output(ctx, outpath)))
        rc = vb_errcode(ctx);
    if (rc == VB_OK) {
        char opts[4096];
        vb_provenance prov;
        vb_cli_provenance(&prov, opts, sizeof opts, input, 0);
        vb_periodic_vertices none;
        memset(&none, 0, sizeof none);
        size_t zero = 0;
        none.start = &zero;
        rc = vb_periodic_write_prov(ctx, S.out, &none, 0, &prov, "periodic frames");
    }
    if (rc == VB_OK)
        rc = vb_periodic_run_frames(ctx, input, p->traj, &ro, p->frames ? &p->range : &all,
                                    p->nbox ? &box : NULL, cfg, write_frame, &S, NULL);
    if (S.out)
        rc = vb_cli_finish_output(ctx, S.out, outpath, rc);
    vb_radii_free(radii);
    return rc;
}
