/* The room left to this process (vb_memory.h): limits read from getrlimit,
 * /proc and the cgroup files, each left out when it cannot be read. Plain
 * stdio on small kernel files: nothing here allocates beyond what fopen
 * does, so it works when the heap is nearly full. */
#define _GNU_SOURCE
#include "vb_memory.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

/* The value in bytes of the first line of `path` that starts with `key`
 * (followed by blanks and a number, times `unit`); 0 when absent. */
static int read_key(const char *path, const char *key, size_t unit, size_t *out)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    char line[256];
    size_t klen = strlen(key);
    int found = 0;
    while (!found && fgets(line, sizeof line, f)) {
        unsigned long long v;
        if (strncmp(line, key, klen) == 0 && sscanf(line + klen, " %llu", &v) == 1) {
            *out = (size_t)v * unit;
            found = 1;
        }
    }
    fclose(f);
    return found;
}

/* A file that holds one number ("max" or a number over 2^62: no limit). */
static int read_limit(const char *path, size_t *out)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    unsigned long long v;
    int ok = fscanf(f, "%llu", &v) == 1 && v < (1ull << 62);
    fclose(f);
    if (ok)
        *out = (size_t)v;
    return ok;
}

static void take(vb_memory_limit *room, size_t limit, size_t used, const char *name)
{
    size_t left = limit > used ? limit - used : 0;
    if (left < room->bytes) {
        room->bytes = left;
        room->limit = name;
    }
}

static void rlimit_room(vb_memory_limit *room, int which, const char *status_key,
                        const char *name)
{
    struct rlimit rl;
    size_t used = 0;
    if (getrlimit(which, &rl) != 0 || rl.rlim_cur == RLIM_INFINITY)
        return;
    if (!read_key("/proc/self/status", status_key, 1024, &used))
        used = 0; /* unknown use: the limit alone, the larger room */
    take(room, (size_t)rl.rlim_cur, used, name);
}

/* cgroup v2: the process's own group (the "0::" line of /proc/self/cgroup);
 * v1: the memory controller's root as a container sees it. */
static void cgroup_room(vb_memory_limit *room)
{
    char path[512], dir[400] = "";
    size_t limit, anon = 0;
    FILE *f = fopen("/proc/self/cgroup", "r");
    if (f) {
        char line[512];
        while (fgets(line, sizeof line, f))
            if (strncmp(line, "0::", 3) == 0 && sscanf(line + 3, "%399s", dir) == 1)
                break;
        fclose(f);
    }
    if (dir[0] == '/' && dir[1] == '\0')
        dir[0] = '\0';
    snprintf(path, sizeof path, "/sys/fs/cgroup%s/memory.max", dir);
    if (read_limit(path, &limit)) {
        snprintf(path, sizeof path, "/sys/fs/cgroup%s/memory.stat", dir);
        read_key(path, "anon ", 1, &anon);
        take(room, limit, anon, "cgroup memory limit");
        return;
    }
    if (read_limit("/sys/fs/cgroup/memory/memory.limit_in_bytes", &limit)) {
        read_key("/sys/fs/cgroup/memory/memory.stat", "total_rss ", 1, &anon);
        take(room, limit, anon, "cgroup memory limit");
    }
}

static void machine_room(vb_memory_limit *room)
{
    size_t avail, swap = 0;
    if (read_key("/proc/meminfo", "MemAvailable:", 1024, &avail)) {
        read_key("/proc/meminfo", "SwapFree:", 1024, &swap);
        take(room, avail + swap, 0, "available memory (MemAvailable + SwapFree)");
        return;
    }
    long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    if (pages > 0 && size > 0)
        take(room, (size_t)pages * (size_t)size, 0, "physical memory");
}

void vb_memory_room_get(vb_memory_room *room)
{
    room->address.bytes = room->resident.bytes = SIZE_MAX;
    room->address.limit = room->resident.limit = NULL;
    rlimit_room(&room->address, RLIMIT_AS, "VmSize:", "ulimit -v (RLIMIT_AS)");
    rlimit_room(&room->resident, RLIMIT_DATA, "VmData:", "ulimit -d (RLIMIT_DATA)");
    cgroup_room(&room->resident);
    machine_room(&room->resident);
}
