/* The vertex flow for Python: vb_vertices_run_complete (or a run on an
 * engine opened once, for trajectories, then vb_vertices_complete) on a
 * set, its certified vertices, completion (arc closure, faces and edges,
 * certificate) and counters handed back, and the library's writer of
 * vertex files. */
#include "vbpy.h"

#include <stdlib.h>
#include <string.h>

#define ENGINE_CAPSULE "vorball.vertices_engine"

static void engine_destroy(PyObject *cap)
{
    vb_vertices_close(PyCapsule_GetPointer(cap, ENGINE_CAPSULE));
}

int vbpy_engine_get(PyObject *o, vb_vertices_engine **out)
{
    *out = NULL;
    if (o == Py_None)
        return 0;
    *out = PyCapsule_GetPointer(o, ENGINE_CAPSULE);
    return *out ? 0 : -1;
}

int vbpy_vertices_config(const char *device, PyObject *proposer, vb_vertices_config *cfg)
{
    memset(cfg, 0, sizeof *cfg);
    int kind;
    if (vbpy_device_kind(device, &kind) != 0)
        return -1;
    cfg->device = (vb_device_kind)kind;
    if (proposer != Py_None) {
        if (!(cfg->proposer = PyUnicode_AsUTF8(proposer)))
            return -1;
        if (!vb_proposer_find(cfg->proposer)) {
            vbpy_raise(VB_EMISUSE, "unknown proposer '%s'", cfg->proposer);
            return -1;
        }
    }
    return 0;
}

static PyObject *engine_open(PyObject *self, PyObject *args)
{
    (void)self;
    const char *device;
    PyObject *proposer;
    if (!PyArg_ParseTuple(args, "sO", &device, &proposer))
        return NULL;
    vb_vertices_config cfg;
    vbpy_call c;
    if (vbpy_vertices_config(device, proposer, &cfg) != 0 || vbpy_call_open(&c) != 0)
        return NULL;
    vb_vertices_engine *e = NULL;
    int rc;
    Py_BEGIN_ALLOW_THREADS
    rc = vb_vertices_open(c.ctx, vb_default_backends(), &cfg, &e);
    Py_END_ALLOW_THREADS
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    PyObject *cap = PyCapsule_New(e, ENGINE_CAPSULE, engine_destroy);
    if (!cap)
        vb_vertices_close(e);
    return vbpy_call_return(&c, cap);
}

/* The seconds the engine took to open (`vorball bench`'s device set-up). */
static PyObject *engine_seconds(PyObject *self, PyObject *cap)
{
    (void)self;
    vb_vertices_engine *e;
    if (vbpy_engine_get(cap, &e) != 0)
        return NULL;
    return PyFloat_FromDouble(e ? vb_vertices_open_seconds(e) : 0.0);
}

static PyObject *vertex_arrays(const vb_vertex_list *v, PyObject *d)
{
    int64_t *start = malloc((v->n + 1) * sizeof *start);
    if (!start)
        return PyErr_NoMemory();
    for (size_t k = 0; k <= v->n; k++)
        start[k] = v->start ? (int64_t)v->start[k] : 0;
    PyObject *sb = vbpy_bytes(start, v->n + 1, 8);
    free(start);
    int bad = !sb || PyDict_SetItemString(d, "start", sb) != 0;
    Py_XDECREF(sb);
    const struct {
        const char *key;
        const void *p;
        size_t n, size;
    } a[] = {{"ids", v->ids, v->nids, 4}, {"x", v->x, v->n, 8}, {"y", v->y, v->n, 8},
             {"z", v->z, v->n, 8},        {"t", v->t, v->n, 8}, {"dist", v->dist, v->n, 8}};
    for (size_t k = 0; k < sizeof a / sizeof a[0] && !bad; k++) {
        PyObject *b = vbpy_bytes(a[k].p, a[k].n, a[k].size);
        bad = !b || PyDict_SetItemString(d, a[k].key, b) != 0;
        Py_XDECREF(b);
    }
    return bad ? NULL : d;
}

