/* Cell measures for Python (vorball.cells): vb_cells_run (or
 * vb_cells_run_periodic in a box, vbpy_box) on a sphere set,
 * the enclosures handed over as bytes, the tables `vorball cells`
 * writes (its TSV writers) as text, the counts of its --stats and its
 * results page (vb_cells_page_write, --html). */
#include "vbpy.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

/* The contacts as four arrays: id1, id2 (uint32), lo, hi (float64), and
 * in a periodic run shift2 (int16 triples: id2's image shift). */
static int contact_arrays(const vb_cell_measures *m, PyObject *d)
{
    size_t n = m->ncontacts, k1 = n ? n : 1;
    uint32_t *i = malloc(k1 * sizeof *i), *j = malloc(k1 * sizeof *j);
    double *lo = malloc(k1 * sizeof *lo), *hi = malloc(k1 * sizeof *hi);
    int16_t *sh = malloc(3 * k1 * sizeof *sh);
    int bad = !i || !j || !lo || !hi || !sh;
    for (size_t k = 0; !bad && k < n; k++) {
        memcpy(sh + 3 * k, m->contacts[k].s, sizeof m->contacts[k].s);
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
    if (!bad && m->periodic) {
        PyObject *b = vbpy_bytes(sh, 3 * n, 2);
        bad = !b || PyDict_SetItemString(d, "shift2", b) != 0;
        Py_XDECREF(b);
    }
    free(sh);
    free(i);
    free(j);
    free(lo);
    free(hi);
    if (bad && !PyErr_Occurred())
        PyErr_NoMemory();
    return bad ? -1 : 0;
}

/* The tables as `vorball cells` writes them: (atoms TSV, contacts TSV
 * or None, the --json document). NULL with an exception. */
static PyObject *tables(vb_ctx *ctx, const vb_sphere_set *set, const vb_cell_measures *m,
                        int contacts)
{
    vbpy_text a, c, j;
    if (vbpy_text_open(&j) != 0)
        return NULL;
    int rc = vb_cell_measures_write_json(ctx, j.f, set, m, -1, 0);
    fputc('\n', j.f);
    PyObject *jt = vbpy_text_take(&j);
    if (!jt || rc != VB_OK || vbpy_text_open(&a) != 0) {
        Py_XDECREF(jt);
        return rc != VB_OK ? PyErr_NoMemory() : NULL;
    }
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
        Py_DECREF(jt);
        return NULL;
    }
    return Py_BuildValue("(NNN)", at, ct, jt);
}

static PyObject *result_dict(vb_ctx *ctx, const vb_sphere_set *set, const vb_cell_measures *m,
                             int contacts)
{
    PyObject *d = Py_BuildValue(
        "{s:N,s:N,s:N,s:N,s:N,s:N,s:n,s:n,s:n,s:n,s:n,s:N}", "volume_lo", vbpy_bytes(m->vol_lo, m->n, 8),
        "volume_hi", vbpy_bytes(m->vol_hi, m->n, 8), "sas_lo", vbpy_bytes(m->sas_lo, m->n, 8),
        "sas_hi", vbpy_bytes(m->sas_hi, m->n, 8), "empty", vbpy_bytes(m->empty, m->n, 1),
        "loose", vbpy_bytes(m->loose, m->n, 1), "patches", (Py_ssize_t)m->patches, "nempty",
        (Py_ssize_t)m->nempty, "nloose", (Py_ssize_t)m->nloose, "ncontacts",
        (Py_ssize_t)m->ncontacts, "nclosed", (Py_ssize_t)m->nclosed, "tables",
        tables(ctx, set, m, contacts));
    if (d && contacts && contact_arrays(m, d) != 0)
        Py_CLEAR(d);
    return d;
}

/* The measure options of the call's numbers; the ranges are the
 * library's (vb_measure_options_check, by the caller): a value out of
 * the fields' types is stored as one the check refuses. */
static void measure_options(double probe, double tolerance, Py_ssize_t max_patches, int contacts,
                            Py_ssize_t threads, vb_measure_options *opt)
{
    vb_measure_defaults(opt);
    opt->probe = probe;
    opt->tolerance = tolerance;
    opt->max_patches = max_patches > 0 ? (size_t)max_patches : 1;
    opt->contacts = contacts;
    opt->threads = threads >= 0 && threads <= INT_MAX ? (int)threads : -1;
}

