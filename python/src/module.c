/* vorball._core: the module, the per-call context and the error path
 * (vbpy.h). */
#include "vbpy.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "vb_device.h"
#include "vb_diag.h"

/* vorball.VorballError, handed over by the package when it is imported. */
static PyObject *error_class;

int vbpy_call_open(vbpy_call *c)
{
    memset(c, 0, sizeof *c);
    c->diag = open_memstream(&c->text, &c->len);
    vb_config cfg = {1, c->diag};
    if (!c->diag || vb_open(&c->ctx, &cfg) != VB_OK) {
        if (c->diag)
            fclose(c->diag);
        free(c->text);
        PyErr_NoMemory();
        return -1;
    }
    return 0;
}

/* The diagnostics as a str; the stream and the context released. */
static PyObject *call_close(vbpy_call *c)
{
    vb_close(c->ctx);
    c->ctx = NULL;
    fclose(c->diag);
    PyObject *s = PyUnicode_DecodeUTF8(c->text ? c->text : "", (Py_ssize_t)c->len, "replace");
    free(c->text);
    c->text = NULL;
    return s;
}

PyObject *vbpy_call_done(vbpy_call *c)
{
    return call_close(c);
}

/* Raises error_class(number, message, status, exit_status, diagnostics). */
static void raise_error(int status, const char *msg, PyObject *diag)
{
    PyObject *cls = error_class ? error_class : PyExc_RuntimeError;
    PyObject *e = PyObject_CallFunction(cls, "isiiO", vb_diag_number(status), msg, status,
                                        vb_diag_exit(status), diag ? diag : Py_None);
    if (e) {
        PyErr_SetObject(cls, e);
        Py_DECREF(e);
    }
}

PyObject *vbpy_call_fail(vbpy_call *c, int rc)
{
    const char *m = vb_errmsg(c->ctx);
    char *msg = strdup(m && *m ? m : vb_errstr(rc));
    PyObject *diag = call_close(c);
    if (!msg) {
        Py_XDECREF(diag);
        return PyErr_NoMemory();
    }
    /* A Python error raised while the call ran (MemoryError) wins. */
    if (!PyErr_Occurred())
        raise_error(rc, msg, diag);
    free(msg);
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
    raise_error(status, msg, NULL);
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

static PyMethodDef base_methods[] = {
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
        add_methods(m, vbpy_channels_methods) ||
        PyModule_AddIntConstant(m, "ZERO_RADIUS_AUTO", VB_ZERO_RADIUS_AUTO) ||
        PyModule_AddIntConstant(m, "ZERO_RADIUS_ERROR", VB_ZERO_RADIUS_ERROR) ||
        PyModule_AddIntConstant(m, "ZERO_RADIUS_POINT", VB_ZERO_RADIUS_POINT) ||
        PyModule_AddIntConstant(m, "ZERO_RADIUS_DROP", VB_ZERO_RADIUS_DROP)) {
        Py_DECREF(m);
        return NULL;
    }
    return m;
}
