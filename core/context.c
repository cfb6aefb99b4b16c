/* The context: error state, diagnostics and counters. */
#include "vb.h"
#include "vb_diag.h"
#include "vb_parallel.h"

#include <pthread.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

/* The exit status of an internal error (E6), for codes the catalogue lacks. */
#define VB_EXIT_CODE_INTERNAL 6

/* The misuse guard: a context that is open carries VB_CTX_LIVE; vb_close
 * overwrites it before freeing, so a call on a closed context meets
 * VB_CTX_DEAD while the memory has not been reused (SQLite's magic). Every
 * call checks it; NULL and dead contexts are VB_EMISUSE, never a crash. */
#define VB_CTX_LIVE 0xa7u
#define VB_CTX_DEAD 0x5du

/* Stages whose progress is tracked at once (more rotate through). */
#define VB_PROGRESS_STAGES 4

struct vb_ctx {
    unsigned char state;
    vb_config cfg;
    int errcode;
    char errmsg[1024];
    size_t errmsg_at;       /* where the message starts after "file:line: " */
    char errfile[256];      /* the file vb_error was given ("" none) */
    long errline;
    vb_log_fn log;          /* NULL: text to the diagnostic stream */
    void *log_arg;
    vb_stats stats;
    /* Progress (vb_progress): the callback, or the context a worker
     * forwards to; per stage (stages may run at once: the cover and the
     * certification of its parts) the done last reported and the done
     * below which a report is not worth a call. */
    vb_progress_fn progress;
    void *progress_user;
    vb_ctx *progress_to;    /* the owner a worker reports through (vb_progress_forward) */
    pthread_mutex_t progress_lock;
    struct {
        _Atomic(const char *) stage;
        _Atomic uint64_t gate;
        uint64_t done;
    } ps[VB_PROGRESS_STAGES];
    unsigned ps_next;       /* the slot a new stage takes (round robin) */
};

/* Contexts open now: the last to close joins the resident thread pool. */
static atomic_long open_contexts;

int vb_open(vb_ctx **out, const vb_config *cfg)
{
    *out = NULL;
    vb_ctx *c = calloc(1, sizeof *c);
    if (!c)
        return VB_ENOMEM;
    if (cfg)
        c->cfg = *cfg;
    else
        c->cfg.verbosity = 1;
    pthread_mutex_init(&c->progress_lock, NULL);
    c->state = VB_CTX_LIVE;
    atomic_fetch_add(&open_contexts, 1);
    *out = c;
    return VB_OK;
}

int vb_ctx_check(const vb_ctx *ctx)
{
    return ctx && ctx->state == VB_CTX_LIVE ? VB_OK : VB_EMISUSE;
}

void vb_close(vb_ctx *ctx)
{
    if (vb_ctx_check(ctx) != VB_OK)
        return;
    ctx->state = VB_CTX_DEAD;
    pthread_mutex_destroy(&ctx->progress_lock);
    free(ctx);
    if (atomic_fetch_sub(&open_contexts, 1) == 1)
        vb_parallel_shutdown();
}

const char *vb_errmsg(const vb_ctx *ctx)
{
    return vb_ctx_check(ctx) == VB_OK ? ctx->errmsg : "no context (NULL or closed)";
}

int vb_errcode(const vb_ctx *ctx)
{
    return vb_ctx_check(ctx) == VB_OK ? ctx->errcode : VB_EMISUSE;
}

void vb_clear_error(vb_ctx *ctx)
{
    if (vb_ctx_check(ctx) != VB_OK)
        return;
    ctx->errcode = VB_OK;
    ctx->errmsg[0] = '\0';
    ctx->errmsg_at = 0;
    ctx->errfile[0] = '\0';
    ctx->errline = 0;
}

int vb_error_record(const vb_ctx *ctx, vb_diag_record *out)
{
    if (vb_ctx_check(ctx) != VB_OK)
        return VB_EMISUSE;
    out->kind = 'E';
    out->number = ctx->errcode == VB_OK ? 0 : vb_diag_number(ctx->errcode);
    out->file = ctx->errfile[0] ? ctx->errfile : NULL;
    out->line = ctx->errline;
    out->message = ctx->errmsg + ctx->errmsg_at;
    return VB_OK;
}

int vb_set_verbosity(vb_ctx *ctx, int verbosity)
{
    if (vb_ctx_check(ctx) != VB_OK)
        return -1;
    int old = ctx->cfg.verbosity;
    ctx->cfg.verbosity = verbosity;
    return old;
}

int vb_set_log(vb_ctx *ctx, vb_log_fn fn, void *arg)
{
    if (vb_ctx_check(ctx) != VB_OK)
        return VB_EMISUSE;
    ctx->log = fn;
    ctx->log_arg = fn ? arg : NULL;
    return VB_OK;
}

