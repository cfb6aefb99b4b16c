/* Sphere sets for Python: read from files by the library's readers, built
 * from array columns through the XYZR reader (so that every number is the
 * exact decimal the CLI would read), their arrays handed back, and the
 * frames of trajectories. */
#include "vbpy.h"

#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "vb_frames.h"
#include "vb_select.h"

#define SPHERES_CAPSULE "vorball.spheres"
#define FRAMES_CAPSULE "vorball.frames"

static void spheres_destroy(PyObject *cap)
{
    vb_spheres_free(PyCapsule_GetPointer(cap, SPHERES_CAPSULE));
}

PyObject *vbpy_spheres_capsule(vb_sphere_set *set)
{
    PyObject *cap = PyCapsule_New(set, SPHERES_CAPSULE, spheres_destroy);
    if (!cap)
        vb_spheres_free(set);
    return cap;
}

vb_sphere_set *vbpy_spheres_get(PyObject *capsule)
{
    return PyCapsule_GetPointer(capsule, SPHERES_CAPSULE);
}

/* The read options of the Python keywords, as the CLI's input options
 * fill them (cli/input_options.c): format by name, model, assembly, water,
 * hydrogens, strict elements, zero radius. VB_OK or VB_EMISUSE in ctx. */
static int read_options(vb_ctx *ctx, const char *format, Py_ssize_t model, Py_ssize_t assembly,
                        int keep_water, int drop_hydrogens, int strict_elements, int zero_radius,
                        vb_read_options *ro)
{
    memset(ro, 0, sizeof *ro);
    /* The ranges are the library's (vb_read_options_check): a number out
     * of the field's type is stored as one it refuses. */
    ro->model = model >= 0 && model <= INT_MAX ? (int)model : -1;
    ro->assembly = assembly >= 0 && assembly <= INT_MAX ? (int)assembly : -1;
    ro->keep_water = keep_water;
    ro->drop_hydrogens = drop_hydrogens;
    ro->strict_elements = strict_elements;
    ro->zero_radius = zero_radius;
    int rc = vb_read_options_check(ctx, ro);
    return rc == VB_OK ? vb_format_parse(ctx, format, &ro->format) : rc;
}

/* A converter ("O&") of the model or assembly number: any Python int, one out of the
 * C field's type stored as -1 (refused by vb_read_options_check). */
static int model_arg(PyObject *o, void *out)
{
    int overflow = 0;
    long long v = PyLong_AsLongLongAndOverflow(o, &overflow);
    if (v == -1 && PyErr_Occurred())
        return 0;
    *(Py_ssize_t *)out = overflow || v < 0 || v > INT_MAX ? -1 : (Py_ssize_t)v;
    return 1;
}

static PyObject *spheres_read(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *path = NULL, *radii = NULL;
    const char *format;
    int water, noh, strict, zero;
    Py_ssize_t model, assembly, min_count;
    if (!PyArg_ParseTuple(args, "O&sO&O&iiiiO&n", PyUnicode_FSConverter, &path, &format, model_arg,
                          &model, model_arg, &assembly, &water, &noh, &strict, &zero,
                          PyUnicode_FSConverter, &radii, &min_count))
        return NULL;
    vbpy_call c;
    if (vbpy_call_open(&c) != 0) {
        Py_DECREF(path);
        Py_DECREF(radii);
        return NULL;
    }
    vb_read_options ro;
    vb_sphere_set *set = NULL;
    const char *rp = PyBytes_AS_STRING(radii);
    int rc = read_options(c.ctx, format, model, assembly, water, noh, strict, zero, &ro);
    if (rc == VB_OK) {
        const char *p = PyBytes_AS_STRING(path);
        Py_BEGIN_ALLOW_THREADS
        rc = vb_spheres_load(c.ctx, p, &ro, *rp ? rp : NULL, (size_t)min_count, &set);
        Py_END_ALLOW_THREADS
    }
    Py_DECREF(path);
    Py_DECREF(radii);
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    return vbpy_call_return(&c, vbpy_spheres_capsule(set));
}

/* ---- sets from columns --------------------------------------------------- */

