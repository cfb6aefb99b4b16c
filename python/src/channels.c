/* The channel analysis for Python: a pipe opened once (device by the one
 * fallback rule), one frame at a time through vbc_frame_run, the result
 * handed back as arrays and as the table and JSON the command writes. */
#include "vbpy.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_default.h"
#include "vb_diag.h"
#include "vbc_frame.h"

#define PIPE_CAPSULE "vorball.channel_pipe"

static void pipe_destroy(PyObject *cap)
{
    vbc_pipe_close(PyCapsule_GetPointer(cap, PIPE_CAPSULE));
}

static PyObject *pipe_open(PyObject *self, PyObject *args)
{
    (void)self;
    const char *device, *jfa;
    if (!PyArg_ParseTuple(args, "ss", &device, &jfa))
        return NULL;
    int kind;
    vbj_variant variant;
    if (vbpy_device_kind(device, &kind) != 0)
        return NULL;
    if (vbj_variant_parse(NULL, jfa, &variant) != VB_OK || variant == VBJ_FACET_FULL ||
        variant == VBJ_EXACT_BOUNDARY)
        return vbpy_raise(VB_EMISUSE,
                          "jfa must be exact, facet, jfa, jfa+1, jfa+2 or 1+jfa, not '%s'", jfa);
    vbpy_call c;
    if (vbpy_call_open(&c) != 0)
        return NULL;
    vbc_pipe *p = NULL;
    int rc;
    Py_BEGIN_ALLOW_THREADS
    rc = vbc_pipe_open(c.ctx, vb_default_devices(), (vb_device_kind)kind, variant, &p);
    Py_END_ALLOW_THREADS
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    PyObject *cap = PyCapsule_New(p, PIPE_CAPSULE, pipe_destroy);
    if (!cap)
        vbc_pipe_close(p);
    return vbpy_call_return(&c, cap);
}

/* The command's table (CSV header and rows) and JSON document for this
 * one frame, through the library's writers. */
static int frame_texts(const vb_sphere_set *s, const vbc_grid *g, const vbc_frame_info *fi,
                       const vbc_result *res, double probe, int n, const char *device,
                       PyObject **csv, PyObject **json)
{
    vbpy_text a, b;
    if (vbpy_text_open(&a) != 0)
        return -1;
    if (vbpy_text_open(&b) != 0) {
        Py_XDECREF(vbpy_text_take(&a));
        return -1;
    }
    vbc_write_csv_header(a.f);
    vbc_write_csv_rows(a.f, fi, g, s, res);
    vbc_write_json_begin(b.f, s->source ? s->source : "", probe, n, device);
    vbc_write_json_frame(b.f, 1, fi, g, s, res);
    vbc_write_json_end(b.f);
    *csv = vbpy_text_take(&a);
    *json = vbpy_text_take(&b);
    return *csv && *json ? 0 : -1;
}

/* The analysis as arrays: channels (a list of tuples), points (x y z r
 * float64, 4 per point), point atoms (int32), lining atoms (int32). */
static PyObject *result_dict(const vbc_result *res, PyObject *d)
{
    PyObject *list = PyList_New((Py_ssize_t)res->nchannels);
    if (!list)
        return NULL;
    size_t np = 0;
    for (size_t t = 0; t < res->nchannels; t++) {
        const vbc_channel *c = &res->channels[t];
        np = c->first_point + c->npoints > np ? c->first_point + c->npoints : np;
        PyObject *row = Py_BuildValue("(iinnddnnnnn)", c->kind, c->through, (Py_ssize_t)c->voxels,
                                      (Py_ssize_t)c->mouths, c->length, c->bottleneck,
                                      (Py_ssize_t)c->bottleneck_at, (Py_ssize_t)c->first_point,
                                      (Py_ssize_t)c->npoints, (Py_ssize_t)c->first_lining,
                                      (Py_ssize_t)c->nlining);
        if (!row) {
            Py_DECREF(list);
            return NULL;
        }
        PyList_SET_ITEM(list, (Py_ssize_t)t, row);
    }
    size_t nl = 0;
    for (size_t t = 0; t < res->nchannels; t++) {
        const vbc_channel *c = &res->channels[t];
        nl = c->first_lining + c->nlining > nl ? c->first_lining + c->nlining : nl;
    }
    double *p = malloc((np ? np : 1) * 4 * sizeof *p);
    int32_t *atom = malloc((np ? np : 1) * sizeof *atom);
    if (!p || !atom) {
        free(p);
        free(atom);
        Py_DECREF(list);
        return PyErr_NoMemory();
    }
    for (size_t k = 0; k < np; k++) {
        const vbc_point *q = &res->points[k];
        p[4 * k] = q->x;
        p[4 * k + 1] = q->y;
        p[4 * k + 2] = q->z;
        p[4 * k + 3] = q->r;
        atom[k] = q->atom;
    }
    PyObject *v[4] = {list, vbpy_bytes(p, 4 * np, 8), vbpy_bytes(atom, np, 4),
                      vbpy_bytes(res->lining, nl, 4)};
    free(p);
    free(atom);
    static const char *const keys[4] = {"channels", "points", "point_atoms", "lining"};
    int bad = 0;
    for (int k = 0; k < 4; k++) {
        bad = bad || !v[k] || PyDict_SetItemString(d, keys[k], v[k]) != 0;
        Py_XDECREF(v[k]);
    }
    return bad ? NULL : d;
}

