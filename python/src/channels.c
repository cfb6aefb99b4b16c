/* The channel analysis for Python: a channels handle (vb_channels.h) opened
 * once (device by the one fallback rule), one frame at a time through
 * vb_channels_run, the result handed back as arrays and as the table and
 * JSON the command writes. */
#include "vbpy.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vb_channels.h"
#include "vb_diag.h"

#define PIPE_CAPSULE "vorball.channel_pipe"

static void pipe_destroy(PyObject *cap)
{
    vb_channels_free(PyCapsule_GetPointer(cap, PIPE_CAPSULE));
}

static PyObject *pipe_open(PyObject *self, PyObject *args)
{
    (void)self;
    const char *device, *jfa;
    if (!PyArg_ParseTuple(args, "ss", &device, &jfa))
        return NULL;
    int kind;
    char err[512];
    if (vbpy_device_kind(device, &kind) != 0)
        return NULL;
    vb_channels *p = NULL;
    if (vb_channels_new(NULL, &p) != VB_OK)
        return PyErr_NoMemory();
    /* The engine's options through the library's table (its checks). */
    if (vb_channels_set(p, "device", device, err, sizeof err) != 0 ||
        vb_channels_set(p, "jfa", jfa, err, sizeof err) != 0) {
        vb_channels_free(p);
        return vbpy_raise(VB_EMISUSE, "%s", err);
    }
    vbpy_call c;
    if (vbpy_call_open(&c) != 0) {
        vb_channels_free(p);
        return NULL;
    }
    int rc;
    Py_BEGIN_ALLOW_THREADS
    rc = vb_channels_open(c.ctx, p);
    Py_END_ALLOW_THREADS
    if (rc != VB_OK) {
        vb_channels_free(p);
        return vbpy_call_fail(&c, rc);
    }
    PyObject *cap = PyCapsule_New(p, PIPE_CAPSULE, pipe_destroy);
    if (!cap)
        vb_channels_free(p);
    return vbpy_call_return(&c, cap);
}

/* The command's texts for the handle's last frame, through the library's
 * writers: its table (CSV header and rows), JSON document and --profile
 * rows. 0, or -1 with a Python error set (*out holds nothing then). */
static int frame_texts(const vb_channels *ch, PyObject *out[3])
{
    static void (*const write[3])(const vb_channels *, FILE *) = {
        vb_channels_write_frame_csv, vb_channels_write_frame_json,
        vb_channels_write_frame_profile};
    for (int k = 0; k < 3; k++) {
        vbpy_text a;
        out[k] = NULL;
        if (vbpy_text_open(&a) == 0) {
            write[k](ch, a.f);
            out[k] = vbpy_text_take(&a);
        }
        if (!out[k]) {
            for (int j = 0; j < k; j++)
                Py_CLEAR(out[j]);
            return -1;
        }
    }
    return 0;
}

/* The frame's pore: axis, openings, HOLE's conductance estimate, the
 * verdict's walled length; None without a pore. */
static PyObject *pore_dict(const vb_channels_result *res)
{
    vb_channels_pore p;
    if (!vb_channels_result_pore(res, &p))
        Py_RETURN_NONE;
    return Py_BuildValue("{s:(ddd),s:(ddd),s:d,s:d,s:d,s:O,s:O,s:d,s:s}", "axis", p.u[0], p.u[1],
                         p.u[2], "start", p.c[0], p.c[1], p.c[2], "step", p.step, "F", p.F,
                         "g_macro_pS", p.g_macro_pS, "open_lo", p.open_lo ? Py_True : Py_False,
                         "open_hi", p.open_hi ? Py_True : Py_False, "buried", p.buried, "why",
                         p.why);
}

/* The analysis as arrays: channels (a list of tuples), points (x y z r
 * float64, 4 per point), point atoms (int32), lining atoms (int32). */