typedef struct {
    char *p;
    size_t n, cap;
} growbuf;

static int grow_put(growbuf *g, const char *s, size_t len, char end)
{
    if (g->n + len + 2 > g->cap) {
        size_t cap = g->cap ? 2 * g->cap : 1 << 16;
        while (cap < g->n + len + 2)
            cap *= 2;
        char *p = realloc(g->p, cap);
        if (!p)
            return -1;
        g->p = p;
        g->cap = cap;
    }
    memcpy(g->p + g->n, s, len);
    g->n += len;
    g->p[g->n++] = end;
    return 0;
}

/* The p-significant-digit decimal next to the one in s (a "%.*e" text of p
 * digits) on the side of v, in "<mantissa>e<exponent>" form. */
static void decimal_neighbour(const char *s, int p, int up, char *out, size_t size)
{
    long long m = 0;
    int neg = *s == '-';
    const char *q = s + neg;
    for (; *q && *q != 'e'; q++)
        if (*q >= '0' && *q <= '9')
            m = m * 10 + (*q - '0');
    int e = *q == 'e' ? atoi(q + 1) : 0;
    /* |value| = m * 10^(e - p + 1); moving the value up means a larger
     * magnitude for a positive number, a smaller one for a negative. */
    m += (up != neg) ? 1 : -1;
    snprintf(out, size, "%s%llde%d", neg ? "-" : "", m, e - p + 1);
}

/* The shortest decimal that reads back (strtof, correctly rounded) as the
 * float v, the closest to v among those of that length: numpy's repr of
 * np.float32. For p digits the candidates are the correctly rounded
 * p-digit decimal c ("%.*e") and, when c does not read back, its
 * neighbour on the other side of v: any p-digit decimal that reads back
 * lies in v's rounding interval, which is an interval around v, so if one
 * lies beyond the neighbour the neighbour does too. 9 digits always read
 * back. */
static void float32_shortest(float v, char *out, size_t size)
{
    if (isnan(v)) {
        snprintf(out, size, "nan");
        return;
    }
    if (isinf(v)) {
        snprintf(out, size, "%sinf", v < 0 ? "-" : "");
        return;
    }
    if (v == 0.0f) {
        snprintf(out, size, "%s0", signbit(v) ? "-" : "");
        return;
    }
    for (int p = 1; p <= 9; p++) {
        snprintf(out, size, "%.*e", p - 1, (double)v);
        if (strtof(out, NULL) == v)
            return;
        char nb[48];
        decimal_neighbour(out, p, strtod(out, NULL) < (double)v, nb, sizeof nb);
        if (strtof(nb, NULL) == v) {
            snprintf(out, size, "%s", nb);
            return;
        }
    }
    snprintf(out, size, "%.8e", (double)v);
}

/* One column: a contiguous buffer of float64 ('d'), float32 ('f') or
 * int64 ('q'), or a sequence of str ('s', decimals verbatim). */
typedef struct {
    char kind;
    Py_buffer buf;
    int has_buf;
    PyObject *seq;
    Py_ssize_t n;
} column;

static void column_release(column *c)
{
    if (c->has_buf)
        PyBuffer_Release(&c->buf);
    Py_XDECREF(c->seq);
    memset(c, 0, sizeof *c);
}

static int column_get(PyObject *spec, column *c)
{
    memset(c, 0, sizeof *c);
    const char *kind;
    PyObject *obj;
    if (!PyArg_ParseTuple(spec, "sO", &kind, &obj))
        return -1;
    c->kind = kind[0];
    if (c->kind == 's') {
        if (!(c->seq = PySequence_Fast(obj, "a column of decimals must be a sequence of str")))
            return -1;
        c->n = PySequence_Fast_GET_SIZE(c->seq);
        return 0;
    }
    Py_ssize_t size = c->kind == 'f' ? 4 : 8;
    if (!strchr("dfq", c->kind) || kind[1]) {
        PyErr_Format(PyExc_ValueError, "unknown column kind '%s'", kind);
        return -1;
    }
    if (PyObject_GetBuffer(obj, &c->buf, PyBUF_C_CONTIGUOUS) != 0)
        return -1;
    c->has_buf = 1;
    if (c->buf.len % size) {
        PyErr_SetString(PyExc_ValueError, "column buffer of the wrong item size");
        return -1;
    }
    c->n = c->buf.len / size;
    return 0;
}

