/* vorball._core: the module, the per-call context and the error path
 * (vbpy.h). */
#include "vbpy.h"

#include <pthread.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "vb_default.h"
#include "vb_device.h"
#include "vb_diag.h"

/* vorball.VorballError, handed over by the package when it is imported. */
static PyObject *error_class;

/* The log callback: a copy of the record kept, under the call's lock. */
static void keep_record(void *arg, const vb_diag_record *r)
{
    vbpy_call *c = arg;
    pthread_mutex_lock(c->lock);
    if (c->n == c->cap) {
        size_t nc = c->cap ? 2 * c->cap : 8;
        vbpy_record *p = realloc(c->rec, nc * sizeof *p);
        if (p) {
            c->rec = p;
            c->cap = nc;
        }
    }
    if (c->n < c->cap) {
        vbpy_record *k = &c->rec[c->n];
        k->kind = r->kind;
        k->number = r->number;
        k->line = r->line;
        k->file = r->file ? strdup(r->file) : NULL;
        k->message = strdup(r->message);
        if (k->message && (k->file || !r->file))
            c->n++;
        else {
            free(k->file);
            free(k->message);
            c->lost = 1;
        }
    } else {
        c->lost = 1;
    }
    pthread_mutex_unlock(c->lock);
}

static void records_free(vbpy_call *c)
{
    for (size_t k = 0; k < c->n; k++) {
        free(c->rec[k].file);
        free(c->rec[k].message);
    }
    free(c->rec);
    c->rec = NULL;
    c->n = c->cap = 0;
}

int vbpy_call_open(vbpy_call *c)
{
    memset(c, 0, sizeof *c);
    vb_config cfg = {1, NULL};
    if (!(c->lock = malloc(sizeof(pthread_mutex_t))) ||
        pthread_mutex_init(c->lock, NULL) != 0) {
        free(c->lock);
        PyErr_NoMemory();
        return -1;
    }
    if (vb_open(&c->ctx, &cfg) != VB_OK) {
        pthread_mutex_destroy(c->lock);
        free(c->lock);
        PyErr_NoMemory();
        return -1;
    }
    vb_set_log(c->ctx, keep_record, c);
    return 0;
}

/* The progress callback: the library serialises the calls; the GIL is
 * taken here because the run released it (Py_BEGIN_ALLOW_THREADS). */
static void call_progress(void *arg, const char *stage, uint64_t done, uint64_t total)
{
    vbpy_call *c = arg;
    if (c->progress_off)
        return;
    PyGILState_STATE g = PyGILState_Ensure();
    PyObject *r = PyObject_CallFunction(c->progress, "sKK", stage, (unsigned long long)done,
                                        (unsigned long long)total);
    if (r) {
        Py_DECREF(r);
    } else {
        c->progress_off = 1;
        PyErr_WriteUnraisable(c->progress);
    }
    PyGILState_Release(g);
}

int vbpy_progress_check(PyObject *fn)
{
    if (fn == Py_None || PyCallable_Check(fn))
        return 0;
    PyErr_SetString(PyExc_TypeError, "progress must be a callable or None");
    return -1;
}

void vbpy_call_progress(vbpy_call *c, PyObject *fn)
{
    if (!fn || fn == Py_None)
        return;
    c->progress = fn;
    vb_set_progress(c->ctx, call_progress, c);
}

/* The records as a list of tuples; the records and the context released. */
static PyObject *call_close(vbpy_call *c)
{
    vb_close(c->ctx);
    c->ctx = NULL;
    pthread_mutex_destroy(c->lock);
    free(c->lock);
    c->lock = NULL;
    PyObject *list = c->lost ? PyErr_NoMemory() : PyList_New((Py_ssize_t)c->n);
    for (size_t k = 0; list && k < c->n; k++) {
        const vbpy_record *r = &c->rec[k];
        PyObject *t = Py_BuildValue("(Cizls)", r->kind, r->number, r->file, r->line,
                                    r->message);
        if (!t) {
            Py_CLEAR(list);
            break;
        }
        PyList_SET_ITEM(list, (Py_ssize_t)k, t);
    }
    records_free(c);
    return list;
}

PyObject *vbpy_call_done(vbpy_call *c)
{
    return call_close(c);
}

/* Raises error_class(number, message, status, exit_status, diagnostics,
 * file, line, row): message without its location when file is given; row
 * (>= 0) the row of spheres given as arrays that the binding names. */