PyObject *vbpy_arcs_dict(const vb_arc_report *a)
{
    return Py_BuildValue("{s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:O}", "vertices",
                         (Py_ssize_t)a->vertices, "half_arcs", (Py_ssize_t)a->half_arcs,
                         "closed", (Py_ssize_t)a->closed, "infinite", (Py_ssize_t)a->infinite,
                         "loops", (Py_ssize_t)a->loops, "undecided", (Py_ssize_t)a->undecided,
                         "components", (Py_ssize_t)a->components, "added",
                         (Py_ssize_t)a->added.n,
                         "complete", vb_arc_report_complete(a) ? Py_True : Py_False);
}

/* The faces and edges as bytes (faces: uint32 pairs; edges: int64 vertex
 * rows, -1 for infinity, and uint32 sphere triples) and the file of
 * `--topology FILE` as text (vb_topology_write), or None. */
static PyObject *topology_dict(vb_ctx *ctx, const vb_completion *c)
{
    const vb_topology *t = &c->topology;
    if (!c->has_topology)
        Py_RETURN_NONE;
    int64_t *v = malloc((2 * t->nedges + 1) * sizeof *v);
    uint32_t *sp = malloc((3 * t->nedges + 1) * sizeof *sp);
    if (!v || !sp) {
        free(v);
        free(sp);
        return PyErr_NoMemory();
    }
    for (size_t k = 0; k < t->nedges; k++) {
        memcpy(v + 2 * k, t->edges[k].v, sizeof t->edges[k].v);
        memcpy(sp + 3 * k, t->edges[k].spheres, sizeof t->edges[k].spheres);
    }
    vbpy_text txt;
    if (vbpy_text_open(&txt) != 0) {
        free(v);
        free(sp);
        return NULL;
    }
    int rc = vb_topology_write(ctx, txt.f, t);
    PyObject *text = vbpy_text_take(&txt);
    if (rc != VB_OK && text)
        Py_SETREF(text, PyErr_NoMemory());
    PyObject *d = !text ? NULL : Py_BuildValue("{s:N,s:N,s:N,s:O,s:n,s:n,s:N}", "faces",
                                vbpy_bytes(t->faces, 2 * t->nfaces, 4), "edges",
                                vbpy_bytes(v, 2 * t->nedges, 8), "edge_spheres",
                                vbpy_bytes(sp, 3 * t->nedges, 4), "exact",
                                t->exact ? Py_True : Py_False, "unresolved",
                                (Py_ssize_t)t->unresolved, "sampled", (Py_ssize_t)t->sampled,
                                "text", text);
    free(v);
    free(sp);
    return d;
}

/* The --stats table (vb_stat_field.h) as a dict of its typed values:
 * int, float (full precision, not the printed digits) or str. */
static PyObject *stats_dict(const vb_stat_fields *fs)
{
    PyObject *d = PyDict_New();
    for (size_t i = 0; d && i < fs->n; i++) {
        const vb_stat_field *e = &fs->f[i];
        PyObject *v = e->kind == VB_STAT_UINT   ? PyLong_FromUnsignedLongLong(e->u)
                      : e->kind == VB_STAT_REAL ? PyFloat_FromDouble(e->x)
                                                : PyUnicode_FromString(e->s ? e->s : "");
        if (!v || PyDict_SetItemString(d, e->name, v) != 0)
            Py_CLEAR(d);
        Py_XDECREF(v);
    }
    return d;
}

