/* Output files written under a temporary name and renamed when complete
 * (see vb_output.h). The open ones (and, with deferral, the closed ones
 * waiting for their rename: one per frame of `channels --volume v%d.mrc`)
 * sit in a table of fixed chunks, linked and never moved or freed, which a
 * signal handler can walk: it only follows the links and calls unlink. A
 * chunk is linked only once it is whole, so the handler never sees half of
 * one; there is no limit but memory. */
/* realpath is XSI. */
#define _XOPEN_SOURCE 700
#include "vb_output.h"

#include <errno.h>
#include <limits.h>
#include <stdatomic.h>
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Entries per chunk (channels writes five files, more with per-frame
 * volumes). */
#define VB_OUTPUT_CHUNK 32
#define VB_OUTPUT_PATH 4096

typedef struct out_entry {
    volatile sig_atomic_t live; /* tmp names a file to remove on a signal */
    FILE *f;                    /* NULL once closed */
    int ready;                  /* closed whole, waiting for vb_output_commit_deferred */
    int direct;                 /* written in place (not a regular file) */
    char final[VB_OUTPUT_PATH];
    char tmp[VB_OUTPUT_PATH];
} out_entry;

typedef struct out_chunk {
    out_entry e[VB_OUTPUT_CHUNK];
    struct out_chunk *_Atomic next;
} out_chunk;

static out_chunk outputs;
static pthread_mutex_t outputs_lock = PTHREAD_MUTEX_INITIALIZER;
static int handlers_installed;
static int defer_commits;

/* Every entry e of the table, chunk by chunk. */
#define FOR_EACH_ENTRY(e)                                                                        \
    for (out_chunk *c_ = &outputs; c_; c_ = atomic_load(&c_->next))                              \
        for (out_entry *e = c_->e; e < c_->e + VB_OUTPUT_CHUNK; e++)

static void remove_live(void)
{
    FOR_EACH_ENTRY(e)
        if (e->live)
            unlink(e->tmp);
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
    FOR_EACH_ENTRY(e)
        if (e->f == f && f)
            return e;
    return NULL;
}

/* A free entry (under outputs_lock): in the chunks there are, else in a
 * new chunk linked at the end. NULL when out of memory. */
static out_entry *free_entry(void)
{
    out_chunk *last = &outputs;
    FOR_EACH_ENTRY(e) {
        if (!e->f && !e->ready)
            return e;
        last = c_;
    }
    out_chunk *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    atomic_store(&last->next, c);
    return &c->e[0];
}

const char *vb_output_name(FILE *f)
{
    pthread_mutex_lock(&outputs_lock);
    out_entry *e = find(f);
    pthread_mutex_unlock(&outputs_lock);
    return e ? e->final : NULL;
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
    out_entry *e = free_entry();
    if (!e) {
        pthread_mutex_unlock(&outputs_lock);
        vb_error(ctx, VB_ENOMEM, path, 0, "out of memory (output table)");
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
        /* No signal between the file's creation and its entry going live:
         * a SIGTERM there left the temporary file behind. */
        sigset_t all, old;
        sigfillset(&all);
        pthread_sigmask(SIG_BLOCK, &all, &old);
        int fd = mkstemp(e->tmp);
        if (fd >= 0)
            e->live = 1;
        pthread_sigmask(SIG_SETMASK, &old, NULL);
        if (fd < 0) {
            vb_error(ctx, VB_EIO, path, 0, "cannot open for writing: %s", strerror(errno));
        } else {
            /* The mode fopen would give: the old file's, else 0666 less the umask. */
            mode_t mask = umask(0);
            umask(mask);
            fchmod(fd, exists ? (st.st_mode & 07777) : (0666 & ~mask));
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
    FOR_EACH_ENTRY(e) {
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
    FOR_EACH_ENTRY(e)
        if (e->f || e->ready) {
            if (e->f)
                fclose(e->f);
            if (!e->direct)
                unlink(e->tmp);
            forget(e);
        }
    pthread_mutex_unlock(&outputs_lock);
}