int vb_set_progress(vb_ctx *ctx, vb_progress_fn fn, void *user)
{
    if (vb_ctx_check(ctx) != VB_OK)
        return VB_EMISUSE;
    pthread_mutex_lock(&ctx->progress_lock);
    ctx->progress = fn;
    ctx->progress_user = fn ? user : NULL;
    for (int k = 0; k < VB_PROGRESS_STAGES; k++) {
        atomic_store(&ctx->ps[k].stage, NULL);
        atomic_store(&ctx->ps[k].gate, 0);
        ctx->ps[k].done = 0;
    }
    pthread_mutex_unlock(&ctx->progress_lock);
    return VB_OK;
}

void vb_progress_forward(vb_ctx *worker, vb_ctx *owner)
{
    if (vb_ctx_check(worker) == VB_OK && vb_ctx_check(owner) == VB_OK && worker != owner)
        worker->progress_to = owner;
}

int vb_open_worker(vb_ctx **out, vb_ctx *owner)
{
    *out = NULL;
    if (vb_ctx_check(owner) != VB_OK)
        return VB_EMISUSE;
    int rc = vb_open(out, &owner->cfg);
    if (rc == VB_OK)
        (*out)->progress_to = owner;
    return rc;
}

/* The context whose log callback, stream and verbosity speak for ctx: the
 * last owner up its chain of workers (vb_progress_forward). */
static vb_ctx *speaker(vb_ctx *ctx)
{
    for (int hops = 0; ctx->progress_to && hops < 8; hops++)
        ctx = ctx->progress_to;
    return ctx;
}

static int progress_slot(vb_ctx *ctx, const char *stage)
{
    for (int k = 0; k < VB_PROGRESS_STAGES; k++)
    {
        const char *s = atomic_load(&ctx->ps[k].stage);
        if (s == stage || (s && strcmp(s, stage) == 0))
            return k;
    }
    return -1;
}

void vb_progress(vb_ctx *ctx, const char *stage, uint64_t done, uint64_t total)
{
    if (vb_ctx_check(ctx) != VB_OK || !stage)
        return;
    ctx = speaker(ctx);
    if (!ctx->progress)
        return;
    /* The fast path, without the lock: a known stage below its next 1/1000. */
    int last = total > 0 && done >= total;
    int k = progress_slot(ctx, stage);
    if (k >= 0 && !last && done > 0 && done < atomic_load(&ctx->ps[k].gate))
        return;
    pthread_mutex_lock(&ctx->progress_lock);
    k = progress_slot(ctx, stage);
    int fresh = k < 0;
    if (fresh) {
        k = (int)(ctx->ps_next++ % VB_PROGRESS_STAGES);
        atomic_store(&ctx->ps[k].stage, stage);
    }
    if (ctx->progress && (fresh || done == 0 || done > ctx->ps[k].done)) {
        uint64_t step = total >= 1000 ? total / 1000 : 1;
        ctx->ps[k].done = done;
        atomic_store(&ctx->ps[k].gate, done + step);
        ctx->progress(ctx->progress_user, stage, done, total);
    }
    pthread_mutex_unlock(&ctx->progress_lock);
}

vb_stats *vb_ctx_stats(vb_ctx *ctx)
{
    return vb_ctx_check(ctx) == VB_OK ? &ctx->stats : NULL;
}

void vb_stats_add(vb_stats *to, const vb_stats *from)
{
    if (!to || !from)
        return;
    to->filter_calls += from->filter_calls;
    to->filter_failures += from->filter_failures;
    to->exact_evals += from->exact_evals;
    to->candidates += from->candidates;
    to->certified += from->certified;
    to->rejected += from->rejected;
    to->warnings += from->warnings;
    to->judged_vertex += from->judged_vertex;
    to->judged_not += from->judged_not;
    to->judged_open += from->judged_open;
}

int vb_diag_number(int code)
{
    if ((VB_CATEGORY(code) == VB_EINPUT || VB_CATEGORY(code) == VB_ENOMEM) &&
        VB_DETAIL(code) > 0)
        return 100 + VB_DETAIL(code);
    return VB_CATEGORY(code);
}

