/* The C side of the Python package (vorball._core): one library context
 * per call, its diagnostics captured instead of printed, failures raised as
 * vorball.VorballError, sphere sets and engines held in capsules. The
 * Python modules of python/vorball/ turn what these functions return
 * (bytes, tuples, text) into NumPy arrays; nothing here needs NumPy. */
#ifndef VBPY_H
#define VBPY_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <stdio.h>

/* Py_NewRef came with Python 3.10; the package supports 3.9 (pyproject). */
#if PY_VERSION_HEX < 0x030A0000
static inline PyObject *vbpy_newref(PyObject *o)
{
    Py_INCREF(o);
    return o;
}
#define Py_NewRef vbpy_newref
#endif

#include "vorball.h"

/* One library call's context: its diagnostics are collected as records
 * through the log callback (vb_set_log), never printed and never parsed
 * back from text (the Python side warns or prints them). */
typedef struct vbpy_record {
    char kind;
    int number;
    char *file;             /* NULL when none */
    long line;
    char *message;
} vbpy_record;

typedef struct vbpy_call {
    vb_ctx *ctx;
    vbpy_record *rec;
    size_t n, cap;
    int lost;               /* a record could not be kept (out of memory) */
    void *lock;             /* pthread_mutex_t: threads of a run may log at once */
    PyObject *progress;     /* the progress callable (borrowed), or NULL */
    int progress_off;       /* it raised: no more calls */
} vbpy_call;

/* Opens the context. 0, or -1 with MemoryError set. */
int vbpy_call_open(vbpy_call *c);

/* Installs the callable `fn` (None: nothing) as the call's progress
 * callback (vb_set_progress): fn(stage, done, total) from whichever thread
 * reports, with the GIL taken. An exception it raises is printed as
 * unraisable (sys.unraisablehook) and ends the calls; the run goes on.
 * fn must have passed vbpy_progress_check and outlive the call (an
 * argument of the Python call does). */
void vbpy_call_progress(vbpy_call *c, PyObject *fn);

/* 0 when fn is None or callable, else -1 with TypeError set. */
int vbpy_progress_check(PyObject *fn);

/* The diagnostics captured so far as a list of (kind, number, file, line,
 * message) tuples (new reference; NULL with an exception set) and the
 * context closed: every call ends in exactly one
 * of vbpy_call_done and vbpy_call_fail. */
PyObject *vbpy_call_done(vbpy_call *c);

/* Raises VorballError for status rc with the context's message and the
 * diagnostics captured, closes the context and returns NULL. */
PyObject *vbpy_call_fail(vbpy_call *c, int rc);

/* Raises VorballError for a misuse found by the binding itself (E7 or the
 * number of `status`), formatted as printf. Returns NULL. */
PyObject *vbpy_raise(int status, const char *fmt, ...);

/* vbpy_raise for a value of spheres given as arrays: the error carries
 * the row (VorballError.row) beside the message that names it. */
PyObject *vbpy_raise_row(int status, Py_ssize_t row, const char *fmt, ...);

/* (value, diagnostics) as a 2-tuple, stealing value; closes the call.
 * NULL (value released) on failure. */
PyObject *vbpy_call_return(vbpy_call *c, PyObject *value);

/* A bytes object holding a copy of n items of size bytes each at p. */
PyObject *vbpy_bytes(const void *p, size_t n, size_t size);

/* The text a writer leaves in a memory stream: open, write through f,
 * then vbpy_text_take. */
typedef struct vbpy_text {
    FILE *f;
    char *buf;
    size_t len;
} vbpy_text;

int vbpy_text_open(vbpy_text *t);          /* 0, or -1 with MemoryError set */
PyObject *vbpy_text_take(vbpy_text *t);    /* a str (new), the stream freed */

/* Arc closure's counts as a dict (vertices, half_arcs, closed, infinite,
 * loops, undecided, components, added, complete). NULL with an exception. */