static PyObject *channels_run(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *pcap, *scap;
    int grid, cavities, model, want_flags, first;
    double probe;
    long frame;
    vbc_options opt;
    memset(&opt, 0, sizeof opt);
    if (!PyArg_ParseTuple(args, "OOiddddpilpp", &pcap, &scap, &grid, &probe, &opt.min_length,
                          &opt.min_radius, &opt.lining_tol, &cavities, &model, &frame,
                          &want_flags, &first))
        return NULL;
    opt.keep_cavities = cavities;
    vbc_pipe *pipe = PyCapsule_GetPointer(pcap, PIPE_CAPSULE);
    vb_sphere_set *s = pipe ? vbpy_spheres_get(scap) : NULL;
    if (!s)
        return NULL;
    /* The command's ranges (cli/cmd_channels.c); the library checks the grid. */
    if (!(probe >= 0.0 && probe <= 20.0))
        return vbpy_raise(VB_EMISUSE, "probe must be a radius in 0..20 A, not %g", probe);
    if (!(opt.min_length >= 0 && opt.min_length <= 1e4 && opt.min_radius >= 0 &&
          opt.min_radius <= 1e4 && opt.lining_tol >= 0 && opt.lining_tol <= 1e4))
        return vbpy_raise(VB_EMISUSE, "min_length, min_radius and lining_tol must be in 0..1e4 A");
    vbpy_call c;
    if (vbpy_call_open(&c) != 0)
        return NULL;
    vbc_grid g;
    vbc_frame F;
    memset(&F, 0, sizeof F);
    int rc;
    Py_BEGIN_ALLOW_THREADS
    rc = vbc_grid_fit(c.ctx, s, probe, grid, 3, &g);
    /* As the command warns on its first frame. */
    if (rc == VB_OK && first && g.h > fmax(probe, 0.5))
        vb_warn(c.ctx, VB_W_VOXEL_COARSE, s->source, 0,
                "voxel edge %.2f A is coarser than the probe radius %.2f A: narrow channels may be "
                "missed (raise grid)", g.h, probe);
    if (rc == VB_OK)
        rc = vbc_frame_run(c.ctx, pipe, &g, s, probe, want_flags ? VBC_WANT_FLAGS : 0, &opt, &F);
    Py_END_ALLOW_THREADS
    if (rc != VB_OK) {
        vbc_frame_free(&F);
        return vbpy_call_fail(&c, rc);
    }
    /* No pore stage here (opt.pore NULL): the tables of `vorball channels
     * --no-pore`. */
    vbc_frame_info fi = {frame,          model,         s->n,
                         F.out.nvoxels,  F.out.ms_upload, F.out.ms_jfa,
                         F.out.ms_masks, F.ms_analysis, F.ms_masks + F.ms_analysis,
                         0.0};
    const char *device = vbc_pipe_device_name(pipe);
    PyObject *csv = NULL, *json = NULL;
    PyObject *d = NULL;
    if (frame_texts(s, &g, &fi, &F.result, probe, grid, device, &csv, &json) == 0)
        d = Py_BuildValue("{s:O,s:O,s:s,s:n,s:n,s:n,s:{s:i,s:i,s:i,s:d,s:(ddd)},"
                          "s:{s:d,s:d,s:d,s:d,s:d}}",
                          "csv", csv, "json", json, "device", device, "components",
                          (Py_ssize_t)F.result.components, "pruned", (Py_ssize_t)F.result.pruned,
                          "channel_voxels", (Py_ssize_t)F.out.nvoxels, "grid", "nx", g.nx, "ny",
                          g.ny, "nz", g.nz, "h", g.h, "origin", g.origin[0], g.origin[1],
                          g.origin[2], "ms", "upload", fi.ms_upload, "jfa", fi.ms_jfa, "masks",
                          fi.ms_masks, "analysis", fi.ms_analysis, "total", fi.ms_total);
    Py_XDECREF(csv);
    Py_XDECREF(json);
    if (d && !result_dict(&F.result, d))
        Py_CLEAR(d);
    if (d && want_flags) {
        PyObject *fl = vbpy_bytes(F.out.flags, vbc_grid_voxels(&g), 1);
        if (!fl || PyDict_SetItemString(d, "flags", fl) != 0)
            Py_CLEAR(d);
        Py_XDECREF(fl);
    }
    vbc_frame_free(&F);
    return vbpy_call_return(&c, d);
}

static PyObject *flag_bits(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    return Py_BuildValue("{s:I,s:I,s:I,s:I,s:I,s:I}", "atomic", VBC_F_ATOMIC, "molecular",
                         VBC_F_MOLECULAR, "edge", VBC_F_EDGE, "interior", VBC_F_INTERIOR,
                         "channel", VBC_F_CHANNEL, "mouth", VBC_F_MOUTH);
}

PyMethodDef vbpy_channels_methods[] = {
    {"channels_open", pipe_open, METH_VARARGS,
     "channels_open(device, jfa) -> (capsule, diagnostics)"},
    {"channels_run", channels_run, METH_VARARGS,
     "channels_run(pipe, spheres, grid, probe, min_length, min_radius, lining_tol, cavities, "
     "model, frame, want_flags, first) -> (dict, diagnostics)"},
    {"channel_flag_bits", flag_bits, METH_NOARGS, "The VBC_F_* bits of the flag volume."},
    {NULL, NULL, 0, NULL}};
