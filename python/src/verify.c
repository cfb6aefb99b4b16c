/* Exact judgement of vertices for Python: a vertex file (vb_verify_file,
 * as `vorball verify` reads it) or vertices in memory (vb_verify_list),
 * with arc closure when asked (vb_verify_arcs, as `--arcs`), every line's
 * verdict and the report the command writes. */
#include "vbpy.h"

#include <stdlib.h>
#include <string.h>

/* The per-line judgements as bytes: problems (int32), line (int64), dist
 * and dt (float64), exact x y z t (4 float64 per line), intruder
 * (uint32, UINT32_MAX when none). */
static int line_arrays(const vb_verify_report *r, PyObject *d)
{
    size_t n = r->vertices.n, m = n ? n : 1;
    int32_t *prob = malloc(m * sizeof *prob);
    int64_t *line = malloc(m * sizeof *line);
    double *dist = malloc(m * sizeof *dist), *dt = malloc(m * sizeof *dt);
    double *ex = malloc(4 * m * sizeof *ex);
    uint32_t *intr = malloc(m * sizeof *intr);
    int bad = !prob || !line || !dist || !dt || !ex || !intr;
    for (size_t k = 0; !bad && k < n; k++) {
        const vb_verify_line *j = &r->judged[k];
        prob[k] = j->problems;
        line[k] = r->lines ? r->lines[k] : (int64_t)k + 1;
        dist[k] = j->dist;
        dt[k] = j->dt;
        memcpy(ex + 4 * k, j->ex, sizeof j->ex);
        intr[k] = (j->problems & VB_VERIFY_NOT_VERTEX) ? j->intruder : UINT32_MAX;
    }
    const struct {
        const char *key;
        const void *p;
        size_t n, size;
    } a[] = {{"problems", prob, n, 4}, {"line", line, n, 8},    {"dist", dist, n, 8},
             {"dt", dt, n, 8},         {"exact", ex, 4 * n, 8}, {"intruder", intr, n, 4}};
    for (size_t k = 0; k < sizeof a / sizeof a[0] && !bad; k++) {
        PyObject *b = vbpy_bytes(a[k].p, a[k].n, a[k].size);
        bad = !b || PyDict_SetItemString(d, a[k].key, b) != 0;
        Py_XDECREF(b);
    }
    free(prob);
    free(line);
    free(dist);
    free(dt);
    free(ex);
    free(intr);
    if (bad && !PyErr_Occurred())
        PyErr_NoMemory();
    return bad ? -1 : 0;
}

/* The missed vertices (with complete) as ids/start/x/y/z/t bytes. */
static PyObject *missed_dict(const vb_vertex_list *v)
{
    int64_t *start = malloc((v->n + 1) * sizeof *start);
    if (!start)
        return PyErr_NoMemory();
    for (size_t k = 0; k <= v->n; k++)
        start[k] = v->start ? (int64_t)v->start[k] : 0;
    PyObject *d = Py_BuildValue("{s:N,s:N,s:N,s:N,s:N,s:N}", "ids", vbpy_bytes(v->ids, v->nids, 4),
                                "start", vbpy_bytes(start, v->n + 1, 8), "x",
                                vbpy_bytes(v->x, v->n, 8), "y", vbpy_bytes(v->y, v->n, 8), "z",
                                vbpy_bytes(v->z, v->n, 8), "t", vbpy_bytes(v->t, v->n, 8));
    free(start);
    return d;
}

/* Arc closure's counts and the vertices it found that the lines miss, or
 * None when it did not run. */
static PyObject *arcs_dict(const vb_arc_report *a)
{
    if (!a)
        Py_RETURN_NONE;
    PyObject *d = vbpy_arcs_dict(a), *m = d ? missed_dict(&a->added) : NULL;
    if (!m || PyDict_SetItemString(d, "missing", m) != 0)
        Py_CLEAR(d);
    Py_XDECREF(m);
    return d;
}

/* The report as a dict; with a (arc closure ran) its text and JSON as
 * `--arcs` writes them, and ok only when the closure is complete too. */
