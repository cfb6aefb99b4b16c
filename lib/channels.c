/* The channels handle (vb_channels.h): the option table read and set by
 * name, the engine, one frame, and the accessors and writers of its
 * result. The run over frames is lib/channels_frames.c. */
#include <stdlib.h>
#include <string.h>

#include "channels_handle.h"
#include "vb_default.h"

_Static_assert((int)VB_CHANNELS_HELP_MAIN == (int)VBC_SECT_MAIN &&
                   (int)VB_CHANNELS_HELP_PORE == (int)VBC_SECT_PORE,
               "vb_channels_help_section follows vbc_opt_section");
_Static_assert(VB_CHANNEL_F_ATOMIC == VBC_F_ATOMIC && VB_CHANNEL_F_MOLECULAR == VBC_F_MOLECULAR &&
                   VB_CHANNEL_F_EDGE == VBC_F_EDGE && VB_CHANNEL_F_INTERIOR == VBC_F_INTERIOR &&
                   VB_CHANNEL_F_CHANNEL == VBC_F_CHANNEL && VB_CHANNEL_F_MOUTH == VBC_F_MOUTH,
               "VB_CHANNEL_F_* are the VBC_F_* bits");

size_t vb_channels_option_count(void)
{
    size_t n;
    vbc_channels_options(&n);
    return n;
}

int vb_channels_option_at(size_t k, vb_channels_option *o)
{
    size_t n;
    const vbc_opt_spec *t = vbc_channels_options(&n);
    if (k >= n)
        return -1;
    *o = t[k];
    return 0;
}

/* The table's entry for a command-line spelling or a Python keyword. */
static const vbc_opt_spec *spec_of(const char *name)
{
    if (!name)
        return NULL;
    return name[0] == '-' ? vbc_channels_option(name) : vbc_channels_option_py(name);
}

int vb_channels_option_find(const char *name, vb_channels_option *o)
{
    const vbc_opt_spec *s = spec_of(name);
    if (!s)
        return -1;
    *o = *s;
    return 0;
}

void vb_channels_help(FILE *f, int section)
{
    vbc_channels_help(f, section);
}

const char *vb_channels_columns_help(void)
{
    return vbc_table_columns_help();
}

int vb_channels_new(vb_ctx *ctx, vb_channels **out)
{
    *out = calloc(1, sizeof **out);
    if (!*out)
        return vb_error(ctx, VB_ENOMEM, NULL, 0, "channels handle");
    vbc_channels_defaults(&(*out)->cfg);
    return VB_OK;
}

void vb_channels_drop_run(vb_channels *ch)
{
    if (ch->have_out)
        vbc_run_frame_done(&ch->run, 0, &ch->out);
    ch->have_out = 0;
    ch->s0 = NULL;
    if (ch->run_live)
        vbc_run_free(&ch->run);
    ch->run_live = 0;
    vbc_image_free(&ch->stages);
    memset(&ch->stages, 0, sizeof ch->stages);
    vb_page_free(ch->page);
    ch->page = NULL;
}

void vb_channels_free(vb_channels *ch)
{
    if (!ch)
        return;
    vb_channels_drop_run(ch);
    vbc_pipe_close(ch->pipe);
    free(ch);
}

int vb_channels_set(vb_channels *ch, const char *name, const char *value, char *err,
                    size_t errlen)
{
    const vbc_opt_spec *o = spec_of(name);
    if (!o) {
        snprintf(err, errlen, "unknown channels option '%s'", name ? name : "");
        return -1;
    }
    return vbc_channels_set(&ch->cfg, o, o->type == VB_OPT_FLAG ? NULL : value, err, errlen);
}

int vb_channels_check(vb_channels *ch, char *err, size_t errlen)
{
    return vbc_channels_check(&ch->cfg, err, errlen);
}

void vb_channels_reset(vb_channels *ch)
{
    vbc_channels_defaults(&ch->cfg);
}

void vb_channels_request_get(const vb_channels *ch, vb_channels_request *r)
{
    const vbc_channels_config *c = &ch->cfg;
    memset(r, 0, sizeof *r);
    r->out = c->out;
    r->traj = c->traj;
    r->centrelines = c->centrelines;
    r->pymol = c->pymol;
    r->volume = c->volume;
    r->stats = c->stats;
    r->png = c->png;
    r->profile = c->profile;
    r->plot = c->plot;
    r->occupancy = c->occupancy;
    r->html = c->html;
    r->json = c->json;
    r->stats_stderr = c->stats_stderr;
    r->fixed_grid = c->fixed_grid;
    r->f0 = c->f0;
    r->f1 = c->f1;
    r->fstep = c->fstep;
}

