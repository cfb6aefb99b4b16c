/* The channel analysis for Python: a pipe opened once (device by the one
 * fallback rule), one frame at a time through vbc_frame_run, the result
 * handed back as arrays and as the table and JSON the command writes. */
#include "vbpy.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_default.h"
#include "vb_diag.h"
#include "vbc_run.h"

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
    rc = vbc_pipe_open(c.ctx, vb_default_devices(),
                       vbc_channels_device((vb_device_kind)kind, vb_default_devices()), variant,
                       &p);
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

#define CARRY_CAPSULE "vorball.channel_carry"

static void carry_destroy(PyObject *cap)
{
    free(PyCapsule_GetPointer(cap, CARRY_CAPSULE));
}

/* What an Engine carries from frame to frame: the pore request as the
 * first frame left it (vbc_run keeps the axis it found there) and, for
 * axis_refit, the first frame's refitted source and axis (the command's
 * run keeps them in its config across frames). */
typedef struct frame_carry {
    vbc_pore_request pore;
    vbc_axis refit0;
    double u0[3], c0[3];
} frame_carry;

static PyObject *carry_new(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    frame_carry *q = calloc(1, sizeof *q);
    if (!q)
        return PyErr_NoMemory();
    PyObject *cap = PyCapsule_New(q, CARRY_CAPSULE, carry_destroy);
    if (!cap)
        free(q);
    return cap;
}

/* The text of Python value v for option o (vbc_channels_set parses it): a
 * number with 17 digits (the same double back), integers, names, X,Y,Z.
 * Returns 0, or -1 with a Python error set. */
static int option_text(const vbc_opt_spec *o, PyObject *v, char *out, size_t len)
{
    const char *key = o->py;
    int is_bool = PyBool_Check(v);
    switch (o->type) {
    case VBC_OPT_FLAG:
        snprintf(out, len, "%d", PyObject_IsTrue(v) == 1);
        return 0;
    case VBC_OPT_REAL: {
        double d = is_bool ? NAN : PyFloat_AsDouble(v);
        if (is_bool || (d == -1.0 && PyErr_Occurred())) {
            PyErr_Clear();
            vbpy_raise(VB_EMISUSE, "%s must be a length in A, not a %s", key, Py_TYPE(v)->tp_name);
            return -1;
        }
        snprintf(out, len, "%.17g", d);
        return 0;
    }
    case VBC_OPT_COUNT:
    case VBC_OPT_POW2: {
        if (is_bool || !PyLong_Check(v)) {
            vbpy_raise(VB_EMISUSE, "%s must be an integer, not a %s", key, Py_TYPE(v)->tp_name);
            return -1;
        }
        long long n = PyLong_AsLongLong(v);
        if (n == -1 && PyErr_Occurred()) {
            PyErr_Clear();
            n = -1;
        }
        snprintf(out, len, "%lld", n);
        return 0;
    }
    case VBC_OPT_CHOICE:
        if (!PyUnicode_Check(v)) {
            vbpy_raise(VB_EMISUSE, "%s must be a name, not a %s", key, Py_TYPE(v)->tp_name);
            return -1;
        }
        snprintf(out, len, "%s", PyUnicode_AsUTF8(v));
        return 0;
    case VBC_OPT_VEC3: {
        double x[3];
        if (!PySequence_Check(v) || PyUnicode_Check(v) || PySequence_Size(v) != 3) {
            PyErr_Clear();
            vbpy_raise(VB_EMISUSE, "%s must be three numbers", key);
            return -1;
        }
        for (int k = 0; k < 3; k++) {
            PyObject *e = PySequence_GetItem(v, k);
            x[k] = e && !PyBool_Check(e) ? PyFloat_AsDouble(e) : NAN;
            Py_XDECREF(e);
            if (PyErr_Occurred() || isnan(x[k])) {
                PyErr_Clear();
                vbpy_raise(VB_EMISUSE, "%s must be three numbers", key);
                return -1;
            }
        }
        snprintf(out, len, "%.17g,%.17g,%.17g", x[0], x[1], x[2]);
        return 0;
    }
    case VBC_OPT_NAMES:
        if (!PyUnicode_Check(v)) {
            vbpy_raise(VB_EMISUSE, "%s must be comma-separated residue names, not a %s", key,
                       Py_TYPE(v)->tp_name);
            return -1;
        }
        snprintf(out, len, "%s", PyUnicode_AsUTF8(v));
        return 0;
    default:
        vbpy_raise(VB_EMISUSE, "%s is not an option of the binding", key);
        return -1;
    }
}