static void raise_error(int status, const char *msg, PyObject *diag, const char *file,
                        long line, Py_ssize_t row)
{
    PyObject *cls = error_class ? error_class : PyExc_RuntimeError;
    PyObject *r = row >= 0 ? PyLong_FromSsize_t(row) : Py_NewRef(Py_None);
    PyObject *e = r ? PyObject_CallFunction(cls, "isiiOzlO", vb_diag_number(status), msg,
                                            status, vb_diag_exit(status), diag ? diag : Py_None,
                                            file, line, r)
                    : NULL;
    Py_XDECREF(r);
    if (e) {
        PyErr_SetObject(cls, e);
        Py_DECREF(e);
    }
}

PyObject *vbpy_call_fail(vbpy_call *c, int rc)
{
    /* The error as a record: its message and location apart. */
    vb_diag_record er;
    vb_error_record(c->ctx, &er);
    const char *m = er.message && *er.message ? er.message : NULL;
    char *msg = strdup(m ? m : vb_errstr(rc));
    char *file = m && er.file ? strdup(er.file) : NULL;
    long line = er.line;
    PyObject *diag = call_close(c);
    if (!msg || (m && er.file && !file)) {
        free(msg);
        free(file);
        Py_XDECREF(diag);
        return PyErr_NoMemory();
    }
    /* A Python error raised while the call ran (MemoryError) wins. */
    if (!PyErr_Occurred())
        raise_error(rc, msg, diag, file, line, -1);
    free(msg);
    free(file);
    Py_XDECREF(diag);
    return NULL;
}

PyObject *vbpy_raise(int status, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    raise_error(status, msg, NULL, NULL, 0, -1);
    return NULL;
}

PyObject *vbpy_raise_row(int status, Py_ssize_t row, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    raise_error(status, msg, NULL, NULL, 0, row);
    return NULL;
}

PyObject *vbpy_call_return(vbpy_call *c, PyObject *value)
{
    PyObject *diag = call_close(c);
    if (!value || !diag) {
        Py_XDECREF(value);
        Py_XDECREF(diag);
        return NULL;
    }
    PyObject *t = PyTuple_Pack(2, value, diag);
    Py_DECREF(value);
    Py_DECREF(diag);
    return t;
}

int vbpy_frames_open(vbpy_call *c, vbpy_frames *S, PyObject *tokens, int water, vb_box *box,
                     vb_read_options *ro)
{
    int rc = tokens == Py_None ? VB_OK : vbpy_box(c->ctx, tokens, NULL, box);
    S->ctx = c->ctx;
    S->failed = 0;
    S->list = rc < 0 ? NULL : PyList_New(0);
    if (!S->list) {
        Py_XDECREF(vbpy_call_done(c));
        return -1;
    }
    memset(ro, 0, sizeof *ro);
    ro->keep_water = water;
    return rc;
}

int vbpy_frames_append(vbpy_frames *S, long frame, int model, PyObject *d)
{
    PyObject *item = d ? Py_BuildValue("(liN)", frame, model, d) : NULL;
    int bad = !item || PyList_Append(S->list, item) != 0;
    Py_XDECREF(item);
    S->failed |= bad;
    return bad ? VB_ENOMEM : VB_OK;
}

PyObject *vbpy_frames_return(vbpy_call *c, vbpy_frames *S, int rc)
{
    if (S->failed) {
        Py_DECREF(S->list);
        Py_XDECREF(vbpy_call_done(c));
        return NULL;
    }
    if (rc != VB_OK) {
        Py_DECREF(S->list);
        return vbpy_call_fail(c, rc);
    }
    return vbpy_call_return(c, S->list);
}

PyObject *vbpy_bytes(const void *p, size_t n, size_t size)
{
    if (n == 0 || !p)
        return PyBytes_FromStringAndSize("", 0);
    return PyBytes_FromStringAndSize((const char *)p, (Py_ssize_t)(n * size));
}

int vbpy_text_open(vbpy_text *t)
{
    memset(t, 0, sizeof *t);
    if (!(t->f = open_memstream(&t->buf, &t->len))) {
        PyErr_NoMemory();
        return -1;
    }
    return 0;
}

PyObject *vbpy_text_take(vbpy_text *t)
{
    fclose(t->f);
    PyObject *s = PyUnicode_DecodeUTF8(t->buf ? t->buf : "", (Py_ssize_t)t->len, "replace");
    free(t->buf);
    memset(t, 0, sizeof *t);
    return s;
}

int vbpy_device_kind(const char *name, int *kind)
{
    vb_device_kind k;
    if (vb_device_kind_parse(NULL, name, &k) != VB_OK) {
        vbpy_raise(VB_EMISUSE, "device must be auto, gpu, cpu or ref, not '%s'", name);
        return -1;
    }
    *kind = (int)k;
    return 0;
}

