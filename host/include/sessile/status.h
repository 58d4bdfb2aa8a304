/* sessile — status codes and the one error path.
 *
 * Every function that can fail returns a sessile_status.  The function that
 * detects a failure records a message (what failed, with which values, and what
 * to do) with sessile_error_set(); callers propagate the code with SESSILE_CALL.
 * Library code never exits or aborts; the CLI maps codes to exit codes
 * (SESSILE_ERR_USAGE -> 2, everything else -> 1). */
#ifndef SESSILE_STATUS_H
#define SESSILE_STATUS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sessile_status {
  SESSILE_OK = 0,
  SESSILE_ERR_USAGE = 1,       /* bad argument or input from the user */
  SESSILE_ERR_NO_DEVICE = 2,   /* no Vulkan device (or none matching --device) */
  SESSILE_ERR_VULKAN = 3,      /* a Vulkan call failed */
  SESSILE_ERR_NO_MEMORY = 4,   /* host or device allocation failed */
  SESSILE_ERR_TOO_LARGE = 5,   /* exceeds a device limit (maxStorageBufferRange, ...) */
  SESSILE_ERR_IO = 6,          /* file read/write failed */
  SESSILE_ERR_UNSUPPORTED = 7, /* the device lacks a needed feature */
  SESSILE_ERR_NUMERIC = 8,     /* numerically invalid input (zero diagonal, NaN, ...) */
  SESSILE_ERR_INTERNAL = 9,    /* a bug: an invariant of sessile itself failed */
  SESSILE_ERR_INTERRUPTED = 10 /* stopped on request (SIGINT/SIGTERM); the state is saved */
} sessile_status;

/* Short name of a status ("SESSILE_ERR_VULKAN"). */
const char *sessile_status_name(sessile_status s);

/* Records the message of the failure just detected (thread-local) and returns s.
 * The arguments may include sessile_error_message() itself (to prefix it):
 * the message is formatted into a scratch buffer before it replaces the old. */
sessile_status sessile_error_set(sessile_status s, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* Hands a failure upward with where it passed: the recorded message becomes
 * "<where>: <message>" (PETSc's traceback, one line), e.g. "iteration 12:
 * remesh: out of host memory".  Returns s. */
sessile_status sessile_error_pass(sessile_status s, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The last recorded message of this thread ("" if none). */
const char *sessile_error_message(void);

/* Forgets the last message. */
void sessile_error_clear(void);

/* Propagate a failure upward unchanged. */
#define SESSILE_CALL(expr)                                                     \
  do {                                                                         \
    sessile_status sessile_call_s_ = (expr);                                   \
    if (sessile_call_s_ != SESSILE_OK) return sessile_call_s_;                 \
  } while (0)

/* Propagate a failure upward, naming where it passed (sessile_error_pass). */
#define SESSILE_CALL_AT(expr, ...)                                             \
  do {                                                                         \
    sessile_status sessile_call_s_ = (expr);                                   \
    if (sessile_call_s_ != SESSILE_OK)                                         \
      return sessile_error_pass(sessile_call_s_, __VA_ARGS__);                 \
  } while (0)

/* Check a condition where it is detected; message in words a user can act on. */
#define SESSILE_CHECK(cond, status, ...)                                       \
  do {                                                                         \
    if (!(cond)) return sessile_error_set((status), __VA_ARGS__);              \
  } while (0)

#ifdef __cplusplus
}
#endif
#endif