static PyObject *report_dict(vb_ctx *ctx, const vb_sphere_set *set, const char *spheres_name,
                             const char *name, const vb_verify_report *r, const vb_arc_report *a)
{
    vbpy_text text, json;
    if (vbpy_text_open(&text) != 0)
        return NULL;
    if (vbpy_text_open(&json) != 0) {
        Py_XDECREF(vbpy_text_take(&text));
        return NULL;
    }
    int rc = vb_verify_write_text(ctx, text.f, name, set, r);
    if (rc == VB_OK && a)
        rc = vb_arc_write_text(ctx, text.f, name, a);
    if (rc == VB_OK)
        rc = a ? vb_verify_write_json_arcs(ctx, json.f, spheres_name, name, set, r, a)
               : vb_verify_write_json(ctx, json.f, spheres_name, name, set, r);
    PyObject *ts = vbpy_text_take(&text), *js = vbpy_text_take(&json);
    if (rc != VB_OK) {
        Py_XDECREF(ts);
        Py_XDECREF(js);
        return PyErr_NoMemory();
    }
    static const char *const formats[] = {"tsv", "json", "voronota"};
    const vb_verify_counts *n = &r->counts;
    int ok = vb_verify_report_ok(r) && (!a || vb_arc_report_complete(a));
    PyObject *d = Py_BuildValue(
        "{s:N,s:N,s:O,s:s,s:d,s:{s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n},s:N,s:N}", "text", ts, "json",
        js, "ok", ok ? Py_True : Py_False, "format", formats[r->format], "tol",
        r->tol, "counts", "lines", (Py_ssize_t)n->lines, "certified", (Py_ssize_t)n->certified,
        "not_vertex", (Py_ssize_t)n->not_vertex, "wrong", (Py_ssize_t)n->wrong, "missing",
        (Py_ssize_t)n->missing, "duplicate", (Py_ssize_t)n->duplicate, "missed",
        (Py_ssize_t)n->missed, "groups", (Py_ssize_t)n->groups, "missed", missed_dict(&r->missed),
        "arcs", arcs_dict(a));
    if (d && line_arrays(r, d) != 0)
        Py_CLEAR(d);
    return d;
}

static PyObject *verify_run(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *cap, *vertices, *progress;
    const char *format, *name, *spheres_name;
    double tol;
    int complete, arcs;
    unsigned threads;
    if (!PyArg_ParseTuple(args, "OOssdpspIO", &cap, &vertices, &format, &name, &tol, &complete,
                          &spheres_name, &arcs, &threads, &progress))
        return NULL;
    vb_sphere_set *set = vbpy_spheres_get(cap);
    if (!set)
        return NULL;
    if (!(tol > 0))
        return vbpy_raise(VB_EMISUSE, "tol must be > 0, not %g", tol);
    vb_vertex_format fmt;
    if (vb_vertex_format_parse(NULL, format, &fmt) != VB_OK)
        return vbpy_raise(VB_EMISUSE, "vertex format must be tsv, json or voronota, not '%s'",
                          format);
    PyObject *path = NULL;
    vb_vertex_list v;
    vb_vertex_list_init(&v);
    if (PyTuple_Check(vertices)) {
        PyObject *a[6];
        if (!PyArg_ParseTuple(vertices, "OOOOOO", &a[0], &a[1], &a[2], &a[3], &a[4], &a[5]) ||
            vbpy_vertex_list(a[0], a[1], a[2], a[3], a[4], a[5], VB_VERTEX_CANDIDATE, &v) != 0)
            return NULL;
    } else if (!PyUnicode_FSConverter(vertices, &path)) {
        return NULL;
    }
    vbpy_call c;
    if (vbpy_progress_check(progress) != 0 || vbpy_call_open(&c) != 0) {
        Py_XDECREF(path);
        vb_vertex_list_free(&v);
        return NULL;
    }
    vbpy_call_progress(&c, progress);
    vb_verify_report r;
    int rc;
    const char *p = path ? PyBytes_AS_STRING(path) : NULL;
    vb_sphere_set run;
    vb_arc_report ar;
    memset(&r, 0, sizeof r);
    memset(&ar, 0, sizeof ar);
    vb_vertex_list_init(&ar.added);
    Py_BEGIN_ALLOW_THREADS
    rc = vbpy_validate(c.ctx, set, 4, &run);
    if (rc == VB_OK)
        rc = p ? vb_verify_file(c.ctx, &run, p, tol, complete, &r)
               : vb_verify_list(c.ctx, &run, name, &v, fmt, tol, complete, &r);
    if (rc == VB_OK && arcs)
        rc = vb_verify_arcs(c.ctx, &run, &r, threads, &ar);
    Py_END_ALLOW_THREADS
    vb_vertex_list_free(&v);
    PyObject *d = rc == VB_OK ? report_dict(c.ctx, &run, spheres_name, p ? p : name, &r,
                                            arcs ? &ar : NULL)
                              : NULL;
    free(run.contained);
    vb_arc_report_free(&ar);
    vb_verify_report_free(&r);
    Py_XDECREF(path);
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    return vbpy_call_return(&c, d);
}

PyMethodDef vbpy_verify_methods[] = {
    {"verify_run", verify_run, METH_VARARGS,
     "verify_run(spheres, path or (ids, start, x, y, z, t), format, name, tol, complete, "
     "spheres_name, arcs, threads) -> (dict, diagnostics)"},
    {NULL, NULL, 0, NULL}};