static PyObject *set_error_class(PyObject *self, PyObject *cls)
{
    (void)self;
    if (!PyType_Check(cls) || !PyType_IsSubtype((PyTypeObject *)cls, (PyTypeObject *)PyExc_Exception)) {
        PyErr_SetString(PyExc_TypeError, "an Exception subclass is needed");
        return NULL;
    }
    Py_INCREF(cls);
    Py_XSETREF(error_class, cls);
    Py_RETURN_NONE;
}

/* Appends t (stolen; NULL when building it failed) to list: 0 or -1. */
static int append(PyObject *list, PyObject *t)
{
    int rc = t ? PyList_Append(list, t) : -1;
    Py_XDECREF(t);
    return rc;
}

/* The catalogue of vb_diag.h: (kind, number, name, exit, meaning) for every
 * entry, then the retired numbers as (kind, number, None, None, meaning). */
static PyObject *diagnostics(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    PyObject *list = PyList_New(0);
    int bad = !list;
#define VBPY_DIAG(kind, number, name, exit, meaning)                                             \
    bad = bad || append(list, Py_BuildValue("(sisis)", #kind, number, #name, exit, meaning));
    VB_DIAG_LIST(VBPY_DIAG)
#undef VBPY_DIAG
#define VBPY_RETIRED(kind, number, meaning, why)                                                 \
    bad = bad || append(list, Py_BuildValue("(siOOs)", #kind, number, Py_None, Py_None,          \
                                            meaning " (retired: " why ")"));
    VB_DIAG_RETIRED(VBPY_RETIRED)
#undef VBPY_RETIRED
    if (bad)
        Py_CLEAR(list);
    return list;
}

/* The table of `vorball devices` (vb_devices_write) as a str. */
static PyObject *devices(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    vbpy_call c;
    vbpy_text t;
    if (vbpy_call_open(&c) != 0)
        return NULL;
    if (vbpy_text_open(&t) != 0) {
        Py_XDECREF(vbpy_call_done(&c));
        return NULL;
    }
    int rc;
    Py_BEGIN_ALLOW_THREADS
    rc = vb_devices_write(c.ctx, t.f);
    Py_END_ALLOW_THREADS
    PyObject *text = vbpy_text_take(&t);
    if (rc != VB_OK) {
        Py_XDECREF(text);
        return vbpy_call_fail(&c, rc);
    }
    return vbpy_call_return(&c, text);
}

static PyMethodDef base_methods[] = {
    {"devices", devices, METH_NOARGS, "devices() -> (str, diagnostics): `vorball devices`"},
    {"_set_error_class", set_error_class, METH_O, "Sets the exception class raised on errors."},
    {"diagnostics", diagnostics, METH_NOARGS,
     "The diagnostics catalogue: (kind, number, name, exit, meaning) tuples."},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "vorball._core",
                                    "The C side of vorball (see the vorball package).", -1,
                                    NULL, NULL, NULL, NULL, NULL};

/* Adds the functions of one table to the module. */
static int add_methods(PyObject *m, PyMethodDef *defs)
{
    PyObject *name = PyModule_GetNameObject(m);
    if (!name)
        return -1;
    for (PyMethodDef *d = defs; d->ml_name; d++) {
        PyObject *f = PyCFunction_NewEx(d, NULL, name);
        if (!f || PyModule_AddObject(m, d->ml_name, f) != 0) {
            Py_XDECREF(f);
            Py_DECREF(name);
            return -1;
        }
    }
    Py_DECREF(name);
    return 0;
}

PyMODINIT_FUNC PyInit__core(void)
{
    PyObject *m = PyModule_Create(&module);
    if (!m)
        return NULL;
    if (add_methods(m, base_methods) || add_methods(m, vbpy_spheres_methods) ||
        add_methods(m, vbpy_vertices_methods) || add_methods(m, vbpy_verify_methods) ||
        add_methods(m, vbpy_channels_methods) || add_methods(m, vbpy_cells_methods) ||
        add_methods(m, vbpy_periodic_methods) || add_methods(m, vbpy_jfa_methods) ||
        PyModule_AddIntConstant(m, "ZERO_RADIUS_AUTO", VB_ZERO_RADIUS_AUTO) ||
        PyModule_AddIntConstant(m, "ZERO_RADIUS_ERROR", VB_ZERO_RADIUS_ERROR) ||
        PyModule_AddIntConstant(m, "ZERO_RADIUS_POINT", VB_ZERO_RADIUS_POINT) ||
        PyModule_AddIntConstant(m, "ZERO_RADIUS_DROP", VB_ZERO_RADIUS_DROP)) {
        Py_DECREF(m);
        return NULL;
    }
    return m;
}