/* The result of a run as a dict (see python/vorball/_vertices.py). */
static PyObject *result_dict(vb_ctx *ctx, const vb_vertices_result *r, const vb_completion *c)
{
    const vb_proposal *s = &r->proposal;
    const char *note = c->certificate;
    vb_stat_fields *fs = malloc(sizeof *fs);
    if (!fs)
        return PyErr_NoMemory();
    fs->n = 0;
    vb_vertices_stats(ctx, r, fs);
    if (c->traced)
        vb_arc_stats(&c->arcs, fs);
    PyObject *stats = stats_dict(fs);
    free(fs);
    if (!stats)
        return NULL;
    const vb_stage_times *tm = &s->times;
    PyObject *d = Py_BuildValue(
        "{s:N,s:s,s:O,s:n,s:n,s:K,s:K,s:K,s:K,s:s,s:s,s:d,s:n,"
        "s:{s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d,s:d}}",
        "stats", stats, "certificate", note, "complete", s->complete ? Py_True : Py_False,
        "certified", (Py_ssize_t)r->certified.n, "rejected", (Py_ssize_t)r->rejected.n,
        "quadruples", (unsigned long long)s->cover_quads, "cover_cells",
        (unsigned long long)s->cover_cells,
        "cover_patches", (unsigned long long)s->cover_patches, "cover_host_cells",
        (unsigned long long)s->cover_host_cells, "backend", r->backend, "device", r->device,
        "max_distance", r->max_dist, "repaired", (Py_ssize_t)r->repaired_candidates, "times",
        "setup", r->t_setup, "setup_wait", r->t_setup_wait, "certify", r->t_certify, "total",
        r->t_total, "cull", tm->cull, "upload", tm->upload, "envelope", tm->envelope, "vertices",
        tm->vertices, "matching", tm->matching, "targeted", tm->targeted, "tangent", tm->tangent,
        "completion", tm->completion, "cover_device", s->t_cover_device);
    if (!d)
        return NULL;
    PyObject *arcs = c->traced ? vbpy_arcs_dict(&c->arcs) : Py_NewRef(Py_None);
    PyObject *topo = arcs ? topology_dict(ctx, c) : NULL;
    int bad = !topo || PyDict_SetItemString(d, "arcs", arcs) != 0 ||
              PyDict_SetItemString(d, "topology", topo) != 0;
    Py_XDECREF(arcs);
    Py_XDECREF(topo);
    if (bad || !vertex_arrays(&r->certified, d)) {
        Py_DECREF(d);
        return NULL;
    }
    return d;
}

static PyObject *vertices_run(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *cap, *engine, *proposer, *progress;
    const char *device;
    unsigned samples, tiles, threads;
    double tol;
    int all_pairs;
    vb_completion_opts co = {0};
    if (!PyArg_ParseTuple(args, "OOsOIdIpIppO", &cap, &engine, &device, &proposer, &samples, &tol,
                          &tiles, &all_pairs, &threads, &co.arcs, &co.topology, &progress))
        return NULL;
    vb_sphere_set *set = vbpy_spheres_get(cap);
    vb_vertices_engine *e = engine == Py_None ? NULL : PyCapsule_GetPointer(engine, ENGINE_CAPSULE);
    vb_vertices_config cfg;
    if (!set || (engine != Py_None && !e) || vbpy_vertices_config(device, proposer, &cfg) != 0)
        return NULL;
    cfg.propose.samples = samples;
    cfg.propose.tol = tol;
    cfg.propose.tiles = tiles;
    cfg.propose.all_pairs = all_pairs;
    cfg.propose.threads = threads;
    vbpy_call c;
    if (vbpy_progress_check(progress) != 0 || vbpy_call_open(&c) != 0)
        return NULL;
    vbpy_call_progress(&c, progress);
    vb_vertices_result res;
    vb_vertices_result_init(&res);
    vb_completion done;
    vb_completion_init(&done);
    int rc;
    vb_sphere_set run;
    Py_BEGIN_ALLOW_THREADS
    rc = vbpy_validate(c.ctx, set, 4, &run);
    if (rc == VB_OK && e) {
        vb_completion_plan(&cfg, &co);
        rc = vb_vertices_run_on(c.ctx, e, &run, &cfg, &res);
        if (rc == VB_OK)
            rc = vb_vertices_complete(c.ctx, &run, &res, res.rejected.n, &co, &done);
    } else if (rc == VB_OK) {
        rc = vb_vertices_run_complete(c.ctx, &run, &cfg, &co, &res, &done);
    }
    free(run.contained);
    Py_END_ALLOW_THREADS
    PyObject *d = rc == VB_OK ? result_dict(c.ctx, &res, &done) : NULL;
    vb_completion_free(&done);
    vb_vertices_result_free(&res);
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    return vbpy_call_return(&c, d);
}

