/* `vorball jfa` for Python (vorball.jfa): the setup checked by the
 * library's one check (vbj_setup_check), the seeds made, the variants run
 * and the figures written by the library's calls of the command
 * (vbj_runs.h); the label grids handed over as bytes, and the picture of
 * one (vbj_picture, `--png`'s pixels). */
#include "vbpy.h"

#include <stdlib.h>
#include <string.h>

/* A number of the setup from a Python int: a negative or oversized one
 * is stored as `refused`, a value vbj_setup_check refuses (as the command
 * stores a number it cannot parse). 0, or -1 with TypeError set. */
static int to_u64(const char *key, PyObject *v, uint64_t refused, uint64_t *field)
{
    if (!PyLong_Check(v) || PyBool_Check(v)) {
        PyErr_Format(PyExc_TypeError, "%s must be an int", key);
        return -1;
    }
    int overflow = 0;
    long long x = PyLong_AsLongLongAndOverflow(v, &overflow);
    if (x == -1 && PyErr_Occurred())
        return -1;
    *field = overflow || x < 0 ? refused : (uint64_t)x;
    return 0;
}

/* The setup from the dict of the call's numbers (None or absent: the
 * library's default; slices a sequence); 0 or -1 with an exception set. */
static int setup_from(PyObject *d, vbj_setup *set)
{
    vbj_setup_defaults(set);
    /* zero: the value stored for an explicit 0 where 0 means "not given" */
    const struct {
        const char *key;
        uint64_t *field, refused, zero;
    } f[] = {{"dim", &set->dim, UINT64_MAX, 0},
             {"n", &set->n, UINT64_MAX, 0},
             {"k", &set->k, 0, 0},
             {"m", &set->m, UINT64_MAX, UINT64_MAX},
             {"fuse_cells", &set->fuse_cells, UINT64_MAX, UINT64_MAX},
             {"repeat", &set->repeat, UINT64_MAX, 0},
             {"rng", &set->rng, UINT64_MAX, 0}};
    for (size_t k = 0; k < sizeof f / sizeof f[0]; k++) {
        PyObject *v = PyDict_GetItemString(d, f[k].key);
        if (!v || v == Py_None)
            continue;
        if (to_u64(f[k].key, v, f[k].refused, f[k].field) != 0)
            return -1;
        if (*f[k].field == 0)
            *f[k].field = f[k].zero;
    }
    PyObject *margin = PyDict_GetItemString(d, "margin");
    if (margin && margin != Py_None) {
        set->margin = PyFloat_AsDouble(margin);
        if (set->margin == -1.0 && PyErr_Occurred())
            return -1;
    }
    PyObject *sl = PyDict_GetItemString(d, "slices");
    if (!sl || sl == Py_None)
        return 0;
    PyObject *seq = PySequence_Fast(sl, "slices must be a sequence of ints");
    if (!seq)
        return -1;
    Py_ssize_t ns = PySequence_Fast_GET_SIZE(seq);
    set->nslices = ns > VBJ_MAX_SLICES ? VBJ_MAX_SLICES + 1 : (uint32_t)(ns ? ns : 1);
    set->slice[0] = UINT64_MAX; /* none given: refused, as an empty --slice */
    int rc = 0;
    for (Py_ssize_t i = 0; rc == 0 && i < ns && i < VBJ_MAX_SLICES; i++)
        rc = to_u64("slices", PySequence_Fast_GET_ITEM(seq, i), UINT64_MAX, &set->slice[i]);
    Py_DECREF(seq);
    return rc;
}

/* One variant's figures as a dict; NULL with an exception. */
static PyObject *figures_dict(const vbj_figures *x)
{
    const vbj_counts *c = &x->r.counts;
    PyObject *m = Py_NewRef(Py_None);
    if (x->checked) {
        Py_DECREF(m);
        m = Py_BuildValue("{s:n,s:n,s:d,s:d,s:d,s:n,s:n,s:n,s:n}", "wrong", (Py_ssize_t)x->m.wrong,
                          "differ", (Py_ssize_t)x->m.differ, "wrong_rate", x->m.wrong_rate,
                          "max_err", x->m.max_err, "mean_err", x->m.mean_err, "boundary_exact",
                          (Py_ssize_t)x->m.boundary_exact, "boundary_found",
                          (Py_ssize_t)x->m.boundary_found, "boundary_missed",
                          (Py_ssize_t)x->m.boundary_missed, "boundary_extra",
                          (Py_ssize_t)x->m.boundary_extra);
        if (!m)
            return NULL;
    }
    PyObject *counts = Py_BuildValue(
        "{s:I,s:K,s:K,s:I,s:K,s:I,s:K,s:K,s:K,s:K,s:K,s:K,s:K,s:K}", "steps", c->steps,
        "pixels_processed", (unsigned long long)c->step_pixels, "threads",
        (unsigned long long)c->threads, "m", c->m, "boundary", (unsigned long long)c->boundary,
        "collisions", c->collisions, "tiles", (unsigned long long)c->tiles, "tiles_uniform",
        (unsigned long long)c->tiles_uniform, "candidates", (unsigned long long)c->candidates,
        "survivors", (unsigned long long)c->survivors, "evals", (unsigned long long)c->evals,
        "exact_voxels", (unsigned long long)c->exact_voxels, "tiles_chunked",
        (unsigned long long)c->tiles_chunked, "visited", (unsigned long long)c->visited);
    if (!counts) {
        Py_DECREF(m);
        return NULL;
    }
    return Py_BuildValue("{s:s,s:d,s:d,s:d,s:d,s:d,s:d,s:N,s:N,s:N}", "variant",
                         vbj_variant_name(x->v), "time_ms", x->mean_ms, "time_ms_min", x->min_ms,
                         "gpu_ms", x->mean_gpu_ms, "fill_ms", x->r.ms_fill, "prep_transfer_ms",
                         x->r.ms_transfer, "prep_ms", x->r.ms_prep, "counts", counts, "metrics",
                         m, "labels", vbpy_bytes(x->r.labels, x->r.pixels, sizeof *x->r.labels));
}

