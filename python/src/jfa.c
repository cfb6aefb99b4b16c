/* `vorball jfa` for Python (vorball.jfa): the call's keywords set on the
 * library's jfa handle by name (lib/vb_jfa.h: its option table and its one
 * check, the command's words in its messages), the seeds' source given,
 * the variants run; the figures read through the handle's accessors and
 * written by its writers, the label grids handed over as bytes, and the
 * picture of one (`--png`'s pixels). */
#include "vbpy.h"

#include <stdlib.h>
#include <string.h>

/* A Python int as the command line would give it (decimal text); 0, or -1
 * with TypeError set. */
static int int_text(const char *key, PyObject *v, char *buf, size_t len)
{
    if (!PyLong_Check(v) || PyBool_Check(v)) {
        PyErr_Format(PyExc_TypeError, "%s must be an int", key);
        return -1;
    }
    PyObject *s = PyObject_Str(v);
    const char *t = s ? PyUnicode_AsUTF8(s) : NULL;
    if (t)
        snprintf(buf, len, "%s", t);
    Py_XDECREF(s);
    return t ? 0 : -1;
}

/* Sets option `opt` of j to `text`: 0, or -1 with VorballError (E7, the
 * command's message) raised and the call closed. */
static int set_or_fail(vbpy_call *c, vb_jfa *j, const char *opt, const char *text)
{
    char err[512];
    if (vb_jfa_set(j, opt, text, err, sizeof err) == 0)
        return 0;
    vb_jfa_free(j);
    vbpy_call_fail(c, VB_EMISUSE);
    return -1;
}

/* The call's numbers (None or absent: the library's default) onto the
 * handle, in the order of the library's check. 0, or -1 with an exception
 * raised and the call closed. */
static int numbers_set(vbpy_call *c, vb_jfa *j, PyObject *d)
{
    static const char *const key[][2] = {{"dim", "--dim"},     {"n", "--size"},
                                         {"k", "--seeds"},     {"margin", "--margin"},
                                         {"m", "-m"},          {"fuse_cells", "--fuse-cells"},
                                         {"repeat", "--repeat"}, {"rng", "--rng"}};
    for (size_t k = 0; k < sizeof key / sizeof key[0]; k++) {
        PyObject *v = PyDict_GetItemString(d, key[k][0]);
        if (!v || v == Py_None)
            continue;
        char text[64];
        if (strcmp(key[k][0], "margin") == 0) {
            double x = PyFloat_AsDouble(v);
            if (x == -1.0 && PyErr_Occurred())
                goto fail;
            snprintf(text, sizeof text, "%.17g", x);
        } else if (int_text(key[k][0], v, text, sizeof text) != 0)
            goto fail;
        if (set_or_fail(c, j, key[k][1], text) != 0)
            return -1;
    }
    return 0;
fail:
    vb_jfa_free(j);
    Py_XDECREF(vbpy_call_done(c));
    return -1;
}

/* One variant's figures as a dict; NULL with an exception. */
static PyObject *figures_dict(const vb_jfa_figures *x)
{
    PyObject *m = Py_NewRef(Py_None);
    if (x->checked) {
        Py_DECREF(m);
        m = Py_BuildValue("{s:n,s:n,s:d,s:d,s:d,s:n,s:n,s:n,s:n}", "wrong", (Py_ssize_t)x->wrong,
                          "differ", (Py_ssize_t)x->differ, "wrong_rate", x->wrong_rate,
                          "max_err", x->max_err, "mean_err", x->mean_err, "boundary_exact",
                          (Py_ssize_t)x->boundary_exact, "boundary_found",
                          (Py_ssize_t)x->boundary_found, "boundary_missed",
                          (Py_ssize_t)x->boundary_missed, "boundary_extra",
                          (Py_ssize_t)x->boundary_extra);
        if (!m)
            return NULL;
    }
    PyObject *counts = Py_BuildValue(
        "{s:I,s:K,s:K,s:I,s:K,s:I,s:K,s:K,s:K,s:K,s:K,s:K,s:K,s:K}", "steps", x->steps,
        "pixels_processed", (unsigned long long)x->pixels_processed, "threads",
        (unsigned long long)x->threads, "m", x->m, "boundary", (unsigned long long)x->boundary,
        "collisions", x->collisions, "tiles", (unsigned long long)x->tiles, "tiles_uniform",
        (unsigned long long)x->tiles_uniform, "candidates", (unsigned long long)x->candidates,
        "survivors", (unsigned long long)x->survivors, "evals", (unsigned long long)x->evals,
        "exact_voxels", (unsigned long long)x->exact_voxels, "tiles_chunked",
        (unsigned long long)x->tiles_chunked, "visited", (unsigned long long)x->visited);
    if (!counts) {
        Py_DECREF(m);
        return NULL;
    }
    return Py_BuildValue("{s:s,s:d,s:d,s:d,s:d,s:d,s:d,s:N,s:N,s:N}", "variant", x->variant,
                         "time_ms", x->time_ms, "time_ms_min", x->time_ms_min, "gpu_ms",
                         x->gpu_ms, "fill_ms", x->fill_ms, "prep_transfer_ms",
                         x->prep_transfer_ms, "prep_ms", x->prep_ms, "counts", counts, "metrics",
                         m, "labels", vbpy_bytes(x->labels, x->pixels, sizeof *x->labels));
}