int vbpy_vertex_list(PyObject *ids, PyObject *start, PyObject *x, PyObject *y, PyObject *z,
                     PyObject *t, int status, vb_vertex_list *out)
{
    vb_vertex_list_init(out);
    Py_buffer b[6];
    PyObject *o[6] = {ids, start, x, y, z, t};
    int got = 0, rc = 0;
    for (; got < 6; got++)
        if (PyObject_GetBuffer(o[got], &b[got], PyBUF_C_CONTIGUOUS) != 0) {
            rc = -1;
            break;
        }
    size_t n = 0, nids = 0;
    if (rc == 0) {
        nids = (size_t)b[0].len / 4;
        n = (size_t)b[1].len / 8;
        n = n ? n - 1 : 0;
        for (int k = 2; k < 6; k++)
            if ((size_t)b[k].len != 8 * n)
                rc = -1;
        if (rc)
            PyErr_SetString(PyExc_ValueError, "vertex arrays of different lengths");
    }
    const uint32_t *id = rc == 0 ? b[0].buf : NULL;
    const int64_t *st = rc == 0 ? b[1].buf : NULL;
    for (size_t k = 0; rc == 0 && k < n; k++) {
        if (st[k] < 0 || st[k + 1] < st[k] || (size_t)st[k + 1] > nids) {
            PyErr_SetString(PyExc_ValueError, "vertex offsets out of order");
            rc = -1;
            break;
        }
        const double *xs = b[2].buf, *ys = b[3].buf, *zs = b[4].buf, *ts = b[5].buf;
        if (vb_vertex_list_push(out, id + st[k], (size_t)(st[k + 1] - st[k]), xs[k], ys[k], zs[k],
                                ts[k], 0.0, status) != VB_OK) {
            PyErr_NoMemory();
            rc = -1;
        }
    }
    while (got > 0)
        PyBuffer_Release(&b[--got]);
    if (rc)
        vb_vertex_list_free(out);
    return rc;
}

static PyObject *vertex_text(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *ids, *start, *x, *y, *z, *t, *comment;
    const char *format;
    if (!PyArg_ParseTuple(args, "OOOOOOsO", &ids, &start, &x, &y, &z, &t, &format, &comment))
        return NULL;
    const char *note = comment == Py_None ? NULL : PyUnicode_AsUTF8(comment);
    if (comment != Py_None && !note)
        return NULL;
    vb_vertex_format fmt;
    if (vb_vertex_format_parse(NULL, format, &fmt) != VB_OK)
        return vbpy_raise(VB_EMISUSE,
                          "vertex format must be tsv, json, voronota or npz, not '%s'", format);
    vb_vertex_list v;
    if (vbpy_vertex_list(ids, start, x, y, z, t, VB_VERTEX_CERTIFIED, &v) != 0)
        return NULL;
    vbpy_text out;
    vbpy_call c;
    if (vbpy_text_open(&out) != 0) {
        vb_vertex_list_free(&v);
        return NULL;
    }
    if (vbpy_call_open(&c) != 0) {
        Py_XDECREF(vbpy_text_take(&out));
        vb_vertex_list_free(&v);
        return NULL;
    }
    int rc = vb_vertex_write(c.ctx, out.f, &v, fmt, note && *note ? note : NULL);
    vb_vertex_list_free(&v);
    PyObject *s;
    if (fmt == VB_VFMT_NPZ) { /* a binary archive: bytes */
        fclose(out.f);
        s = PyBytes_FromStringAndSize(out.buf ? out.buf : "", (Py_ssize_t)out.len);
        free(out.buf);
    } else {
        s = vbpy_text_take(&out);
    }
    if (rc != VB_OK) {
        Py_XDECREF(s);
        return vbpy_call_fail(&c, rc);
    }
    Py_XDECREF(vbpy_call_done(&c));
    return s;
}

/* `vorball vertices --html`: the results page of certified vertices
 * (vb_vertex_page_write: E133 past its size, E7 without the viewer). */