/* The configuration from the keyword dict: the library's defaults, then
 * each keyword checked and set through the option table. Returns 0, or -1
 * with a Python error set. */
static int config_from(PyObject *kw, vbc_channels_config *cfg)
{
    vbc_channels_defaults(cfg);
    char err[512], text[1024];
    PyObject *key, *v;
    Py_ssize_t pos = 0;
    while (PyDict_Next(kw, &pos, &key, &v)) {
        const char *name = PyUnicode_Check(key) ? PyUnicode_AsUTF8(key) : NULL;
        const vbc_opt_spec *o = name ? vbc_channels_option_py(name) : NULL;
        if (!o) {
            vbpy_raise(VB_EMISUSE, "unknown channels option %s", name ? name : "?");
            return -1;
        }
        if (v == Py_None)
            continue; /* the library's default */
        if (option_text(o, v, text, sizeof text) != 0)
            return -1;
        if (o->type == VBC_OPT_FLAG && text[0] == '0')
            continue;
        /* Python's keywords by their names in messages. */
        if (vbc_channels_set(cfg, o, o->type == VBC_OPT_FLAG ? NULL : text, err, sizeof err) != 0) {
            vbpy_raise(VB_EMISUSE, "%s (%s)", err, name);
            return -1;
        }
    }
    if (vbc_channels_check(cfg, err, sizeof err) != 0) {
        vbpy_raise(VB_EMISUSE, "%s", err);
        return -1;
    }
    return 0;
}

