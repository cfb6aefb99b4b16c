/* Allocation-failure injection (issue 28; SQLite's malloc fault tests):
 * linked into a test copy of vorball with -Wl,--wrap=malloc,calloc,realloc
 * (tests/fault/CMakeLists.txt), so every allocation of vorball's own code
 * (the CLI and the static libraries it links) goes through here, and the
 * n-th of them fails. Allocations inside shared libraries (libc's stdio,
 * GMP, which aborts when its allocator fails, PoCL) are neither counted nor
 * failed: they are not vorball's to handle. A link-time wrap rather than an
 * LD_PRELOAD shim, because a preloaded malloc and ASan's interceptors do not
 * mix: the wrapped calls go on to __real_malloc, which under the sanitizers
 * is ASan's, so the sanitizer tree runs the same test and finds the leaks
 * of every failure path.
 *
 * Environment:
 *   VB_FAIL_ALLOC_AT      which allocation fails, from 1 (unset or 0: none)
 *   VB_FAIL_ALLOC_STICKY  non-empty: that one and every later one fail
 *   VB_FAIL_ALLOC_COUNTS  file to which "allocations N" and "failed K" are
 *                         written at exit (the counting pass)
 *   VB_FAIL_ALLOC_TRACE   non-empty: the failing call's stack on stderr (to
 *                         find the caller of a failure a run mishandles)
 * A failed allocation is named on stderr ("allocfault: allocation N
 * failed", once). */
#include <execinfo.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>

void *__real_malloc(size_t size);
void *__real_calloc(size_t n, size_t size);
void *__real_realloc(void *p, size_t size);
void *__wrap_malloc(size_t size);
void *__wrap_calloc(size_t n, size_t size);
void *__wrap_realloc(void *p, size_t size);

static atomic_ulong vbaf_calls;
static atomic_ulong vbaf_failed;
static unsigned long vbaf_at;
static int vbaf_sticky;
static int vbaf_trace;

__attribute__((constructor)) static void vbaf_init(void)
{
    const char *at = getenv("VB_FAIL_ALLOC_AT");
    const char *sticky = getenv("VB_FAIL_ALLOC_STICKY");
    vbaf_at = at ? strtoul(at, NULL, 10) : 0;
    vbaf_sticky = sticky && *sticky;
    const char *trace = getenv("VB_FAIL_ALLOC_TRACE");
    vbaf_trace = trace && *trace;
}

__attribute__((destructor)) static void vbaf_report(void)
{
    const char *path = getenv("VB_FAIL_ALLOC_COUNTS");
    FILE *f = path ? fopen(path, "w") : NULL;
    if (!f)
        return;
    fprintf(f, "allocations %lu\nfailed %lu\n", atomic_load(&vbaf_calls),
            atomic_load(&vbaf_failed));
    fclose(f);
}

/* The caller of the wrapped function, as "caller 0x.. (wrap 0x..)": with
 * the wrapper's own address, addr2line finds the line (PIE-relative). */
static int vbaf_fail(void *caller)
{
    unsigned long k = atomic_fetch_add(&vbaf_calls, 1) + 1;
    if (vbaf_at == 0 || k < vbaf_at || (k > vbaf_at && !vbaf_sticky))
        return 0;
    if (atomic_fetch_add(&vbaf_failed, 1) == 0) {
        fprintf(stderr, "allocfault: allocation %lu failed (caller %p, wrap %p)\n", k, caller,
                (void *)&__wrap_malloc);
        if (vbaf_trace) {
            void *frames[32];
            backtrace_symbols_fd(frames, backtrace(frames, 32), 2);
        }
    }
    return 1;
}

void *__wrap_malloc(size_t size)
{
    return vbaf_fail(__builtin_return_address(0)) ? NULL : __real_malloc(size);
}

void *__wrap_calloc(size_t n, size_t size)
{
    return vbaf_fail(__builtin_return_address(0)) ? NULL : __real_calloc(n, size);
}

void *__wrap_realloc(void *p, size_t size)
{
    return vbaf_fail(__builtin_return_address(0)) ? NULL : __real_realloc(p, size);
}