static PyObject *vertex_page(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *cap, *ids, *start, *x, *y, *z, *t, *path;
    const char *certificate, *title;
    if (!PyArg_ParseTuple(args, "OOOOOOOzO&s", &cap, &ids, &start, &x, &y, &z, &t, &certificate,
                          PyUnicode_FSConverter, &path, &title))
        return NULL;
    vb_sphere_set *set = vbpy_spheres_get(cap);
    vb_vertex_list v;
    vbpy_call c;
    if (!set || vbpy_vertex_list(ids, start, x, y, z, t, VB_VERTEX_CERTIFIED, &v) != 0) {
        Py_DECREF(path);
        return NULL;
    }
    if (vbpy_call_open(&c) != 0) {
        vb_vertex_list_free(&v);
        Py_DECREF(path);
        return NULL;
    }
    int rc;
    Py_BEGIN_ALLOW_THREADS
    rc = vb_vertex_page_check(c.ctx, set);
    if (rc == VB_OK)
        rc = vb_vertex_page_write(c.ctx, PyBytes_AS_STRING(path), title, set, &v, certificate);
    Py_END_ALLOW_THREADS
    vb_vertex_list_free(&v);
    Py_DECREF(path);
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    return vbpy_call_return(&c, Py_NewRef(Py_None));
}

/* `vorball reference`: every vertex exactly by brute force (vb_reference_run,
 * E130 above 500 spheres unless force): the vertex arrays and the count. */
static PyObject *reference_run(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *cap;
    int force;
    if (!PyArg_ParseTuple(args, "Op", &cap, &force))
        return NULL;
    vb_sphere_set *set = vbpy_spheres_get(cap);
    vbpy_call c;
    if (!set || vbpy_call_open(&c) != 0)
        return NULL;
    vb_vertex_list out;
    vb_vertex_list_init(&out);
    int rc;
    vb_sphere_set run;
    Py_BEGIN_ALLOW_THREADS
    rc = vbpy_validate(c.ctx, set, 4, &run);
    if (rc == VB_OK)
        rc = vb_reference_run(c.ctx, &run, force, set->source, &out);
    free(run.contained);
    Py_END_ALLOW_THREADS
    /* The counts `vorball reference --stats` prints (vb_ctx_stats). */
    const vb_stats *st = vb_ctx_stats(c.ctx);
    PyObject *d = rc == VB_OK ? Py_BuildValue("{s:n,s:{s:K,s:K,s:K,s:K,s:K}}", "certified",
                                              (Py_ssize_t)out.n, "stats", "quadruples",
                                              (unsigned long long)st->candidates, "refuted",
                                              (unsigned long long)st->rejected, "filter_calls",
                                              (unsigned long long)st->filter_calls, "undecided",
                                              (unsigned long long)st->filter_failures,
                                              "exact_evals", (unsigned long long)st->exact_evals)
                              : NULL;
    if (d && !vertex_arrays(&out, d))
        Py_CLEAR(d);
    vb_vertex_list_free(&out);
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    return vbpy_call_return(&c, d);
}

PyMethodDef vbpy_vertices_methods[] = {
    {"reference_run", reference_run, METH_VARARGS,
     "reference_run(spheres, force) -> (dict, diagnostics)"},
    {"vertices_engine_open", engine_open, METH_VARARGS,
     "vertices_engine_open(device, proposer) -> (capsule, diagnostics)"},
    {"vertices_engine_seconds", engine_seconds, METH_O,
     "vertices_engine_seconds(capsule) -> float: the seconds opening took"},
    {"vertices_run", vertices_run, METH_VARARGS,
     "vertices_run(spheres, engine, device, proposer, samples, tol, tiles, all_pairs, threads, "
     "arcs, topology) -> (dict, diagnostics)"},
    {"vertex_page", vertex_page, METH_VARARGS,
     "vertex_page(spheres, ids, start, x, y, z, t, certificate, path, title) -> (None, "
     "diagnostics)"},
    {"vertex_text", vertex_text, METH_VARARGS,
     "vertex_text(ids, start, x, y, z, t, format, comment) -> str (bytes for npz: the "
     "library's writer)"},
    {NULL, NULL, 0, NULL}};
