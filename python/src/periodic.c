/* Periodic boxes for Python (issue 34): the box of a call (`--box`'s
 * tokens or the set's own), vb_periodic_vertices_run on a set, and
 * vb_periodic_run_frames over a trajectory, each frame in its own box,
 * vb_periodic_verify_file judging a periodic vertex file; the
 * vertices handed over as arrays (members' ids and image shifts) and as
 * the library writer's text. */
#include "vbpy.h"

#include <stdlib.h>
#include <string.h>

int vbpy_box(vb_ctx *ctx, PyObject *tokens, const vb_sphere_set *set, vb_box *box)
{
    if (tokens == Py_None) {
        if (set && set->box) {
            *box = *set->box;
            return VB_OK;
        }
        return vb_error(ctx, VB_EINPUT_BOX, set ? set->source : NULL, 0,
                        "periodic: the input carries no box (GRO box line, PDB CRYST1): "
                        "give box=");
    }
    PyObject *seq = PySequence_Fast(tokens, "box tokens must be a sequence of str");
    if (!seq)
        return -1;
    Py_ssize_t n = PySequence_Fast_GET_SIZE(seq);
    const char *tok[9];
    for (Py_ssize_t k = 0; k < n && k < 9; k++)
        if (!(tok[k] = PyUnicode_AsUTF8(PySequence_Fast_GET_ITEM(seq, k)))) {
            Py_DECREF(seq);
            return -1;
        }
    int rc = vb_box_parse_args(ctx, tok, (int)(n < 1000 ? n : 1000), box); /* > 9: refused */
    Py_DECREF(seq);
    return rc;
}

/* The vertices as arrays and text, the box and the counters (see
 * python/vorball/_periodic.py). NULL with an exception. */
static PyObject *result_dict(vb_ctx *ctx, const vb_periodic_result *r, const vb_box *box)
{
    const vb_periodic_vertices *v = &r->v;
    size_t nm = v->start ? v->start[v->n] : 0;
    uint32_t *id = malloc((nm + 1) * sizeof *id);
    int16_t *sh = malloc((3 * nm + 1) * sizeof *sh);
    int64_t *st = malloc((v->n + 1) * sizeof *st);
    PyObject *d = NULL;
    if (!id || !sh || !st) {
        PyErr_NoMemory();
        goto done;
    }
    for (size_t k = 0; k < nm; k++) {
        id[k] = v->m[k].id;
        memcpy(sh + 3 * k, v->m[k].s, sizeof v->m[k].s);
    }
    for (size_t k = 0; k <= v->n; k++)
        st[k] = v->start ? (int64_t)v->start[k] : 0;
    char note[1024];
    vb_periodic_certificate(r, box, note, sizeof note);
    vbpy_text tsv, json;
    if (vbpy_text_open(&tsv) != 0)
        goto done;
    vb_periodic_write(ctx, tsv.f, v, 0, note);
    PyObject *ttsv = vbpy_text_take(&tsv);
    if (!ttsv || vbpy_text_open(&json) != 0) {
        Py_XDECREF(ttsv);
        goto done;
    }
    vb_periodic_write(ctx, json.f, v, 1, note);
    d = Py_BuildValue("{s:N,s:N,s:N,s:N,s:N,s:N,s:N,s:N,s:N,s:N,s:s,s:n,s:n,s:d,s:d,s:n,s:n}",
                      "ids", vbpy_bytes(id, nm, 4), "shifts", vbpy_bytes(sh, 3 * nm, 2), "start",
                      vbpy_bytes(st, v->n + 1, 8), "x", vbpy_bytes(v->x, v->n, 8), "y",
                      vbpy_bytes(v->y, v->n, 8), "z", vbpy_bytes(v->z, v->n, 8), "t",
                      vbpy_bytes(v->t, v->n, 8), "box", vbpy_bytes(box->v, 9, 8), "tsv", ttsv,
                      "json", vbpy_text_take(&json), "certificate", note, "atoms",
                      (Py_ssize_t)r->img.n0, "spheres",
                      (Py_ssize_t)(r->img.set ? r->img.set->n : 0), "rho", r->img.rho, "reach",
                      r->img.reach, "translates", (Py_ssize_t)r->translates, "beyond_rho",
                      (Py_ssize_t)r->beyond_rho);
done:
    free(id);
    free(sh);
    free(st);
    return d;
}