/* The decimal text of row i of column c into out (size >= 64), or -1
 * with a Python exception set. */
static int column_token(const column *c, Py_ssize_t i, char *out, size_t size, int col,
                        const char *name)
{
    if (c->kind == 'd') {
        double v;
        memcpy(&v, (const char *)c->buf.buf + 8 * i, 8);
        char *s = PyOS_double_to_string(v, 'r', 0, 0, NULL);
        if (!s)
            return -1;
        snprintf(out, size, "%s", s);
        PyMem_Free(s);
    } else if (c->kind == 'f') {
        float v;
        memcpy(&v, (const char *)c->buf.buf + 4 * i, 4);
        float32_shortest(v, out, size);
    } else if (c->kind == 'q') {
        long long v;
        memcpy(&v, (const char *)c->buf.buf + 8 * i, 8);
        snprintf(out, size, "%lld", v);
    } else {
        PyObject *o = PySequence_Fast_GET_ITEM(c->seq, i);
        Py_ssize_t len;
        const char *s = PyUnicode_Check(o) ? PyUnicode_AsUTF8AndSize(o, &len) : NULL;
        if (!s) {
            PyErr_Clear();
            vbpy_raise_row(VB_EINPUT_MALFORMED, i, "%s row %zd, column %d: not a str", name, i,
                           col);
            return -1;
        }
        int bad = len == 0 || (size_t)len >= size;
        for (Py_ssize_t k = 0; k < len && !bad; k++)
            bad = (unsigned char)s[k] <= ' ' || s[k] == '#' || (unsigned char)s[k] >= 127;
        if (bad) {
            vbpy_raise_row(VB_EINPUT_MALFORMED, i,
                           "%s row %zd, column %d: '%.40s' is not a decimal", name, i, col, s);
            return -1;
        }
        memcpy(out, s, (size_t)len);
        out[len] = '\0';
    }
    return 0;
}

static PyObject *spheres_from_columns(PyObject *self, PyObject *args)
{
    (void)self;
    const char *name;
    PyObject *specs;
    Py_ssize_t min_count;
    int zero;
    if (!PyArg_ParseTuple(args, "sO!ni", &name, &PyTuple_Type, &specs, &min_count, &zero))
        return NULL;
    if (PyTuple_GET_SIZE(specs) != 4) {
        PyErr_SetString(PyExc_ValueError, "four columns: x, y, z, r");
        return NULL;
    }
    column col[4];
    memset(col, 0, sizeof col);
    growbuf g = {NULL, 0, 0};
    PyObject *ret = NULL;
    int ok = 1;
    for (int k = 0; k < 4 && ok; k++)
        ok = column_get(PyTuple_GET_ITEM(specs, k), &col[k]) == 0;
    for (int k = 1; k < 4 && ok; k++)
        if (col[k].n != col[0].n) {
            PyErr_SetString(PyExc_ValueError, "columns of different lengths");
            ok = 0;
        }
    char tok[128];
    for (Py_ssize_t i = 0; ok && i < col[0].n; i++)
        for (int k = 0; k < 4 && ok; k++) {
            ok = column_token(&col[k], i, tok, sizeof tok, k, name) == 0;
            if (ok && grow_put(&g, tok, strlen(tok), k == 3 ? '\n' : ' ') != 0) {
                PyErr_NoMemory();
                ok = 0;
            }
        }
    for (int k = 0; k < 4; k++)
        column_release(&col[k]);
    vbpy_call c;
    if (ok && vbpy_call_open(&c) == 0) {
        vb_read_options ro;
        memset(&ro, 0, sizeof ro);
        ro.format = VB_FMT_XYZR;
        ro.zero_radius = zero;
        vb_sphere_set *set = NULL;
        int rc;
        Py_BEGIN_ALLOW_THREADS
        rc = vb_spheres_read_buffer(c.ctx, name, g.p ? g.p : "", g.n, &ro, &set);
        if (rc == VB_OK)
            rc = vb_spheres_validate(c.ctx, set, (size_t)min_count);
        Py_END_ALLOW_THREADS
        if (rc != VB_OK) {
            vb_spheres_free(set);
            ret = vbpy_call_fail(&c, rc);
        } else {
            ret = vbpy_call_return(&c, vbpy_spheres_capsule(set));
        }
    }
    free(g.p);
    return ret;
}

