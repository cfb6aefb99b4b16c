/* Output files written under a temporary name and renamed when complete
 * (see vb_output.h). The open ones sit in a small table, which a signal
 * handler can walk: it only reads fixed arrays and calls unlink. */
/* realpath is XSI. */
#define _XOPEN_SOURCE 700
#include "vb_output.h"

#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Outputs open at once (channels writes five). */
#define VB_OUTPUT_MAX 32
#define VB_OUTPUT_PATH 4096

typedef struct out_entry {
    volatile sig_atomic_t live; /* tmp names a file to remove on a signal */
    FILE *f;                    /* NULL once closed */
    int ready;                  /* closed whole, waiting for vb_output_commit_deferred */
    int direct;                 /* written in place (not a regular file) */
    char final[VB_OUTPUT_PATH];
    char tmp[VB_OUTPUT_PATH];
} out_entry;

static out_entry outputs[VB_OUTPUT_MAX];
static pthread_mutex_t outputs_lock = PTHREAD_MUTEX_INITIALIZER;
static int handlers_installed;
static int defer_commits;

static void remove_live(void)
{
    for (int i = 0; i < VB_OUTPUT_MAX; i++)
        if (outputs[i].live)
            unlink(outputs[i].tmp);
}

static void on_signal(int sig)
{
    remove_live();
    signal(sig, SIG_DFL);
    raise(sig);
}

/* Under outputs_lock. Leaves handlers a program installed itself alone. */
static void install_handlers(void)
{
    if (handlers_installed)
        return;
    handlers_installed = 1;
    const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
    for (size_t k = 0; k < sizeof sigs / sizeof sigs[0]; k++) {
        struct sigaction old, sa;
        if (sigaction(sigs[k], NULL, &old) != 0 || old.sa_handler != SIG_DFL)
            continue;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_signal;
        sigemptyset(&sa.sa_mask);
        sigaction(sigs[k], &sa, NULL);
    }
}

static out_entry *find(FILE *f)
{
    for (int i = 0; i < VB_OUTPUT_MAX; i++)
        if (outputs[i].f == f && f)
            return &outputs[i];
    return NULL;
}

int vb_output_is_open(FILE *f)
{
    pthread_mutex_lock(&outputs_lock);
    int open = find(f) != NULL;
    pthread_mutex_unlock(&outputs_lock);
    return open;
}

/* The temporary name ".BASE.vorball-XXXXXX" in the folder of `final`. */
static int temp_name(const char *final, char *tmp, size_t cap)
{
    const char *slash = strrchr(final, '/');
    int dir_len = slash ? (int)(slash - final + 1) : 0;
    const char *base = slash ? slash + 1 : final;
    int n = snprintf(tmp, cap, "%.*s.%s.vorball-XXXXXX", dir_len, final, base);
    return n > 0 && (size_t)n < cap ? 0 : -1;
}

FILE *vb_output_open(vb_ctx *ctx, const char *path)
{
    pthread_mutex_lock(&outputs_lock);
    out_entry *e = NULL;
    for (int i = 0; !e && i < VB_OUTPUT_MAX; i++)
        if (!outputs[i].f && !outputs[i].ready)
            e = &outputs[i];
    if (!e) {
        pthread_mutex_unlock(&outputs_lock);
        vb_error(ctx, VB_EIO, path, 0, "too many output files open at once");
        return NULL;
    }
    install_handlers();
    memset(e, 0, sizeof *e);
    struct stat st, lst;
    int exists = stat(path, &st) == 0;
    const char *final = path;
    char resolved[PATH_MAX];
    /* A link is replaced at its target; a dangling one is written through. */
    if (exists && lstat(path, &lst) == 0 && S_ISLNK(lst.st_mode)) {
        if (realpath(path, resolved))
            final = resolved;
        else
            e->direct = 1;
    }
    if (exists && !S_ISREG(st.st_mode))
        e->direct = 1;
    if (!exists && lstat(path, &lst) == 0)
        e->direct = 1; /* a dangling link: as fopen would, create its target */
    int n = snprintf(e->final, sizeof e->final, "%s", final);
    FILE *f = NULL;
    if (n < 0 || (size_t)n >= sizeof e->final) {
        vb_error(ctx, VB_EIO, path, 0, "output path too long");
    } else if (e->direct) {
        if (!(f = fopen(path, "w")))
            vb_error(ctx, VB_EIO, path, 0, "cannot open for writing: %s", strerror(errno));
    } else if (temp_name(e->final, e->tmp, sizeof e->tmp) != 0) {
        vb_error(ctx, VB_EIO, path, 0, "output path too long");
    } else {
        int fd = mkstemp(e->tmp);
        if (fd < 0) {
            vb_error(ctx, VB_EIO, path, 0, "cannot open for writing: %s", strerror(errno));
        } else {
            /* The mode fopen would give: the old file's, else 0666 less the umask. */
            mode_t mask = umask(0);
            umask(mask);
            fchmod(fd, exists ? (st.st_mode & 07777) : (0666 & ~mask));
            e->live = 1;
            if (!(f = fdopen(fd, "w"))) {
                vb_error(ctx, VB_ENOMEM, path, 0, "out of memory");
                close(fd);
                unlink(e->tmp);
                e->live = 0;
            }
        }
    }
    e->f = f;
    pthread_mutex_unlock(&outputs_lock);
    return f;
}