int vb_channels_open(vb_ctx *ctx, vb_channels *ch)
{
    if (ch->pipe)
        return VB_OK;
    const vb_device_layer *layer = vb_default_devices();
    return vbc_pipe_open(ctx, layer, vbc_channels_device(ch->cfg.device, layer), ch->cfg.variant,
                         &ch->pipe);
}

const char *vb_channels_device_name(const vb_channels *ch)
{
    return ch->pipe ? vbc_pipe_device_name(ch->pipe) : "";
}

/* An engine's later frames sweep the axis its first frame found, unless
 * the frame's options give an axis or the through-path; the sweep's own
 * options are the frame's. */
static void carry_apply(vb_channels *ch)
{
    vbc_channels_config *cfg = &ch->cfg;
    if (!ch->have_carry || cfg->pore.have_axis || cfg->pore.have_through)
        return;
    vbc_pore_options sweep = cfg->pore.sweep;
    int enabled = cfg->pore.enabled;
    cfg->pore = ch->carry_pore;
    cfg->refit0 = ch->carry_refit0;
    memcpy(cfg->u0, ch->carry_u0, sizeof cfg->u0);
    memcpy(cfg->c0, ch->carry_c0, sizeof cfg->c0);
    cfg->pore.sweep = sweep;
    cfg->pore.enabled = enabled;
}

static void carry_keep(vb_channels *ch)
{
    const vbc_channels_config *cfg = &ch->cfg;
    if (!cfg->pore.have_axis)
        return;
    ch->have_carry = 1;
    ch->carry_pore = cfg->pore;
    ch->carry_refit0 = cfg->refit0;
    memcpy(ch->carry_u0, cfg->u0, sizeof ch->carry_u0);
    memcpy(ch->carry_c0, cfg->c0, sizeof ch->carry_c0);
}

int vb_channels_run(vb_ctx *ctx, vb_channels *ch, const vb_sphere_set *s, long index, int model,
                    int first, unsigned flags)
{
    vb_channels_drop_run(ch);
    if (!ch->pipe)
        return vb_error(ctx, VB_EMISUSE, NULL, 0, "channels: no engine (vb_channels_open)");
    if (!(flags & VB_CHANNELS_CARRY_AXIS))
        ch->have_carry = 0;
    carry_apply(ch);
    vbc_run_init(&ch->run, &ch->cfg, ch->pipe, s->source);
    ch->run_live = 1;
    ch->run.want = flags & VB_CHANNELS_KEEP_FLAGS ? VBC_WANT_FLAGS | VBC_WANT_EDGES : 0; /* every bit of every voxel */
    ch->run.frames_total = 1; /* one frame a call: progress ("frames", 1, 1) */
    int rc = vbc_run_frame(ctx, &ch->run, s, index, model, first, &ch->out);
    if (rc == VB_OK)
        vbc_run_report_left_out(ctx, &ch->run);
    if (rc != VB_OK) {
        vb_channels_drop_run(ch);
        return rc;
    }
    ch->have_out = 1;
    ch->keep_flags = (flags & VB_CHANNELS_KEEP_FLAGS) != 0;
    ch->s0 = s;
    if (flags & VB_CHANNELS_CARRY_AXIS)
        carry_keep(ch);
    return VB_OK;
}

void vb_channels_done(vb_channels *ch)
{
    vb_channels_drop_run(ch);
}

int vb_channels_frame_get(const vb_channels *ch, vb_channels_frame *f)
{
    if (!ch->have_out)
        return -1;
    const vbc_run_out *o = &ch->out;
    const vbc_frame_info *fi = &o->fi;
    memset(f, 0, sizeof *f);
    f->frame = fi->frame;
    f->model = fi->model;
    f->components = o->F.result.components;
    f->pruned = o->F.result.pruned;
    f->channel_voxels = o->F.out.nvoxels;
    f->nx = o->g.nx;
    f->ny = o->g.ny;
    f->nz = o->g.nz;
    f->h = o->g.h;
    memcpy(f->origin, o->g.origin, sizeof f->origin);
    f->ms_prepare = fi->ms_prepare;
    f->ms_upload = fi->ms_upload;
    f->ms_jfa = fi->ms_jfa;
    f->ms_masks = fi->ms_masks;
    f->ms_analysis = fi->ms_analysis;
    f->ms_cells = fi->ms_cells;
    f->ms_refine = fi->ms_refine;
    f->ms_sweep = fi->ms_sweep;
    f->ms_verdict = fi->ms_verdict;
    f->ms_lining = fi->ms_lining;
    f->ms_pore = fi->ms_pore;
    f->ms_total = fi->ms_total;
    return 0;
}