/* The figures written by the library, json or the table. */
static PyObject *figures_text(const vb_jfa *j, int json)
{
    vbpy_text t;
    if (vbpy_text_open(&t) != 0)
        return NULL;
    vb_jfa_write(j, t.f, json);
    return vbpy_text_take(&t);
}

static PyObject *result_dict(const vb_jfa *j)
{
    vb_jfa_info in;
    vb_jfa_info_get(j, &in);
    PyObject *runs = PyList_New(in.runs);
    for (int i = 0; runs && i < in.runs; i++) {
        vb_jfa_figures x;
        vb_jfa_figures_get(j, i, &x);
        PyObject *one = figures_dict(&x);
        if (!one)
            Py_CLEAR(runs);
        else
            PyList_SET_ITEM(runs, i, one);
    }
    if (!runs)
        return NULL;
    PyObject *exact_ms = in.exact_ms >= 0 ? PyFloat_FromDouble(in.exact_ms) : Py_NewRef(Py_None);
    return Py_BuildValue("{s:s,s:i,s:I,s:n,s:s,s:i,s:N,s:N,s:N,s:N}", "device", in.device, "dim",
                         in.dim, "n", in.n, "seeds", (Py_ssize_t)in.seeds, "source", in.source,
                         "repeat", in.repeat, "exact_ms", exact_ms, "runs", runs, "text",
                         figures_text(j, 0), "json", figures_text(j, 1));
}

/* A (k, dim) float64 buffer of points onto the handle, or None. 0, or -1
 * with an exception. */
static int points_give(PyObject *o, int dim, vb_jfa *j)
{
    if (o == Py_None)
        return 0;
    Py_buffer b;
    if (PyObject_GetBuffer(o, &b, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT) != 0)
        return -1;
    int bad = b.itemsize != 8 || !b.format || strcmp(b.format, "d") != 0 ||
              b.len % (8 * dim) != 0;
    int rc = bad ? -1 : vb_jfa_source_points(j, b.buf, (size_t)b.len / (8 * (size_t)dim));
    PyBuffer_Release(&b);
    if (bad)
        PyErr_SetString(PyExc_ValueError, "points: a C-contiguous float64 (k, dim) array");
    else if (rc)
        PyErr_NoMemory();
    return bad || rc ? -1 : 0;
}

static PyObject *jfa_run(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *numbers, *points, *spheres;
    const char *dist, *variant, *device, *path, *name;
    int check;
    if (!PyArg_ParseTuple(args, "OzzspzOOz", &numbers, &dist, &variant, &device, &check, &path,
                          &points, &spheres, &name))
        return NULL;
    if (!PyDict_Check(numbers))
        return PyErr_Format(PyExc_TypeError, "numbers must be a dict");
    const vb_sphere_set *sph = NULL;
    if (spheres != Py_None && !(sph = vbpy_spheres_get(spheres)))
        return NULL;
    PyObject *dv = PyDict_GetItemString(numbers, "dim");
    int dim = dv && PyLong_Check(dv) && PyLong_AsLong(dv) == 3 ? 3 : 2;
    vbpy_call c;
    if (vbpy_call_open(&c) != 0)
        return NULL;
    vb_jfa *j;
    if (vb_jfa_new(c.ctx, &j) != VB_OK) {
        vb_jfa_free(j);
        return vbpy_call_fail(&c, VB_ENOMEM);
    }
    if (numbers_set(&c, j, numbers) != 0 ||
        (variant && set_or_fail(&c, j, "variant", variant) != 0) ||
        (dist && set_or_fail(&c, j, "dist", dist) != 0) ||
        set_or_fail(&c, j, "device", device) != 0 ||
        (check && set_or_fail(&c, j, "check", NULL) != 0))
        return NULL;
    char err[512];
    if (sph)
        vb_jfa_source_spheres(j, sph, name);
    if (path)
        vb_jfa_source_file(j, path);
    if (vb_jfa_check(j, err, sizeof err) != 0) {
        vb_jfa_free(j);
        return vbpy_call_fail(&c, VB_EMISUSE);
    }
    if (points_give(points, dim, j) != 0) {
        vb_jfa_free(j);
        Py_XDECREF(vbpy_call_done(&c));
        return NULL;
    }
    int rc;
    Py_BEGIN_ALLOW_THREADS
    rc = vb_jfa_run(c.ctx, j);
    Py_END_ALLOW_THREADS
    PyObject *d = rc == VB_OK ? result_dict(j) : NULL;
    vb_jfa_free(j);
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    return vbpy_call_return(&c, d);
}