static PyObject *cells_run(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *cap, *tokens, *html = NULL;
    const char *title;
    double probe, tolerance;
    Py_ssize_t max_patches, threads;
    int contacts, periodic;
    if (!PyArg_ParseTuple(args, "OddnpnpOO&z", &cap, &probe, &tolerance, &max_patches, &contacts,
                          &threads, &periodic, &tokens, PyUnicode_FSConverter, &html, &title))
        return NULL;
    vb_sphere_set *set = vbpy_spheres_get(cap);
    vb_measure_options opt;
    measure_options(probe, tolerance, max_patches, contacts, threads, &opt);
    vbpy_call c;
    if (!set || vbpy_call_open(&c) != 0) {
        Py_DECREF(html);
        return NULL;
    }
    if (vb_measure_options_check(c.ctx, &opt) != VB_OK) {
        Py_DECREF(html);
        return vbpy_call_fail(&c, VB_EMISUSE);
    }
    /* html: b"" for no page */
    const char *page = PyBytes_AS_STRING(html);
    vb_sphere_set run;
    memset(&run, 0, sizeof run);
    vb_cell_measures m;
    memset(&m, 0, sizeof m);
    vb_box box;
    int rc = periodic ? vbpy_box(c.ctx, tokens, set, &box) : VB_OK;
    if (rc < 0) {
        Py_DECREF(html);
        Py_XDECREF(vbpy_call_done(&c));
        return NULL;
    }
    Py_BEGIN_ALLOW_THREADS
    if (rc == VB_OK)
        rc = vbpy_validate(c.ctx, set, 1, &run);
    if (rc == VB_OK)
        rc = periodic ? vb_cells_run_periodic(c.ctx, &run, &box, &opt, &m)
                      : vb_cells_run(c.ctx, &run, &opt, &m);
    if (rc == VB_OK && *page)
        rc = vb_cells_page_write(c.ctx, page, title ? title : "vorball cells", &run, &m,
                                 contacts);
    Py_END_ALLOW_THREADS
    Py_DECREF(html);
    PyObject *d = rc == VB_OK ? result_dict(c.ctx, &run, &m, contacts) : NULL;
    free(run.contained);
    vb_cell_measures_free(&m);
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    return vbpy_call_return(&c, d);
}

typedef struct frames_sink {
    vbpy_frames f;
    int contacts;
} frames_sink;

/* Each frame's measures appended as (frame, model, dict), with the GIL. */
static int keep_frame(void *arg, long frame, int model, const vb_sphere_set *set,
                      const vb_cell_measures *m)
{
    frames_sink *S = arg;
    PyGILState_STATE g = PyGILState_Ensure();
    int rc = vbpy_frames_append(&S->f, frame, model, result_dict(S->f.ctx, set, m, S->contacts));
    PyGILState_Release(g);
    return rc;
}

/* `vorball cells --traj/--frames` (vb_cells_run_frames, or
 * vb_cells_run_frames_periodic): [(frame, model, dict)]. */
static PyObject *cells_frames(PyObject *self, PyObject *args)
{
    (void)self;
    const char *path, *traj;
    PyObject *tokens;
    long start, stop, step;
    int water, contacts, periodic;
    double probe, tolerance;
    Py_ssize_t max_patches, threads;
    if (!PyArg_ParseTuple(args, "szlllp(ddnpn)pO", &path, &traj, &start, &stop, &step, &water,
                          &probe, &tolerance, &max_patches, &contacts, &threads, &periodic,
                          &tokens))
        return NULL;
    vb_measure_options opt;
    measure_options(probe, tolerance, max_patches, contacts, threads, &opt);
    vbpy_call c;
    if (vbpy_call_open(&c) != 0)
        return NULL;
    if (vb_measure_options_check(c.ctx, &opt) != VB_OK)
        return vbpy_call_fail(&c, VB_EMISUSE);
    vb_box box;
    int given = periodic && tokens != Py_None;
    frames_sink S = {{0}, contacts};
    vb_read_options ro;
    int rc = vbpy_frames_open(&c, &S.f, given ? tokens : Py_None, water, &box, &ro);
    if (rc < 0)
        return NULL;
    vb_frame_range range = {start, stop, step};
    Py_BEGIN_ALLOW_THREADS
    if (rc == VB_OK)
        rc = periodic ? vb_cells_run_frames_periodic(c.ctx, path, traj, &ro, &range,
                                                     given ? &box : NULL, &opt, keep_frame, &S,
                                                     NULL)
                      : vb_cells_run_frames(c.ctx, path, traj, &ro, &range, &opt, keep_frame, &S,
                                            NULL);
    Py_END_ALLOW_THREADS
    return vbpy_frames_return(&c, &S.f, rc);
}

PyMethodDef vbpy_cells_methods[] = {
    {"cells_run", cells_run, METH_VARARGS,
     "cells_run(spheres, probe, tolerance, max_patches, contacts, threads, periodic, box_tokens, "
     "html, title) -> (dict, diagnostics)"},
    {"cells_frames", cells_frames, METH_VARARGS,
     "cells_frames(path, trajectory, start, stop, step, water, (probe, tolerance, max_patches, "
     "contacts, threads), periodic, box_tokens) -> ([(frame, model, dict)], diagnostics)"},
    {NULL, NULL, 0, NULL}};
