/* The context: error state, diagnostics and counters. */
#include "vb.h"
#include "vb_diag.h"

#include <stdarg.h>
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
};

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
    c->state = VB_CTX_LIVE;
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
    free(ctx);
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
    case VB_EINPUT_BOX: return "periodic box absent, malformed or flat";
    case VB_EINPUT_BOX_SMALL: return "periodic box too small for its atoms";
    case VB_EINPUT_REFERENCE_SIZE: return "too many spheres for the exact reference";
    case VB_EINPUT_SCALE: return "radii too small for the sampling pipeline";
    case VB_EINPUT_TOL: return "tolerance finer than the sampling pipeline resolves";
    case VB_ENOMEM_ESTIMATE: return "not enough memory for the input";
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

/* A record to the log callback, its message formatted from fmt. */
static void log_record(const vb_ctx *ctx, char kind, int num, const char *file, long line,
                       const char *fmt, va_list ap)
{
    char msg[2048];
    vsnprintf(msg, sizeof msg, fmt, ap);
    vb_diag_record rec = {kind, num, file, file ? line : 0, msg};
    ctx->log(ctx->log_arg, &rec);
}

int vb_warn(vb_ctx *ctx, int num, const char *file, long line, const char *fmt, ...)
{
    if (vb_ctx_check(ctx) != VB_OK)
        return VB_EMISUSE;
    ctx->stats.warnings++;
    if (ctx->cfg.verbosity < 1)
        return VB_OK;
    va_list ap;
    if (ctx->log) {
        va_start(ap, fmt);
        log_record(ctx, 'W', num, file, line > 0 ? line : 0, fmt, ap);
        va_end(ap);
        return VB_OK;
    }
    FILE *f = diag_stream(ctx);
    if (file && line > 0)
        fprintf(f, "vorball: W%d: %s:%ld: ", num, file, line);
    else if (file)
        fprintf(f, "vorball: W%d: %s: ", num, file);
    else
        fprintf(f, "vorball: W%d: ", num);
    va_start(ap, fmt);
    vfprintf(f, fmt, ap);
    va_end(ap);
    fputc('\n', f);
    return VB_OK;
}

void vb_info(vb_ctx *ctx, const char *fmt, ...)
{
    if (vb_ctx_check(ctx) != VB_OK || ctx->cfg.verbosity < 2)
        return;
    va_list ap;
    if (ctx->log) {
        va_start(ap, fmt);
        log_record(ctx, 'I', 0, NULL, 0, fmt, ap);
        va_end(ap);
        return;
    }
    FILE *f = diag_stream(ctx);
    fputs("vorball: ", f);
    va_start(ap, fmt);
    vfprintf(f, fmt, ap);
    va_end(ap);
    fputc('\n', f);
}