/* --slice's text from a sequence of ints; 0, or -1 with an exception. */
static int slices_text(PyObject *sl, char *buf, size_t len)
{
    PyObject *seq = PySequence_Fast(sl, "slices must be a sequence of ints");
    if (!seq)
        return -1;
    buf[0] = 0;
    int rc = 0;
    for (Py_ssize_t i = 0; rc == 0 && i < PySequence_Fast_GET_SIZE(seq); i++) {
        char one[64];
        size_t at = strlen(buf);
        rc = int_text("slices", PySequence_Fast_GET_ITEM(seq, i), one, sizeof one);
        if (rc == 0)
            snprintf(buf + at, len - at, "%s%s", i ? "," : "", one);
    }
    Py_DECREF(seq);
    return rc;
}

/* The picture of a label grid (`vorball jfa --png`'s pixels) as bytes of
 * (n, w, 3). */
static PyObject *jfa_picture(PyObject *self, PyObject *args)
{
    (void)self;
    Py_buffer labels;
    int dim;
    unsigned int n;
    PyObject *slices;
    if (!PyArg_ParseTuple(args, "y*iIO", &labels, &dim, &n, &slices))
        return NULL;
    char sl[256], dtext[16], ntext[16];
    size_t pixels = (size_t)n * n * (dim == 3 ? n : 1);
    int bad = slices != Py_None && slices_text(slices, sl, sizeof sl) != 0;
    if (!bad && (size_t)labels.len != pixels * sizeof(uint32_t)) {
        PyErr_SetString(PyExc_ValueError, "labels: n^dim uint32 values");
        bad = 1;
    }
    vbpy_call c;
    if (bad || vbpy_call_open(&c) != 0) {
        PyBuffer_Release(&labels);
        return NULL;
    }
    snprintf(dtext, sizeof dtext, "%d", dim);
    snprintf(ntext, sizeof ntext, "%u", n);
    vb_jfa *j = NULL;
    char err[512];
    uint8_t *rgb = NULL;
    uint32_t w = 0;
    int rc = vb_jfa_new(c.ctx, &j);
    if (rc == VB_OK && (vb_jfa_set(j, "dim", dtext, err, sizeof err) != 0 ||
                        vb_jfa_set(j, "size", ntext, err, sizeof err) != 0 ||
                        (slices != Py_None && vb_jfa_set(j, "--slice", sl, err, sizeof err)) ||
                        vb_jfa_check(j, err, sizeof err) != 0))
        rc = VB_EMISUSE;
    if (rc == VB_OK)
        rc = vb_jfa_picture(c.ctx, j, labels.buf, &rgb, &w);
    vb_jfa_free(j);
    PyBuffer_Release(&labels);
    PyObject *out = rc == VB_OK ? Py_BuildValue("(NI)", vbpy_bytes(rgb, (size_t)w * n, 3), w)
                                : NULL;
    free(rgb);
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    return vbpy_call_return(&c, out);
}

PyMethodDef vbpy_jfa_methods[] = {
    {"jfa_run", jfa_run, METH_VARARGS,
     "jfa_run(numbers, dist, variant, device, check, path, points, spheres, name) "
     "-> (dict, diagnostics)"},
    {"jfa_picture", jfa_picture, METH_VARARGS,
     "jfa_picture(labels, dim, n, slices) -> ((bytes, width), diagnostics)"},
    {NULL, NULL, 0, NULL}};