/* Fills cfg from the tuple (device, proposer, samples, tol, tiles,
 * all_pairs, threads, progress) and opens the call *c with that progress
 * callable (the tuple, an argument, outlives the call). 0, or -1 with an
 * exception set (nothing open). */
static int run_open(PyObject *args, vb_vertices_config *cfg, vbpy_call *c)
{
    PyObject *progress;
    const char *device;
    PyObject *proposer;
    unsigned samples, tiles, threads;
    double tol;
    int all_pairs;
    if (!PyArg_ParseTuple(args, "sOIdIpIO", &device, &proposer, &samples, &tol, &tiles,
                          &all_pairs, &threads, &progress))
        return -1;
    if (vbpy_vertices_config(device, proposer, cfg) != 0)
        return -1;
    cfg->propose.samples = samples;
    cfg->propose.tol = tol;
    cfg->propose.tiles = tiles;
    cfg->propose.all_pairs = all_pairs;
    cfg->propose.threads = threads;
    if (vbpy_progress_check(progress) != 0 || vbpy_call_open(c) != 0)
        return -1;
    vbpy_call_progress(c, progress);
    return 0;
}

static PyObject *periodic_vertices(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *cap, *engine, *tokens, *opts;
    if (!PyArg_ParseTuple(args, "OOOO!", &cap, &engine, &tokens, &PyTuple_Type, &opts))
        return NULL;
    vb_vertices_config cfg;
    vbpy_call c;
    vb_vertices_engine *e;
    vb_sphere_set *set = vbpy_spheres_get(cap);
    if (!set || vbpy_engine_get(engine, &e) != 0 || run_open(opts, &cfg, &c) != 0)
        return NULL;
    vb_box box;
    int rc = vbpy_box(c.ctx, tokens, set, &box);
    if (rc < 0) {
        Py_XDECREF(vbpy_call_done(&c));
        return NULL;
    }
    vb_periodic_result res;
    vb_periodic_result_init(&res);
    vb_sphere_set run;
    memset(&run, 0, sizeof run);
    Py_BEGIN_ALLOW_THREADS
    if (rc == VB_OK)
        rc = vbpy_validate(c.ctx, set, 1, &run);
    if (rc == VB_OK)
        rc = e ? vb_periodic_vertices_run_on(c.ctx, e, &run, &box, &cfg, &res)
               : vb_periodic_vertices_run(c.ctx, &run, &box, &cfg, vb_default_backends(), &res);
    free(run.contained);
    Py_END_ALLOW_THREADS
    PyObject *d = rc == VB_OK ? result_dict(c.ctx, &res, &box) : NULL;
    vb_periodic_result_free(&res);
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    return vbpy_call_return(&c, d);
}

/* Each frame's result appended as (frame, model, dict), with the GIL. */
static int keep_frame(void *arg, long frame, int model, const vb_sphere_set *set,
                      const vb_box *box, const vb_periodic_result *res)
{
    vbpy_frames *S = arg;
    (void)set;
    PyGILState_STATE g = PyGILState_Ensure();
    int rc = vbpy_frames_append(S, frame, model, result_dict(S->ctx, res, box));
    PyGILState_Release(g);
    return rc;
}

static PyObject *periodic_frames(PyObject *self, PyObject *args)
{
    (void)self;
    const char *path, *traj;
    PyObject *tokens, *opts;
    long start, stop, step;
    int water;
    if (!PyArg_ParseTuple(args, "szOlllpO!", &path, &traj, &tokens, &start, &stop, &step, &water,
                          &PyTuple_Type, &opts))
        return NULL;
    vb_vertices_config cfg;
    vbpy_call c;
    if (run_open(opts, &cfg, &c) != 0)
        return NULL;
    vb_box box;
    vbpy_frames S;
    vb_read_options ro;
    int rc = vbpy_frames_open(&c, &S, tokens, water, &box, &ro);
    if (rc < 0)
        return NULL;
    vb_frame_range range = {start, stop, step};
    Py_BEGIN_ALLOW_THREADS
    if (rc == VB_OK)
        rc = vb_periodic_run_frames(c.ctx, path, traj, &ro, &range,
                                    tokens == Py_None ? NULL : &box, &cfg, keep_frame, &S, NULL);
    Py_END_ALLOW_THREADS
    return vbpy_frames_return(&c, &S, rc);
}