int vb_diag_exit(int status)
{
    if (status == VB_OK)
        return 0;
    int number = vb_diag_number(status);
#define VB_DIAG_EXIT(kind, num, name, exit, meaning)                                              \
    if (#kind[0] == 'E' && num == number)                                                       \
        return exit;
    VB_DIAG_LIST(VB_DIAG_EXIT)
#undef VB_DIAG_EXIT
    return VB_EXIT_CODE_INTERNAL;
}

const char *vb_errstr(int code)
{
    switch (code) {
    case VB_OK: return "ok";
    case VB_EINPUT_MALFORMED: return "malformed input line";
    case VB_EINPUT_NONFINITE: return "NaN or infinite value";
    case VB_EINPUT_RADIUS: return "radius not positive";
    case VB_EINPUT_DUPLICATE: return "duplicate sphere";
    case VB_EINPUT_EMPTY: return "empty input";
    case VB_EINPUT_TOOFEW: return "too few spheres";
    case VB_EINPUT_MAGNITUDE: return "value of absurd magnitude or precision";
    case VB_EINPUT_ELEMENT: return "unknown element";
    case VB_EINPUT_FORMAT: return "input format not recognised";
    case VB_EINPUT_TOOLARGE: return "input too large";
    case VB_EINPUT_MODEL: return "model not present";
    case VB_EINPUT_INFERRED: return "element not in the file";
    case VB_EINPUT_COMPRESSED: return "damaged compressed data";
    case VB_EINPUT_NOSPHERES: return "no spheres: trajectory or topology alone";
    case VB_EINPUT_TRAJECTORY: return "damaged trajectory";
    case VB_EINPUT_TOPOLOGY: return "trajectory and topology disagree";
    case VB_EINPUT_ASSEMBLY: return "assembly absent or malformed";
    case VB_EINPUT_SELECT: return "selection malformed or empty";
    case VB_EINPUT_BOX: return "periodic box absent, malformed or flat";
    case VB_EINPUT_FRAMES_MEMORY: return "frames in flight over their memory budget";
    case VB_EINPUT_BOX_SMALL: return "periodic box too small for its atoms";
    case VB_EINPUT_REFERENCE_SIZE: return "too many spheres for the exact reference";
    case VB_EINPUT_SCALE: return "radii too small for the sampling pipeline";
    case VB_EINPUT_TOL: return "tolerance finer than the sampling pipeline resolves";
    case VB_EINPUT_PAGE_SIZE: return "too many spheres for a results page of vertices";
    case VB_ENOMEM_ESTIMATE: return "not enough memory for the input";
    case VB_ENOMEM_DEVICE: return "device memory budget too small for the input";
    default: break;
    }
    switch (VB_CATEGORY(code)) {
    case VB_EINPUT: return "bad input";
    case VB_EDEGENERATE: return "degenerate input";
    case VB_EPREC: return "precision limit";
    case VB_ENOMEM: return "out of memory";
    case VB_EDEVICE: return "device failure";
    case VB_EINTERNAL: return "internal error";
    case VB_EMISUSE: return "misuse";
    case VB_EIO: return "i/o error";
    case VB_EMISMATCH: return "mismatch";
    default: return "unknown status";
    }
}

int vb_error(vb_ctx *ctx, int code, const char *file, long line, const char *fmt, ...)
{
    if (vb_ctx_check(ctx) != VB_OK)
        return code;
    ctx->errcode = code;
    size_t off = 0;
    int k;
    if (file && line > 0)
        k = snprintf(ctx->errmsg, sizeof ctx->errmsg, "%s:%ld: ", file, line);
    else if (file)
        k = snprintf(ctx->errmsg, sizeof ctx->errmsg, "%s: ", file);
    else
        k = 0;
    if (k > 0)
        off = (size_t)k < sizeof ctx->errmsg ? (size_t)k : sizeof ctx->errmsg - 1;
    ctx->errmsg_at = off;
    snprintf(ctx->errfile, sizeof ctx->errfile, "%s", file ? file : "");
    ctx->errline = file && line > 0 ? line : 0;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(ctx->errmsg + off, sizeof ctx->errmsg - off, fmt, ap);
    va_end(ap);
    return code;
}

static FILE *diag_stream(const vb_ctx *ctx)
{
    return ctx->cfg.diag ? ctx->cfg.diag : stderr;
}

/* A record, its message formatted from fmt, to the log callback or, without
 * one, as text to the diagnostic stream. */
static void log_record(const vb_ctx *ctx, char kind, int num, const char *file, long line,
                       const char *fmt, va_list ap)
{
    char msg[2048];
    vsnprintf(msg, sizeof msg, fmt, ap);
    vb_diag_record rec = {kind, num, file, file ? line : 0, msg};
    if (ctx->log)
        ctx->log(ctx->log_arg, &rec);
    else
        vb_diag_record_write(diag_stream(ctx), &rec);
}

void vb_diag_record_write(FILE *f, const vb_diag_record *rec)
{
    if (rec->kind == 'I')
        fputs("vorball: ", f);
    else if (rec->file && rec->line > 0)
        fprintf(f, "vorball: %c%d: %s:%ld: ", rec->kind, rec->number, rec->file, rec->line);
    else if (rec->file)
        fprintf(f, "vorball: %c%d: %s: ", rec->kind, rec->number, rec->file);
    else
        fprintf(f, "vorball: %c%d: ", rec->kind, rec->number);
    fputs(rec->message, f);
    fputc('\n', f);
}

int vb_warn(vb_ctx *ctx, int num, const char *file, long line, const char *fmt, ...)
{
    if (vb_ctx_check(ctx) != VB_OK)
        return VB_EMISUSE;
    ctx->stats.warnings++;
    const vb_ctx *to = speaker(ctx);
    if (to->cfg.verbosity < 1)
        return VB_OK;
    va_list ap;
    va_start(ap, fmt);
    log_record(to, 'W', num, file, line > 0 ? line : 0, fmt, ap);
    va_end(ap);
    return VB_OK;
}

void vb_info(vb_ctx *ctx, const char *fmt, ...)
{
    if (vb_ctx_check(ctx) != VB_OK)
        return;
    const vb_ctx *to = speaker(ctx);
    if (to->cfg.verbosity < 2)
        return;
    va_list ap;
    va_start(ap, fmt);
    log_record(to, 'I', 0, NULL, 0, fmt, ap);
    va_end(ap);
}
