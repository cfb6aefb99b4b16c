/* A regular file's end written through a shared mapping (vb_write_map.h).
 * Copying a round of text into the page cache through write(2) runs on one
 * thread and costs the kernel's per-page path of a buffered write (160 MB
 * of vertex lines: 0.35 s of system CPU on the 2-core machine, against
 * 0.10-0.13 s through a mapping, results/proc55_stop54.md); a mapping lets
 * every thread copy its own blocks. The round's bytes are reserved with
 * fallocate first, so a full disk is an error here, not a SIGBUS at a
 * store into the mapping. */
#define _GNU_SOURCE
#include "vb_write_map.h"

#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

/* VORBALL_WRITE_MAP=1 turns the mapping on: on the 2-core machine it cost
 * more system CPU than write(2) (results/proc55_stop54.md); whether the
 * threads' copies pay on a many-core host is measured there first. */
static int map_allowed(void)
{
    const char *e = getenv("VORBALL_WRITE_MAP");
    return e && strcmp(e, "1") == 0;
}

int vb_map_begin(FILE *f, vb_map_out *m)
{
    memset(m, 0, sizeof *m);
    m->fd = -1;
    if (!map_allowed() || fflush(f) != 0)
        return -1;
    int fd = fileno(f);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
        return -1;
    /* Only a writer at the file's end that owns its position: an appending
     * descriptor (shared with a shell, say) keeps stdio. */
    int fl = fcntl(fd, F_GETFL);
    off_t at = lseek(fd, 0, SEEK_CUR);
    if (fl < 0 || (fl & O_APPEND) || (fl & O_ACCMODE) != O_RDWR || at != st.st_size)
        return -1;
    long pg = sysconf(_SC_PAGESIZE);
    m->fd = fd;
    m->off = at;
    m->page = pg > 0 ? (size_t)pg : 4096;
    return 0;
}

char *vb_map_round(vb_map_out *m, size_t len)
{
    if (m->fd < 0 || len == 0)
        return NULL;
    off_t start = m->off - (m->off % (off_t)m->page);
    size_t lead = (size_t)(m->off - start);
    void *p = MAP_FAILED;
    if (fallocate(m->fd, 0, m->off, (off_t)len) == 0)
        p = mmap(NULL, lead + len, PROT_READ | PROT_WRITE, MAP_SHARED, m->fd, start);
    if (p == MAP_FAILED) {
        /* Whatever a failed reservation added is cut back, so that stdio
         * goes on where the text ends (vb_map_end). */
        if (ftruncate(m->fd, m->off) != 0)
            m->failed = 1;
        return NULL;
    }
    m->base = p;
    m->maplen = lead + len;
    m->len = len;
    return (char *)p + lead;
}

void vb_map_round_end(vb_map_out *m)
{
    if (!m->base)
        return;
    munmap(m->base, m->maplen);
    m->off += (off_t)m->len;
    m->base = NULL;
    m->maplen = m->len = 0;
}

int vb_map_end(FILE *f, vb_map_out *m)
{
    if (m->fd < 0)
        return m->failed ? -1 : 0;
    vb_map_round_end(m);
    m->fd = -1;
    return fseeko(f, m->off, SEEK_SET) != 0 || m->failed ? -1 : 0;
}