/* The figures written by the library, json or the table. */
static PyObject *figures_text(const vbj_runs *r, const vbj_seeds *s, const char *source, int json)
{
    vbpy_text t;
    if (vbpy_text_open(&t) != 0)
        return NULL;
    vbj_runs_write(t.f, r, s, source, json);
    return vbpy_text_take(&t);
}

static PyObject *result_dict(const vbj_runs *r, const vbj_seeds *s, const char *source)
{
    PyObject *runs = PyList_New(r->n);
    for (int i = 0; runs && i < r->n; i++) {
        PyObject *one = figures_dict(&r->run[i]);
        if (!one)
            Py_CLEAR(runs);
        else
            PyList_SET_ITEM(runs, i, one);
    }
    if (!runs)
        return NULL;
    PyObject *exact_ms = r->exact_ms >= 0 ? PyFloat_FromDouble(r->exact_ms) : Py_NewRef(Py_None);
    return Py_BuildValue("{s:s,s:i,s:I,s:n,s:s,s:i,s:N,s:N,s:N,s:N}", "device", r->device, "dim",
                         s->dim, "n", s->n, "seeds", (Py_ssize_t)s->k, "source", source, "repeat",
                         r->repeat, "exact_ms", exact_ms, "runs", runs, "text",
                         figures_text(r, s, source, 0), "json", figures_text(r, s, source, 1));
}

/* A (k, dim) float64 buffer of points, or None. 0, or -1 with an exception. */
static int points_get(PyObject *o, int dim, Py_buffer *b, vbj_seed_source *src)
{
    if (o == Py_None)
        return 0;
    if (PyObject_GetBuffer(o, b, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT) != 0)
        return -1;
    if (b->itemsize != 8 || !b->format || strcmp(b->format, "d") != 0 ||
        b->len % (8 * dim) != 0) {
        PyBuffer_Release(b);
        b->obj = NULL;
        PyErr_SetString(PyExc_ValueError, "points: a C-contiguous float64 (k, dim) array");
        return -1;
    }
    src->points = b->buf;
    src->npoints = (size_t)b->len / (8 * (size_t)dim);
    return 0;
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
    vbj_setup set;
    if (setup_from(numbers, &set) != 0)
        return NULL;
    vbj_seed_source src = {NULL, name, NULL, 0, path, VBJ_DIST_UNIFORM};
    if (spheres != Py_None && !(src.spheres = vbpy_spheres_get(spheres)))
        return NULL;
    vbpy_call c;
    if (vbpy_call_open(&c) != 0)
        return NULL;
    vbj_variant v[VBJ_MAX_VARIANTS];
    int nv = 0;
    vb_device_kind kind;
    int rc = vbj_setup_check(c.ctx, &set);
    if (rc == VB_OK)
        rc = vbj_variants_parse(c.ctx, variant ? variant : VBJ_VARIANTS_DEFAULT, v, &nv);
    if (rc == VB_OK && dist)
        rc = vbj_distribution_parse(c.ctx, dist, &src.dist);
    if (rc == VB_OK)
        rc = vb_device_kind_parse(c.ctx, device, &kind);
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    Py_buffer b = {0};
    if (points_get(points, (int)set.dim, &b, &src) != 0) {
        Py_XDECREF(vbpy_call_done(&c));
        return NULL;
    }
    vbj_seeds s = {0};
    char source[512];
    vbj_backend *e = NULL;
    vb_device *dev = NULL;
    vbj_runs runs;
    memset(&runs, 0, sizeof runs);
    Py_BEGIN_ALLOW_THREADS
    rc = vbj_seeds_make(c.ctx, &set, &src, &s, source, sizeof source);
    if (rc == VB_OK)
        rc = vbj_backend_open(c.ctx, vb_default_devices(), kind, &dev, &e);
    if (rc == VB_OK)
        rc = vbj_runs_run(c.ctx, e, &s, &set, v, nv, check, &runs);
    Py_END_ALLOW_THREADS
    if (b.obj)
        PyBuffer_Release(&b);
    PyObject *d = rc == VB_OK ? result_dict(&runs, &s, source) : NULL;
    vbj_runs_free(&runs);
    vbj_backend_close(e);
    if (dev)
        vb_default_devices()->close(dev);
    vbj_seeds_free(&s);
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    return vbpy_call_return(&c, d);
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
    PyObject *numbers = Py_BuildValue("{s:i,s:I,s:O}", "dim", dim, "n", n, "slices", slices);
    vbj_setup set;
    int bad = !numbers || setup_from(numbers, &set) != 0;
    Py_XDECREF(numbers);
    size_t pixels = (size_t)n * n * (dim == 3 ? n : 1);
    if (!bad && (size_t)labels.len != pixels * sizeof(uint32_t)) {
        PyErr_SetString(PyExc_ValueError, "labels: n^dim uint32 values");
        bad = 1;
    }
    vbpy_call c;
    if (bad || vbpy_call_open(&c) != 0) {
        PyBuffer_Release(&labels);
        return NULL;
    }
    vbj_seeds s = {.dim = dim, .n = n};
    uint8_t *rgb = NULL;
    uint32_t w = 0;
    int rc = vbj_setup_check(c.ctx, &set);
    if (rc == VB_OK)
        rc = vbj_picture(c.ctx, &s, labels.buf, &set, &rgb, &w);
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