static PyObject *result_dict(const vb_channels_result *res, PyObject *d)
{
    size_t rows = vb_channels_result_rows(res);
    PyObject *list = PyList_New((Py_ssize_t)rows);
    if (!list)
        return NULL;
    for (size_t t = 0; t < rows; t++) {
        vb_channel_row c;
        vb_channels_result_row(res, t, &c);
        PyObject *row = Py_BuildValue("(iinnddnnnnn)", c.kind, c.through, (Py_ssize_t)c.voxels,
                                      (Py_ssize_t)c.mouths, c.length, c.bottleneck,
                                      (Py_ssize_t)c.bottleneck_at, (Py_ssize_t)c.first_point,
                                      (Py_ssize_t)c.npoints, (Py_ssize_t)c.first_lining,
                                      (Py_ssize_t)c.nlining);
        if (!row) {
            Py_DECREF(list);
            return NULL;
        }
        PyList_SET_ITEM(list, (Py_ssize_t)t, row);
    }
    size_t np = vb_channels_result_points(res), nl;
    const int32_t *lining = vb_channels_result_lining(res, &nl);
    double *p = malloc((np ? np : 1) * 4 * sizeof *p);
    int32_t *atom = malloc((np ? np : 1) * sizeof *atom);
    if (!p || !atom) {
        free(p);
        free(atom);
        Py_DECREF(list);
        return PyErr_NoMemory();
    }
    for (size_t k = 0; k < np; k++) {
        vb_channel_point q;
        vb_channels_result_point(res, k, &q);
        p[4 * k] = q.x;
        p[4 * k + 1] = q.y;
        p[4 * k + 2] = q.z;
        p[4 * k + 3] = q.r;
        atom[k] = q.atom;
    }
    PyObject *v[4] = {list, vbpy_bytes(p, 4 * np, 8), vbpy_bytes(atom, np, 4),
                      vbpy_bytes(lining, nl, 4)};
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

/* What an Engine carries from frame to frame (the pore axis its first
 * frame found) is kept by its handle (VB_CHANNELS_CARRY_AXIS): the carry
 * is a token that asks for it. */
static PyObject *carry_new(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    Py_RETURN_TRUE;
}

/* The text of Python value v for option o (vb_channels_set parses it): a
 * number with 17 digits (the same double back), integers, names, X,Y,Z.
 * Returns 0, or -1 with a Python error set. */
static int option_text(const vb_channels_option *o, PyObject *v, char *out, size_t len)
{
    const char *key = o->py;
    int is_bool = PyBool_Check(v);
    switch (o->type) {
    case VB_OPT_FLAG:
        snprintf(out, len, "%d", PyObject_IsTrue(v) == 1);
        return 0;
    case VB_OPT_REAL: {
        double d = is_bool ? NAN : PyFloat_AsDouble(v);
        if (is_bool || (d == -1.0 && PyErr_Occurred())) {
            PyErr_Clear();
            vbpy_raise(VB_EMISUSE, "%s must be a length in A, not a %s", key, Py_TYPE(v)->tp_name);
            return -1;
        }
        snprintf(out, len, "%.17g", d);
        return 0;
    }
    case VB_OPT_COUNT:
    case VB_OPT_POW2: {
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
    case VB_OPT_CHOICE:
        if (!PyUnicode_Check(v)) {
            vbpy_raise(VB_EMISUSE, "%s must be a name, not a %s", key, Py_TYPE(v)->tp_name);
            return -1;
        }
        snprintf(out, len, "%s", PyUnicode_AsUTF8(v));
        return 0;
    case VB_OPT_VEC3: {
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
    case VB_OPT_NAMES:
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

/* Sets the keywords of dict kw on the handle through the option table
 * (None: the library's default). Returns 0, or -1 with a Python error set. */
static int set_keywords(PyObject *kw, vb_channels *ch)
{
    char err[512], text[1024];
    PyObject *key, *v;
    Py_ssize_t pos = 0;
    while (PyDict_Next(kw, &pos, &key, &v)) {
        const char *name = PyUnicode_Check(key) ? PyUnicode_AsUTF8(key) : NULL;
        vb_channels_option o;
        /* Python's keywords only: a name starting with '-' is none. */
        if (!name || name[0] == '-' || vb_channels_option_find(name, &o) != 0) {
            vbpy_raise(VB_EMISUSE, "unknown channels option %s", name ? name : "?");
            return -1;
        }
        if (v == Py_None)
            continue; /* the library's default */
        if (option_text(&o, v, text, sizeof text) != 0)
            return -1;
        if (o.type == VB_OPT_FLAG && text[0] == '0')
            continue;
        /* Python's keywords by their names in messages. */
        if (vb_channels_set(ch, name, text, err, sizeof err) != 0) {
            vbpy_raise(VB_EMISUSE, "%s (%s)", err, name);
            return -1;
        }
    }
    return 0;
}

/* The rules between the options, once all are set. 0, or -1 with a Python
 * error set. */
static int check(vb_channels *ch)
{
    char err[512];
    if (vb_channels_check(ch, err, sizeof err) == 0)
        return 0;
    vbpy_raise(VB_EMISUSE, "%s", err);
    return -1;
}

/* The handle's options from the keyword dict: the library's defaults,
 * then each keyword checked and set. 0, or -1 with a Python error set. */
static int config_from(PyObject *kw, vb_channels *ch)
{
    vb_channels_reset(ch);
    return set_keywords(kw, ch) != 0 ? -1 : check(ch);
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
    vb_channels *ch = PyCapsule_GetPointer(pcap, PIPE_CAPSULE);
    vb_sphere_set *s = ch ? vbpy_spheres_get(scap) : NULL;
    if (!s || config_from(kw, ch) != 0)
        return NULL;
    vbpy_call c;
    if (vbpy_progress_check(progress) != 0 || vbpy_call_open(&c) != 0)
        return NULL;
    vbpy_call_progress(&c, progress);
    unsigned flags = (want_flags ? VB_CHANNELS_KEEP_FLAGS : 0) |
                     (ccap != Py_None ? VB_CHANNELS_CARRY_AXIS : 0);
    int rc;
    Py_BEGIN_ALLOW_THREADS
    rc = vb_channels_run(c.ctx, ch, s, frame, model, first, flags);
    Py_END_ALLOW_THREADS
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    vb_channels_frame f;
    vb_channels_frame_get(ch, &f);
    const char *device = vb_channels_device_name(ch);
    PyObject *text[3], *pore = NULL, *d = NULL;
    int texts = frame_texts(ch, text) == 0;
    if (texts)
        pore = pore_dict(vb_channels_last(ch));
    if (pore)
        d = Py_BuildValue("{s:O,s:O,s:O,s:O,s:s,s:n,s:n,s:n,s:{s:i,s:i,s:i,s:d,s:(ddd)},"
                          "s:{s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d}}",
                          "csv", text[0], "json", text[1], "profile", text[2], "pore", pore,
                          "device", device, "components",
                          (Py_ssize_t)f.components, "pruned", (Py_ssize_t)f.pruned,
                          "channel_voxels", (Py_ssize_t)f.channel_voxels, "grid", "nx", f.nx,
                          "ny", f.ny, "nz", f.nz, "h", f.h, "origin", f.origin[0], f.origin[1],
                          f.origin[2], "ms", "prepare", f.ms_prepare, "upload", f.ms_upload,
                          "jfa", f.ms_jfa, "masks", f.ms_masks, "analysis", f.ms_analysis,
                          "cells", f.ms_cells, "refine", f.ms_refine, "sweep", f.ms_sweep,
                          "verdict", f.ms_verdict, "lining", f.ms_lining, "pore", f.ms_pore,
                          "total", f.ms_total);
    for (int k = 0; texts && k < 3; k++)
        Py_DECREF(text[k]);
    Py_XDECREF(pore);
    if (d && !result_dict(vb_channels_last(ch), d))
        Py_CLEAR(d);
    size_t nflags;
    const uint8_t *fl = vb_channels_flags(ch, &nflags);
    if (d && want_flags) {
        PyObject *b = vbpy_bytes(fl, nflags, 1);
        if (!b || PyDict_SetItemString(d, "flags", b) != 0)
            Py_CLEAR(d);
        Py_XDECREF(b);
    }
    vb_channels_done(ch); /* an engine keeps no frame between calls */
    return vbpy_call_return(&c, d);
}

/* The command's own options (outputs, --frames, --traj, --repeat) from a
 * dict of its spellings: a str value, or True for a flag. Values must
 * outlive the run (the dict's strings do). 0, or -1 with a Python error. */
static int set_outputs(PyObject *outs, vb_channels *ch)
{
    char err[512];
    PyObject *key, *v;
    Py_ssize_t pos = 0;
    while (PyDict_Next(outs, &pos, &key, &v)) {
        const char *name = PyUnicode_Check(key) ? PyUnicode_AsUTF8(key) : NULL;
        const char *value = PyUnicode_Check(v) ? PyUnicode_AsUTF8(v) : NULL;
        if (!name || (!value && v != Py_True)) {
            vbpy_raise(VB_EMISUSE, "channels output %s: a str or True", name ? name : "?");
            return -1;
        }
        if (vb_channels_set(ch, name, value, err, sizeof err) != 0) {
            vbpy_raise(VB_EMISUSE, "%s", err);
            return -1;
        }
    }
    return 0;
}

enum { TEXT_TABLE, TEXT_STATS, TEXT_CL, TEXT_PROFILE, TEXTS };

/* What a run over frames gives Python besides its texts: the selection,
 * totals, the pore series, the first frame's stage picture. */
static PyObject *frames_dict(const vb_channels *ch, long selected, PyObject *text[TEXTS])
{
    vb_channels_totals tot;
    vb_channels_totals_get(ch, &tot);
    size_t n = vb_channels_series(ch, 0, NULL, NULL, NULL);
    PyObject *series = PyList_New((Py_ssize_t)n);
    for (size_t k = 0; series && k < n; k++) {
        long frame;
        double rmin, s;
        vb_channels_series(ch, k, &frame, &rmin, &s);
        PyObject *row = Py_BuildValue("(ldd)", frame, rmin, s);
        if (!row)
            Py_CLEAR(series);
        else
            PyList_SET_ITEM(series, (Py_ssize_t)k, row);
    }
    uint32_t w, h;
    const uint8_t *rgb;
    PyObject *stages = vb_channels_stages(ch, &w, &h, &rgb) == 0
                           ? Py_BuildValue("(IIy#)", w, h, (const char *)rgb,
                                           (Py_ssize_t)w * h * 3)
                           : Py_NewRef(Py_None);
    PyObject *d = NULL;
    if (series && stages)
        d = Py_BuildValue("{s:O,s:O,s:O,s:O,s:l,s:l,s:i,s:d,s:d,s:s,s:O,s:O}", "table",
                          text[TEXT_TABLE], "stats", text[TEXT_STATS], "centrelines",
                          text[TEXT_CL], "profile", text[TEXT_PROFILE], "selected", selected,
                          "analysed", tot.frames, "repeat", tot.repeat, "ms_total", tot.ms_total,
                          "ms_masks", tot.ms_masks, "device", vb_channels_device_name(ch),
                          "series", series, "stages", stages);
    Py_XDECREF(series);
    Py_XDECREF(stages);
    return d;
}

/* Every frame of an opened vorball.Frames through the library's run over
 * frames (vb_channels_run_frames), as `vorball channels` runs a trajectory:
 * the texts of its table, statistics, centrelines and profile (None when
 * not asked), its files (volumes, occupancy, page, PyMOL script) written
 * by the library. */
static PyObject *channels_frames(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *fcap, *kw, *outs, *progress;
    const char *input, *device, *jfa;
    int want[TEXTS];
    if (!PyArg_ParseTuple(args, "OsO!O!sspppO", &fcap, &input, &PyDict_Type, &kw, &PyDict_Type,
                          &outs, &device, &jfa, &want[TEXT_STATS], &want[TEXT_CL],
                          &want[TEXT_PROFILE], &progress))
        return NULL;
    want[TEXT_TABLE] = 1;
    vb_frame_source *F = vbpy_frames_source(fcap);
    if (!F || vbpy_progress_check(progress) != 0)
        return NULL;
    vb_channels *ch = NULL;
    char err[512];
    if (vb_channels_new(NULL, &ch) != VB_OK)
        return PyErr_NoMemory();
    if (set_keywords(kw, ch) != 0 || set_outputs(outs, ch) != 0)
        goto fail;
    if (vb_channels_set(ch, "device", device, err, sizeof err) != 0 ||
        vb_channels_set(ch, "jfa", jfa, err, sizeof err) != 0) {
        vbpy_raise(VB_EMISUSE, "%s", err);
        goto fail;
    }
    if (check(ch) != 0)
        goto fail;
    vbpy_text tx[TEXTS];
    PyObject *text[TEXTS];
    vb_channels_io io;
    memset(&io, 0, sizeof io);
    io.input = input;
    int k = 0;
    for (; k < TEXTS; k++)
        if (want[k] && vbpy_text_open(&tx[k]) != 0)
            break;
    if (k < TEXTS) {
        while (k-- > 0)
            if (want[k])
                Py_XDECREF(vbpy_text_take(&tx[k]));
        goto fail;
    }
    for (k = 0; k < VB_CHANNELS_SINKS; k++)
        io.sink[k] = want[k] ? tx[k].f : NULL;
    io.profile = want[TEXT_PROFILE] ? tx[TEXT_PROFILE].f : NULL;
    vbpy_call c;
    if (vbpy_call_open(&c) != 0) {
        for (k = 0; k < TEXTS; k++)
            if (want[k])
                Py_XDECREF(vbpy_text_take(&tx[k]));
        goto fail;
    }
    vbpy_call_progress(&c, progress);
    long selected = 0;
    int rc;
    Py_BEGIN_ALLOW_THREADS
    rc = vb_channels_open(c.ctx, ch);
    if (rc == VB_OK) {
        vb_channels_write_head(ch, &io, NULL);
        rc = vb_channels_run_frames(c.ctx, ch, F, &io, &selected);
    }
    if (rc == VB_OK)
        rc = vb_channels_finish(c.ctx, ch, &io, 1, selected);
    Py_END_ALLOW_THREADS
    int bad = 0;
    for (k = 0; k < TEXTS; k++) {
        text[k] = want[k] ? vbpy_text_take(&tx[k]) : Py_NewRef(Py_None);
        bad = bad || !text[k];
    }
    PyObject *d = NULL;
    if (rc != VB_OK) {
        for (k = 0; k < TEXTS; k++)
            Py_XDECREF(text[k]);
        vb_channels_free(ch);
        return vbpy_call_fail(&c, rc);
    }
    if (!bad)
        d = frames_dict(ch, selected, text);
    for (k = 0; k < TEXTS; k++)
        Py_XDECREF(text[k]);
    vb_channels_free(ch);
    return vbpy_call_return(&c, d);
fail:
    vb_channels_free(ch);
    return NULL;
}

/* The option table as Python sees it: per keyword (type, min, max,
 * default text or None, choices or None, help). */
static PyObject *option_table(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    static const char *const types[] = {"flag", "real", "count", "pow2", "path",
                                        "choice", "vec3", "frames", "names"};
    PyObject *d = PyDict_New();
    vb_channels_option o;
    for (size_t k = 0; d && vb_channels_option_at(k, &o) == 0; k++) {
        if (!o.py)
            continue;
        PyObject *row = Py_BuildValue("(sddzzs)", types[o.type], o.min, o.max, o.def, o.choices,
                                      o.help);
        if (!row || PyDict_SetItemString(d, o.py, row) != 0)
            Py_CLEAR(d);
        Py_XDECREF(row);
    }
    return d;
}

static PyObject *flag_bits(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    return Py_BuildValue("{s:I,s:I,s:I,s:I,s:I,s:I}", "atomic", VB_CHANNEL_F_ATOMIC, "molecular",
                         VB_CHANNEL_F_MOLECULAR, "edge", VB_CHANNEL_F_EDGE, "interior",
                         VB_CHANNEL_F_INTERIOR, "channel", VB_CHANNEL_F_CHANNEL, "mouth",
                         VB_CHANNEL_F_MOUTH);
}

PyMethodDef vbpy_channels_methods[] = {
    {"channels_open", pipe_open, METH_VARARGS,
     "channels_open(device, jfa) -> (capsule, diagnostics)"},
    {"channels_run", channels_run, METH_VARARGS,
     "channels_run(pipe, spheres, options, carry, model, frame, want_flags, first) -> "
     "(dict, diagnostics): options by their Python keywords (channel_options())"},
    {"channels_carry", carry_new, METH_NOARGS,
     "channels_carry() -> token: an engine's frames carry the pore axis (kept by the handle)"},
    {"channels_frames", channels_frames, METH_VARARGS,
     "channels_frames(frames, input, options, outputs, device, jfa, stats, centrelines, "
     "profile, progress) -> (dict, diagnostics): every frame through the library's run over "
     "frames; outputs by the command's spellings"},
    {"channel_options", option_table, METH_NOARGS,
     "channel_options() -> {keyword: (type, min, max, default, choices, help)}"},
    {"channel_flag_bits", flag_bits, METH_NOARGS, "The VB_CHANNEL_F_* bits of the flag volume."},
    {NULL, NULL, 0, NULL}};