int vbpy_validate(vb_ctx *ctx, const vb_sphere_set *set, size_t min_count, vb_sphere_set *run)
{
    *run = *set;
    run->contained = NULL;
    if (!set->ex)
        return vb_error(ctx, VB_EMISUSE, set->source, 0,
                        "a set of doubles only (a binary trajectory's frame) has no exact "
                        "decimals to certify: build it from its arrays");
    return vb_spheres_validate(ctx, run, min_count);
}

/* ---- what a set holds ---------------------------------------------------- */

static PyObject *spheres_info(PyObject *self, PyObject *cap)
{
    (void)self;
    vb_sphere_set *s = vbpy_spheres_get(cap);
    if (!s)
        return NULL;
    /* Source lines as int64 whatever the width of long. */
    int64_t *line = malloc((s->n ? s->n : 1) * sizeof *line);
    if (!line)
        return PyErr_NoMemory();
    for (size_t i = 0; i < s->n; i++)
        line[i] = s->line ? (int64_t)s->line[i] : 0;
    PyObject *contained = s->contained ? vbpy_bytes(s->contained, s->n, 1) : Py_NewRef(Py_None);
    PyObject *d = Py_BuildValue("{s:n,s:s,s:N,s:N,s:N,s:N,s:N,s:N,s:O,s:O,s:O}", "n",
                                (Py_ssize_t)s->n, "source", s->source ? s->source : "",
                                "x", vbpy_bytes(s->x, s->n, 8), "y", vbpy_bytes(s->y, s->n, 8),
                                "z", vbpy_bytes(s->z, s->n, 8), "r", vbpy_bytes(s->r, s->n, 8),
                                "line", vbpy_bytes(line, s->n, 8), "contained", contained,
                                "exact", s->ex ? Py_True : Py_False, "atoms",
                                s->info ? Py_True : Py_False, "zero_radius_points",
                                s->allows_zero_radius ? Py_True : Py_False);
    free(line);
    return d;
}

/* The exact decimals: (mantissas, exponents) as bytes of int64 and int32,
 * four per sphere (x y z r), or None for a set built from doubles alone. */
static PyObject *spheres_decimals(PyObject *self, PyObject *cap)
{
    (void)self;
    vb_sphere_set *s = vbpy_spheres_get(cap);
    if (!s)
        return NULL;
    if (!s->ex)
        Py_RETURN_NONE;
    size_t n = s->n ? s->n : 1;
    int64_t *m = malloc(4 * n * sizeof *m);
    int32_t *e = malloc(4 * n * sizeof *e);
    if (!m || !e) {
        free(m);
        free(e);
        return PyErr_NoMemory();
    }
    const vb_decimal *col[4] = {s->ex, s->ey, s->ez, s->er};
    for (size_t i = 0; i < s->n; i++)
        for (int k = 0; k < 4; k++) {
            m[4 * i + k] = col[k][i].mant;
            e[4 * i + k] = col[k][i].exp10;
        }
    PyObject *t = Py_BuildValue("(NN)", vbpy_bytes(m, 4 * s->n, 8), vbpy_bytes(e, 4 * s->n, 4));
    free(m);
    free(e);
    return t;
}

/* The atom records as raw vb_atom_info bytes with their layout (itemsize
 * and the offset of every field), or None for a set without records. */
