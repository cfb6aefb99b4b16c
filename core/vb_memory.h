/* How much more memory this process can take before an allocation fails
 * or the machine runs out: the room a pipeline compares its estimate with
 * before it starts (issue 28 item 7). */
#ifndef VB_MEMORY_H
#define VB_MEMORY_H

#include <stddef.h>

/* The room under one kind of limit. */
typedef struct vb_memory_limit {
    size_t bytes;        /* the least room of the limits of the kind; SIZE_MAX: none known */
    const char *limit;   /* which limit that is ("ulimit -v (RLIMIT_AS)", "ulimit -d
                          * (RLIMIT_DATA)", "cgroup memory limit", "available memory
                          * (MemAvailable + SwapFree)", "physical memory"); NULL: none */
} vb_memory_limit;

typedef struct vb_memory_room {
    vb_memory_limit address;  /* address space: reserved, untouched pages count too */
    vb_memory_limit resident; /* memory in use: what is touched */
} vb_memory_room;

/* Fills *room with the room left to this process. The address room is
 * RLIMIT_AS (ulimit -v) less the address space now mapped (VmSize). The
 * resident room is the least of:
 *   - RLIMIT_DATA (ulimit -d) less the data now mapped (VmData);
 *   - a cgroup's memory limit less its anonymous memory in use (v2
 *     memory.max / memory.stat anon, or v1 memory.limit_in_bytes /
 *     total_rss): page cache is left out, the kernel reclaims it;
 *   - MemAvailable + SwapFree of /proc/meminfo (what the kernel can hand
 *     out before it kills a process), or where that cannot be read the
 *     physical memory (sysconf _SC_PHYS_PAGES x page size).
 * A limit that cannot be read is left out (never guessed), so the room is
 * never smaller than the truth by the reading: callers may refuse work
 * that needs more. Allocates nothing; cannot fail. */
void vb_memory_room_get(vb_memory_room *room);

#endif
