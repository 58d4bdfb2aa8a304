/* Allocation fault injection for the test-only CLI `sessile_faultinj`
 * (docs/design.md, "Errors and diagnostics").  The executable is linked with
 * -Wl,--wrap=malloc,... so every call that sessile's own objects make to an
 * allocator comes here; shared libraries (libc itself, the Vulkan loader and
 * driver, cJSON, OpenEXR, ...) keep the real ones.
 *
 * SESSILE_FAULT_ALLOC=N (N >= 1) fails the N-th wrapped allocation of the
 * process, once (later ones succeed, as after a transient shortage, so the
 * failure path's own clean-up runs on a working allocator).
 * SESSILE_FAULT_ALLOC=0 fails none and prints "faultinj: N allocations" on
 * stderr at exit, so that a test knows the range of N to try.
 * Unset: the wrappers only forward.  SESSILE_FAULT_TRACE=1 also prints the
 * failed allocation's call stack (for finding the site, never in the test). */
#define _GNU_SOURCE /* strndup, getline, realpath */
#include <errno.h>
#include <execinfo.h>
#include <limits.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>

void *__real_malloc(size_t n);
void *__real_calloc(size_t k, size_t n);
void *__real_realloc(void *p, size_t n);
char *__real_strdup(const char *s);
char *__real_strndup(const char *s, size_t n);
ssize_t __real_getline(char **line, size_t *cap, FILE *f);
char *__real_realpath(const char *path, char *resolved);

static long fault_at = -1; /* -1 off, 0 count only, N fail the N-th */
static atomic_long calls;
static int trace;

static void report_count(void) { fprintf(stderr, "faultinj: %ld allocations\n", atomic_load(&calls)); }

/* Before main (and before any of our allocations): the test binary's own code
 * reads the environment, the library never does. */
__attribute__((constructor)) static void faultinj_init(void) {
  const char *e = getenv("SESSILE_FAULT_ALLOC");
  if (!e || !*e) return;
  char *end;
  long n = strtol(e, &end, 10);
  if (*end || n < 0) return;
  fault_at = n;
  const char *t = getenv("SESSILE_FAULT_TRACE");
  trace = t && *t == '1';
  if (n == 0) atexit(report_count);
}

/* Whether this allocation is the one to fail (counts it either way). */
static int fail_now(void) {
  if (fault_at < 0) return 0;
  long k = atomic_fetch_add(&calls, 1) + 1;
  if (k != fault_at) return 0;
  if (trace) { /* backtrace_symbols_fd allocates nothing */
    void *pc[32];
    backtrace_symbols_fd(pc, backtrace(pc, 32), 2);
  }
  errno = ENOMEM;
  return 1;
}

void *__wrap_malloc(size_t n) { return fail_now() ? NULL : __real_malloc(n); }
void *__wrap_calloc(size_t k, size_t n) { return fail_now() ? NULL : __real_calloc(k, n); }
/* realloc(p, n) failing leaves p allocated, as the real one does. */
void *__wrap_realloc(void *p, size_t n) { return fail_now() ? NULL : __real_realloc(p, n); }
char *__wrap_strdup(const char *s) { return fail_now() ? NULL : __real_strdup(s); }
char *__wrap_strndup(const char *s, size_t n) { return fail_now() ? NULL : __real_strndup(s, n); }
/* getline may (re)allocate its buffer on every call; failing reads as -1 with
 * errno ENOMEM, as glibc's does. */
ssize_t __wrap_getline(char **line, size_t *cap, FILE *f) {
  return fail_now() ? -1 : __real_getline(line, cap, f);
}
/* realpath allocates only when given no buffer. */
char *__wrap_realpath(const char *path, char *resolved) {
  if (!resolved && fail_now()) return NULL;
  return __real_realpath(path, resolved);
}