/* vb_periodic_verify_file on a path: (dict of counts and per-line arrays
 * line (int64), flags (uint8: VB_PERIODIC_*), problems (int32:
 * VB_VERIFY_*), diagnostics). */
static PyObject *periodic_verify(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *cap, *tokens, *path;
    double tol;
    if (!PyArg_ParseTuple(args, "OO&Od", &cap, PyUnicode_FSConverter, &path, &tokens, &tol))
        return NULL;
    vb_sphere_set *set = vbpy_spheres_get(cap);
    vbpy_call c;
    if (!set || vbpy_call_open(&c) != 0) {
        Py_DECREF(path);
        return NULL;
    }
    vb_box box;
    int rc = vbpy_box(c.ctx, tokens, set, &box);
    if (rc < 0) {
        Py_DECREF(path);
        Py_XDECREF(vbpy_call_done(&c));
        return NULL;
    }
    vb_periodic_judgement j;
    memset(&j, 0, sizeof j);
    vb_sphere_set run;
    memset(&run, 0, sizeof run);
    const char *p = PyBytes_AS_STRING(path);
    Py_BEGIN_ALLOW_THREADS
    if (rc == VB_OK)
        rc = vbpy_validate(c.ctx, set, 1, &run);
    if (rc == VB_OK)
        rc = vb_periodic_verify_file(c.ctx, &run, &box, p, tol, &j);
    free(run.contained);
    Py_END_ALLOW_THREADS
    Py_DECREF(path);
    PyObject *d = NULL;
    int64_t *line = rc == VB_OK ? malloc((j.n + 1) * sizeof *line) : NULL;
    if (rc == VB_OK && !line)
        PyErr_NoMemory();
    else if (rc == VB_OK) {
        for (size_t k = 0; k < j.n; k++)
            line[k] = j.line[k];
        d = Py_BuildValue("{s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:N,s:N,s:N}", "lines",
                          (Py_ssize_t)j.n, "certified", (Py_ssize_t)j.certified, "not_canonical",
                          (Py_ssize_t)j.not_canonical, "beyond_reach", (Py_ssize_t)j.beyond,
                          "not_vertex", (Py_ssize_t)j.not_vertex, "wrong_coordinates",
                          (Py_ssize_t)j.wrong, "missing_members", (Py_ssize_t)j.missing,
                          "duplicate", (Py_ssize_t)j.duplicate, "line", vbpy_bytes(line, j.n, 8),
                          "flags", vbpy_bytes(j.flags, j.n, 1), "problems",
                          vbpy_bytes(j.problems, j.n, sizeof *j.problems));
    }
    free(line);
    vb_periodic_judgement_free(&j);
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    return vbpy_call_return(&c, d);
}

PyMethodDef vbpy_periodic_methods[] = {
    {"periodic_vertices", periodic_vertices, METH_VARARGS,
     "periodic_vertices(spheres, engine, box_tokens, (device, proposer, samples, tol, tiles, "
     "all_pairs, threads, progress)) -> (dict, diagnostics)"},
    {"periodic_frames", periodic_frames, METH_VARARGS,
     "periodic_frames(path, trajectory, box_tokens, start, stop, step, water, (device, proposer, "
     "samples, tol, tiles, all_pairs, threads, progress)) -> ([(frame, model, dict)], "
     "diagnostics)"},
    {"periodic_verify", periodic_verify, METH_VARARGS,
     "periodic_verify(spheres, path, box_tokens, tol) -> (dict, diagnostics)"},
    {NULL, NULL, 0, NULL}};