static PyObject *spheres_atoms(PyObject *self, PyObject *cap)
{
    (void)self;
    vb_sphere_set *s = vbpy_spheres_get(cap);
    if (!s)
        return NULL;
    if (!s->info)
        Py_RETURN_NONE;
    return Py_BuildValue(
        "(N n {s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n})", vbpy_bytes(s->info, s->n, sizeof *s->info),
        (Py_ssize_t)sizeof(vb_atom_info), "serial", (Py_ssize_t)offsetof(vb_atom_info, serial),
        "resseq", (Py_ssize_t)offsetof(vb_atom_info, resseq), "name",
        (Py_ssize_t)offsetof(vb_atom_info, name), "resname",
        (Py_ssize_t)offsetof(vb_atom_info, resname), "chain",
        (Py_ssize_t)offsetof(vb_atom_info, chain), "element",
        (Py_ssize_t)offsetof(vb_atom_info, element), "icode",
        (Py_ssize_t)offsetof(vb_atom_info, icode), "altloc",
        (Py_ssize_t)offsetof(vb_atom_info, altloc), "hetatm",
        (Py_ssize_t)offsetof(vb_atom_info, hetatm));
}

/* ---- frames -------------------------------------------------------------- */

typedef struct {
    vb_frame_source *src;
    vb_radii_table *radii;
} frames;

static void frames_destroy(PyObject *cap)
{
    frames *f = PyCapsule_GetPointer(cap, FRAMES_CAPSULE);
    if (!f)
        return;
    vb_frame_source_close(f->src);
    vb_radii_free(f->radii);
    free(f);
}

static PyObject *frames_open(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *path = NULL, *traj = NULL, *radii = NULL;
    const char *format;
    int water, noh, strict, zero;
    Py_ssize_t model, assembly;
    if (!PyArg_ParseTuple(args, "O&O&sO&O&iiiiO&", PyUnicode_FSConverter, &path,
                          PyUnicode_FSConverter, &traj, &format, model_arg, &model, model_arg,
                          &assembly, &water, &noh, &strict, &zero, PyUnicode_FSConverter, &radii))
        return NULL;
    frames *f = calloc(1, sizeof *f);
    vbpy_call c;
    if (!f || vbpy_call_open(&c) != 0) {
        free(f);
        Py_DECREF(path);
        Py_DECREF(traj);
        Py_DECREF(radii);
        return f ? NULL : PyErr_NoMemory();
    }
    vb_read_options ro;
    const char *rp = PyBytes_AS_STRING(radii), *tp = PyBytes_AS_STRING(traj);
    int rc = read_options(c.ctx, format, model, assembly, water, noh, strict, zero, &ro);
    if (rc == VB_OK) {
        const char *p = PyBytes_AS_STRING(path);
        Py_BEGIN_ALLOW_THREADS
        if (*rp)
            rc = vb_radii_load(c.ctx, rp, &f->radii);
        ro.radii = f->radii;
        if (rc == VB_OK)
            rc = vb_frame_source_open(c.ctx, p, *tp ? tp : NULL, &ro, &f->src);
        Py_END_ALLOW_THREADS
    }
    Py_DECREF(path);
    Py_DECREF(traj);
    Py_DECREF(radii);
    if (rc != VB_OK) {
        vb_radii_free(f->radii);
        free(f);
        return vbpy_call_fail(&c, rc);
    }
    PyObject *cap = PyCapsule_New(f, FRAMES_CAPSULE, frames_destroy);
    if (!cap) {
        vb_frame_source_close(f->src);
        vb_radii_free(f->radii);
        free(f);
    }
    return vbpy_call_return(&c, cap);
}

/* ((spheres, model) or None at the end, diagnostics). */
static PyObject *frames_next(PyObject *self, PyObject *cap)
{
    (void)self;
    frames *f = PyCapsule_GetPointer(cap, FRAMES_CAPSULE);
    if (!f)
        return NULL;
    if (!f->src)
        return vbpy_raise(VB_EMISUSE, "the frames are closed");
    vbpy_call c;
    if (vbpy_call_open(&c) != 0)
        return NULL;
    vb_sphere_set *s = NULL;
    int model = 0, rc;
    Py_BEGIN_ALLOW_THREADS
    rc = vb_frame_source_next(c.ctx, f->src, &s, &model);
    Py_END_ALLOW_THREADS
    if (rc != VB_OK)
        return vbpy_call_fail(&c, rc);
    if (!s)
        return vbpy_call_return(&c, Py_NewRef(Py_None));
    PyObject *sc = vbpy_spheres_capsule(s);
    return vbpy_call_return(&c, sc ? Py_BuildValue("(Ni)", sc, model) : NULL);
}