const uint8_t *vb_channels_flags(const vb_channels *ch, size_t *n)
{
    *n = 0;
    if (!ch->have_out || !ch->keep_flags || !ch->out.F.out.flags)
        return NULL;
    *n = vbc_grid_voxels(&ch->out.g);
    return ch->out.F.out.flags;
}

void vb_channels_write_frame_csv(const vb_channels *ch, FILE *f)
{
    if (!ch->have_out)
        return;
    vbc_write_csv_header(f);
    vbc_write_csv_rows(f, &ch->out.fi, &ch->out.g, ch->out.s, &ch->out.F.result);
}

void vb_channels_write_frame_json(const vb_channels *ch, FILE *f)
{
    if (!ch->have_out)
        return;
    const vbc_run_out *o = &ch->out;
    vbc_write_json_begin(f, ch->s0->source ? ch->s0->source : "", ch->cfg.probe, ch->cfg.grid,
                         vb_channels_device_name(ch));
    vbc_write_json_frame(f, 1, &o->fi, &o->g, o->s, &o->F.result);
    vbc_write_json_end(f);
}

void vb_channels_write_frame_profile(const vb_channels *ch, FILE *f)
{
    if (!ch->have_out)
        return;
    vbc_write_profile_header(f);
    vbc_write_profile_rows(f, &ch->out.fi, ch->out.s, &ch->out.F.result);
}

const vb_channels_result *vb_channels_last(const vb_channels *ch)
{
    return ch->have_out ? &ch->out.F.result : NULL;
}

const vb_channels_result *vb_channels_first(const vb_channels *ch)
{
    return ch->run_live && ch->run.frames_done > 0 ? &ch->run.first : NULL;
}

size_t vb_channels_result_rows(const vb_channels_result *r)
{
    return r->nchannels;
}

int vb_channels_result_row(const vb_channels_result *r, size_t k, vb_channel_row *row)
{
    if (k >= r->nchannels)
        return -1;
    const vbc_channel *c = &r->channels[k];
    row->kind = c->kind;
    row->through = c->through;
    row->voxels = c->voxels;
    row->mouths = c->mouths;
    row->length = c->length;
    row->bottleneck = c->bottleneck;
    row->bottleneck_at = c->bottleneck_at;
    row->first_point = c->first_point;
    row->npoints = c->npoints;
    row->first_lining = c->first_lining;
    row->nlining = c->nlining;
    return 0;
}

size_t vb_channels_result_points(const vb_channels_result *r)
{
    size_t n = 0;
    for (size_t t = 0; t < r->nchannels; t++) {
        const vbc_channel *c = &r->channels[t];
        n = c->first_point + c->npoints > n ? c->first_point + c->npoints : n;
    }
    return n;
}

int vb_channels_result_point(const vb_channels_result *r, size_t k, vb_channel_point *p)
{
    if (k >= vb_channels_result_points(r))
        return -1;
    const vbc_point *q = &r->points[k];
    p->x = q->x;
    p->y = q->y;
    p->z = q->z;
    p->r = q->r;
    p->atom = q->atom;
    return 0;
}

const int32_t *vb_channels_result_lining(const vb_channels_result *r, size_t *n)
{
    *n = 0;
    for (size_t t = 0; t < r->nchannels; t++) {
        const vbc_channel *c = &r->channels[t];
        *n = c->first_lining + c->nlining > *n ? c->first_lining + c->nlining : *n;
    }
    return r->lining;
}

int vb_channels_result_pore(const vb_channels_result *r, vb_channels_pore *p)
{
    const vbc_pore_summary *q = &r->pore;
    memcpy(p->u, q->u, sizeof p->u);
    memcpy(p->c, q->c, sizeof p->c);
    p->step = q->step;
    p->F = q->F;
    p->g_macro_pS = q->g_macro_pS;
    p->open_lo = q->open_lo;
    p->open_hi = q->open_hi;
    p->judged = q->judged;
    p->buried = q->buried;
    p->why = q->why;
    return q->present && r->nchannels > 0 && r->channels[0].kind == VBC_PORE;
}