/* Forgets entry e (under outputs_lock). */
static void forget(out_entry *e)
{
    e->live = 0;
    e->f = NULL;
    e->ready = 0;
}

void vb_output_defer(int on)
{
    pthread_mutex_lock(&outputs_lock);
    defer_commits = on;
    pthread_mutex_unlock(&outputs_lock);
}

int vb_output_commit_deferred(vb_ctx *ctx)
{
    int rc = VB_OK;
    pthread_mutex_lock(&outputs_lock);
    for (int i = 0; i < VB_OUTPUT_MAX; i++) {
        out_entry *e = &outputs[i];
        if (!e->ready)
            continue;
        if (rc == VB_OK && rename(e->tmp, e->final) != 0)
            rc = vb_error(ctx, VB_EIO, e->final, 0, "cannot replace the file: %s",
                          strerror(errno));
        else if (rc != VB_OK)
            unlink(e->tmp);
        forget(e);
    }
    pthread_mutex_unlock(&outputs_lock);
    return rc;
}

int vb_output_commit(vb_ctx *ctx, FILE *f)
{
    pthread_mutex_lock(&outputs_lock);
    out_entry *e = find(f);
    if (!e) {
        pthread_mutex_unlock(&outputs_lock);
        return vb_error(ctx, VB_EINTERNAL, NULL, 0, "vb_output_commit: not an open output");
    }
    int bad = ferror(f);
    int err = errno;
    if (fclose(f) != 0 && !bad) {
        bad = 1;
        err = errno;
    }
    int rc = VB_OK;
    if (bad) {
        rc = vb_error(ctx, VB_EIO, e->final, 0, "write failed%s%s", err ? ": " : "",
                      err ? strerror(err) : "");
        if (!e->direct)
            unlink(e->tmp);
    } else if (!e->direct && defer_commits) {
        e->f = NULL;
        e->ready = 1; /* renamed by vb_output_commit_deferred */
        pthread_mutex_unlock(&outputs_lock);
        return VB_OK;
    } else if (!e->direct && rename(e->tmp, e->final) != 0) {
        rc = vb_error(ctx, VB_EIO, e->final, 0, "cannot replace the file: %s", strerror(errno));
        unlink(e->tmp);
    }
    forget(e);
    pthread_mutex_unlock(&outputs_lock);
    return rc;
}

void vb_output_discard(FILE *f)
{
    if (!f)
        return;
    pthread_mutex_lock(&outputs_lock);
    out_entry *e = find(f);
    if (e) {
        fclose(f);
        if (!e->direct)
            unlink(e->tmp);
        forget(e);
    }
    pthread_mutex_unlock(&outputs_lock);
}

void vb_output_discard_all(void)
{
    pthread_mutex_lock(&outputs_lock);
    for (int i = 0; i < VB_OUTPUT_MAX; i++)
        if (outputs[i].f || outputs[i].ready) {
            if (outputs[i].f)
                fclose(outputs[i].f);
            if (!outputs[i].direct)
                unlink(outputs[i].tmp);
            forget(&outputs[i]);
        }
    pthread_mutex_unlock(&outputs_lock);
}