static PyObject *frames_close(PyObject *self, PyObject *cap)
{
    (void)self;
    frames *f = PyCapsule_GetPointer(cap, FRAMES_CAPSULE);
    if (!f)
        return NULL;
    vb_frame_source_close(f->src);
    f->src = NULL;
    Py_RETURN_NONE;
}

/* The sphere table of `--atoms FILE` (vb_atoms_write) as a str. */
static PyObject *spheres_atoms_text(PyObject *self, PyObject *cap)
{
    (void)self;
    vb_sphere_set *set = vbpy_spheres_get(cap);
    vbpy_call c;
    vbpy_text t;
    if (!set || vbpy_call_open(&c) != 0)
        return NULL;
    if (vbpy_text_open(&t) != 0) {
        Py_XDECREF(vbpy_call_done(&c));
        return NULL;
    }
    int rc = vb_atoms_write(c.ctx, t.f, set);
    PyObject *text = vbpy_text_take(&t);
    if (rc != VB_OK) {
        Py_XDECREF(text);
        return vbpy_call_fail(&c, rc);
    }
    return vbpy_call_return(&c, text);
}

/* The spheres of a set that an expression selects (vb_spheres_select),
 * validated as a read set is: (capsule, diagnostics); E118 raised. */
static PyObject *spheres_select(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *cap;
    const char *expr;
    if (!PyArg_ParseTuple(args, "Os", &cap, &expr))
        return NULL;
    vb_sphere_set *s = vbpy_spheres_get(cap);
    if (!s)
        return NULL;
    vbpy_call c;
    if (vbpy_call_open(&c) != 0)
        return NULL;
    vb_sphere_set *t = NULL;
    int rc;
    Py_BEGIN_ALLOW_THREADS
    rc = vb_spheres_select(c.ctx, s, expr, &t);
    if (rc == VB_OK)
        rc = vb_spheres_validate(c.ctx, t, 1);
    Py_END_ALLOW_THREADS
    if (rc != VB_OK) {
        vb_spheres_free(t);
        return vbpy_call_fail(&c, rc);
    }
    return vbpy_call_return(&c, vbpy_spheres_capsule(t));
}

PyMethodDef vbpy_spheres_methods[] = {
    {"spheres_select", spheres_select, METH_VARARGS,
     "spheres_select(capsule, expr) -> (capsule, diagnostics)"},
    {"spheres_read", spheres_read, METH_VARARGS,
     "spheres_read(path, format, model, assembly, water, no_hydrogens, strict, zero_radius, radii, "
     "min_count) -> (capsule, diagnostics)"},
    {"spheres_from_columns", spheres_from_columns, METH_VARARGS,
     "spheres_from_columns(name, ((kind, column) x 4), min_count, zero_radius) -> "
     "(capsule, diagnostics)"},
    {"spheres_info", spheres_info, METH_O, "The arrays of a set as bytes, in a dict."},
    {"spheres_decimals", spheres_decimals, METH_O, "(mantissas, exponents) or None."},
    {"spheres_atoms", spheres_atoms, METH_O, "(bytes, itemsize, offsets) or None."},
    {"spheres_atoms_text", spheres_atoms_text, METH_O,
     "(the sphere table of --atoms, diagnostics)"},
    {"frames_open", frames_open, METH_VARARGS,
     "frames_open(path, trajectory, format, model, assembly, water, no_hydrogens, strict, zero_radius, "
     "radii) -> (capsule, diagnostics)"},
    {"frames_next", frames_next, METH_O, "((spheres, model) or None, diagnostics)"},
    {"frames_close", frames_close, METH_O, "Closes the frame source."},
    {NULL, NULL, 0, NULL}};