PyObject *vbpy_arcs_dict(const vb_arc_report *a);

/* Capsules: sphere sets ("vorball.spheres"). */
PyObject *vbpy_spheres_capsule(vb_sphere_set *set);
vb_sphere_set *vbpy_spheres_get(PyObject *capsule); /* NULL with TypeError set */

/* The set validated again in the call's context, as the command validates
 * its input with the call's counters and warnings (W701): *run is a
 * shallow copy of set with its own contained flags (free run->contained
 * afterwards), so a set shared between threads is never written.
 * VB_EMISUSE for a set without decimals. No Python calls: safe without
 * the GIL. */
int vbpy_validate(vb_ctx *ctx, const vb_sphere_set *set, size_t min_count, vb_sphere_set *run);

/* Parses "auto|gpu|cpu|ref" (the library's words) or raises E7. */
int vbpy_device_kind(const char *name, int *kind);

/* A vertex list from arrays: ids (uint32 buffer), start (int64 buffer of
 * n + 1 offsets), x y z t (float64 buffers of n), every vertex of
 * `status`. 0, or -1 with an exception set (out then empty). */
int vbpy_vertex_list(PyObject *ids, PyObject *start, PyObject *x, PyObject *y, PyObject *z,
                     PyObject *t, int status, vb_vertex_list *out);

/* Fills cfg for the vertex pipeline from device ("auto|gpu|cpu|ref") and
 * proposer (None or a name). 0, or -1 with an exception set (E7). */
int vbpy_vertices_config(const char *device, PyObject *proposer, vb_vertices_config *cfg);
/* The engine of an Engine's capsule (python/src/vertices.c), *out NULL for
 * None: 0, or -1 with an exception for anything else. */
int vbpy_engine_get(PyObject *o, vb_vertices_engine **out);

/* The periodic box of a call: tokens (None, or a sequence of 3, 6 or 9 str,
 * as `--box` takes them: vb_box_parse_args) or else the set's own box
 * (GRO box line, PDB CRYST1). VB_OK, or VB_EINPUT_BOX (E120) reported in
 * ctx; -1 with a Python exception set when tokens is not a sequence of
 * str. Call with the GIL. */
int vbpy_box(vb_ctx *ctx, PyObject *tokens, const vb_sphere_set *set, vb_box *box);

/* The results of a run over frames: (frame, model, dict) tuples in a list,
 * appended by the run's per-frame callback. */
typedef struct vbpy_frames {
    vb_ctx *ctx;
    PyObject *list;
    int failed; /* a Python exception is set */
} vbpy_frames;

/* The start of a call over frames: S's list made on c's context, the box
 * of tokens parsed (None: none), ro the command's defaults (format by
 * content, every model) with water. VB_OK, or the box's status (the run
 * is skipped and vbpy_frames_return reports it); -1 with a Python
 * exception set and the call closed. */
int vbpy_frames_open(vbpy_call *c, vbpy_frames *S, PyObject *tokens, int water, vb_box *box,
                     vb_read_options *ro);

/* Appends (frame, model, d), d stolen (NULL: its exception is set). Call
 * with the GIL. VB_OK, or VB_ENOMEM with failed set (the run stops). */
int vbpy_frames_append(vbpy_frames *S, long frame, int model, PyObject *d);

/* The end of a call over frames with status rc: (list, diagnostics), or
 * the Python exception, or VorballError; the list and the call released. */
PyObject *vbpy_frames_return(vbpy_call *c, vbpy_frames *S, int rc);

/* The functions of each file, for the module table. */
extern PyMethodDef vbpy_spheres_methods[];
extern PyMethodDef vbpy_vertices_methods[];
extern PyMethodDef vbpy_verify_methods[];
extern PyMethodDef vbpy_channels_methods[];
extern PyMethodDef vbpy_cells_methods[];
extern PyMethodDef vbpy_periodic_methods[];
extern PyMethodDef vbpy_jfa_methods[];

#endif