static PyObject *channels_run(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *pcap, *scap, *kw, *ccap, *progress;
    int model, want_flags, first;
    long frame;
    if (!PyArg_ParseTuple(args, "OOO!OilppO", &pcap, &scap, &PyDict_Type, &kw, &ccap, &model,
                          &frame, &want_flags, &first, &progress))
        return NULL;
    vbc_pipe *pipe = PyCapsule_GetPointer(pcap, PIPE_CAPSULE);
    vb_sphere_set *s = pipe ? vbpy_spheres_get(scap) : NULL;
    frame_carry *carry = NULL;
    if (!s || (ccap != Py_None && !(carry = PyCapsule_GetPointer(ccap, CARRY_CAPSULE))))
        return NULL;
    /* Heap: the configuration is large (its name lists). */
    vbc_channels_config *cfg = malloc(sizeof *cfg);
    if (!cfg)
        return PyErr_NoMemory();
    if (config_from(kw, cfg) != 0) {
        free(cfg);
        return NULL;
    }
    /* An engine's later frames sweep the axis its first frame found. */
    if (carry && carry->pore.have_axis && !cfg->pore.have_axis && !cfg->pore.have_through) {
        vbc_pore_options sweep = cfg->pore.sweep;
        int enabled = cfg->pore.enabled;
        cfg->pore = carry->pore;
        cfg->refit0 = carry->refit0;
        memcpy(cfg->u0, carry->u0, sizeof cfg->u0);
        memcpy(cfg->c0, carry->c0, sizeof cfg->c0);
        cfg->pore.sweep = sweep;
        cfg->pore.enabled = enabled;
    }
    vbpy_call c;
    if (vbpy_progress_check(progress) != 0 || vbpy_call_open(&c) != 0) {
        free(cfg);
        return NULL;
    }
    vbpy_call_progress(&c, progress);
    vbc_run run;
    vbc_run_out o;
    int rc;
    vbc_run_init(&run, cfg, pipe, s->source);
    run.want = want_flags ? VBC_WANT_FLAGS | VBC_WANT_EDGES : 0; /* every bit of every voxel */
    run.frames_total = 1; /* one frame a call: progress ("frames", 1, 1) */
    Py_BEGIN_ALLOW_THREADS
    rc = vbc_run_frame(c.ctx, &run, s, frame, model, first, &o);
    Py_END_ALLOW_THREADS
    if (rc == VB_OK)
        vbc_run_report_left_out(c.ctx, &run);
    if (rc != VB_OK) {
        vbc_run_free(&run);
        free(cfg);
        return vbpy_call_fail(&c, rc);
    }
    if (carry && cfg->pore.have_axis) {
        carry->pore = cfg->pore;
        carry->refit0 = cfg->refit0;
        memcpy(carry->u0, cfg->u0, sizeof carry->u0);
        memcpy(carry->c0, cfg->c0, sizeof carry->c0);
    }
    const vbc_grid g = o.g;
    const vbc_frame_info fi = o.fi;
    const char *device = vbc_pipe_device_name(pipe);
    PyObject *csv = NULL, *json = NULL;
    PyObject *d = NULL;
    if (frame_texts(o.s, &g, &fi, &o.F.result, cfg->probe, cfg->grid, device, &csv, &json) == 0)
        d = Py_BuildValue("{s:O,s:O,s:s,s:n,s:n,s:n,s:{s:i,s:i,s:i,s:d,s:(ddd)},"
                          "s:{s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d}}",
                          "csv", csv, "json", json, "device", device, "components",
                          (Py_ssize_t)o.F.result.components, "pruned", (Py_ssize_t)o.F.result.pruned,
                          "channel_voxels", (Py_ssize_t)o.F.out.nvoxels, "grid", "nx", g.nx, "ny",
                          g.ny, "nz", g.nz, "h", g.h, "origin", g.origin[0], g.origin[1],
                          g.origin[2], "ms", "prepare", fi.ms_prepare, "upload", fi.ms_upload,
                          "jfa", fi.ms_jfa, "masks", fi.ms_masks, "analysis", fi.ms_analysis,
                          "cells", fi.ms_cells, "refine", fi.ms_refine, "sweep", fi.ms_sweep,
                          "verdict", fi.ms_verdict, "lining", fi.ms_lining, "pore", fi.ms_pore,
                          "total", fi.ms_total);
    Py_XDECREF(csv);
    Py_XDECREF(json);
    if (d && !result_dict(&o.F.result, d))
        Py_CLEAR(d);
    if (d && want_flags) {
        PyObject *fl = vbpy_bytes(o.F.out.flags, vbc_grid_voxels(&g), 1);
        if (!fl || PyDict_SetItemString(d, "flags", fl) != 0)
            Py_CLEAR(d);
        Py_XDECREF(fl);
    }
    vbc_run_frame_done(&run, 0, &o);
    vbc_run_free(&run);
    free(cfg);
    return vbpy_call_return(&c, d);
}

/* The option table as Python sees it: per keyword (type, min, max,
 * default text or None, choices or None, help). */
static PyObject *option_table(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    static const char *const types[] = {"flag", "real", "count", "pow2", "path",
                                        "choice", "vec3", "frames", "names"};
    size_t n;
    const vbc_opt_spec *t = vbc_channels_options(&n);
    PyObject *d = PyDict_New();
    for (size_t k = 0; d && k < n; k++) {
        if (!t[k].py)
            continue;
        PyObject *row = Py_BuildValue("(sddzzs)", types[t[k].type], t[k].min, t[k].max, t[k].def,
                                      t[k].choices, t[k].help);
        if (!row || PyDict_SetItemString(d, t[k].py, row) != 0)
            Py_CLEAR(d);
        Py_XDECREF(row);
    }
    return d;
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
     "channels_run(pipe, spheres, options, carry, model, frame, want_flags, first) -> "
     "(dict, diagnostics): options by their Python keywords (channel_options())"},
    {"channels_carry", carry_new, METH_NOARGS,
     "channels_carry() -> capsule: what an engine carries between frames (the pore axis)"},
    {"channel_options", option_table, METH_NOARGS,
     "channel_options() -> {keyword: (type, min, max, default, choices, help)}"},
    {"channel_flag_bits", flag_bits, METH_NOARGS, "The VBC_F_* bits of the flag volume."},
    {NULL, NULL, 0, NULL}};
