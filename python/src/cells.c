/* Cell measures for Python (vorball.cells): vb_cells_run on a sphere set,
 * the enclosures handed over as bytes and the tables `vorball cells`
 * writes (its TSV writers) as text. */
#include "vbpy.h"

#include <stdlib.h>
#include <string.h>

/* The contacts as four arrays: id1, id2 (uint32), lo, hi (float64). */
static int contact_arrays(const vb_cell_measures *m, PyObject *d)
{
    size_t n = m->ncontacts, k1 = n ? n : 1;
    uint32_t *i = malloc(k1 * sizeof *i), *j = malloc(k1 * sizeof *j);
    double *lo = malloc(k1 * sizeof *lo), *hi = malloc(k1 * sizeof *hi);
    int bad = !i || !j || !lo || !hi;
    for (size_t k = 0; !bad && k < n; k++) {
        i[k] = m->contacts[k].i;
        j[k] = m->contacts[k].j;
        lo[k] = m->contacts[k].lo;
        hi[k] = m->contacts[k].hi;
    }
    const struct {
        const char *key;
        const void *p;
        size_t size;
    } a[] = {{"id1", i, 4}, {"id2", j, 4}, {"area_lo", lo, 8}, {"area_hi", hi, 8}};
    for (size_t k = 0; k < sizeof a / sizeof a[0] && !bad; k++) {
        PyObject *b = vbpy_bytes(a[k].p, n, a[k].size);
        bad = !b || PyDict_SetItemString(d, a[k].key, b) != 0;
        Py_XDECREF(b);
    }
    free(i);
    free(j);
    free(lo);
    free(hi);
    if (bad && !PyErr_Occurred())
        PyErr_NoMemory();
    return bad ? -1 : 0;
}

/* The TSV tables as `vorball cells` writes them: (atoms, contacts or
 * None). NULL with an exception. */
static PyObject *tables(const vb_sphere_set *set, const vb_cell_measures *m, int contacts)
{
    vbpy_text a, c;
    if (vbpy_text_open(&a) != 0)
        return NULL;
    vb_cell_measures_write_atoms(a.f, set, m);
    PyObject *at = vbpy_text_take(&a), *ct = NULL;
    if (at && contacts && vbpy_text_open(&c) == 0) {
        vb_cell_measures_write_contacts(c.f, m);
        ct = vbpy_text_take(&c);
    } else if (at && !contacts) {
        ct = Py_NewRef(Py_None);
    }
    if (!ct) {
        Py_XDECREF(at);
        return NULL;
    }
    return Py_BuildValue("(NN)", at, ct);
}

static PyObject *result_dict(const vb_sphere_set *set, const vb_cell_measures *m, int contacts)
{
    PyObject *d = Py_BuildValue(
        "{s:N,s:N,s:N,s:N,s:N,s:N,s:n,s:n,s:n,s:N}", "volume_lo", vbpy_bytes(m->vol_lo, m->n, 8),
        "volume_hi", vbpy_bytes(m->vol_hi, m->n, 8), "sas_lo", vbpy_bytes(m->sas_lo, m->n, 8),
        "sas_hi", vbpy_bytes(m->sas_hi, m->n, 8), "empty", vbpy_bytes(m->empty, m->n, 1),
        "loose", vbpy_bytes(m->loose, m->n, 1), "patches", (Py_ssize_t)m->patches, "nempty",
        (Py_ssize_t)m->nempty, "nloose", (Py_ssize_t)m->nloose, "tables",
        tables(set, m, contacts));
    if (d && contacts && contact_arrays(m, d) != 0)
        Py_CLEAR(d);
    return d;
}

static PyObject *cells_run(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *cap;
    double probe, tolerance;
    Py_ssize_t max_patches;
    int contacts, threads;
    if (!PyArg_ParseTuple(args, "Oddnpi", &cap, &probe, &tolerance, &max_patches, &contacts,
                          &threads))
        return NULL;
    vb_sphere_set *set = vbpy_spheres_get(cap);
    if (!set)
        return NULL;
    vb_measure_options opt;
    vb_measure_defaults(&opt);
    opt.probe = probe;
    opt.tolerance = tolerance;
    opt.max_patches = max_patches > 0 ? (size_t)max_patches : 0;
    opt.contacts = contacts;
    opt.threads = threads;
    vbpy_call c;
    if (vbpy_call_open(&c) != 0)
        return NULL;
    vb_sphere_set run;
    vb_cell_measures m;
    memset(&m, 0, sizeof m);
    int rc;
    Py_BEGIN_ALLOW_THREADS
    rc = vbpy_validate(c.ctx, set, 1, &run);
    if (rc == VB_OK)
        rc = vb_cells_run(c.ctx, &run, &opt, &m);
    Py_END_ALLOW_THREADS
    PyObject *d = rc == VB_OK ? result_dict(&run, &m, contacts) : NULL;
    free(run.contained);
    vb_cell_measures_free(&m);
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    return vbpy_call_return(&c, d);
}

PyMethodDef vbpy_cells_methods[] = {
    {"cells_run", cells_run, METH_VARARGS,
     "cells_run(spheres, probe, tolerance, max_patches, contacts, threads) -> (dict, diagnostics)"},
    {NULL, NULL, 0, NULL}};
