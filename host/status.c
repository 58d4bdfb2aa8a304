/* The one error path: the failing function records a message here and
 * returns its code; callers only propagate the code.  The message buffer is
 * thread-local so OpenMP workers and Vulkan callers never race on it. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "sessile/status.h"

#define SESSILE_ERROR_MESSAGE_MAX 1024

static _Thread_local char error_message[SESSILE_ERROR_MESSAGE_MAX];

const char *sessile_status_name(sessile_status s) {
  switch (s) {
#define X(v) case v: return #v;
    X(SESSILE_OK) X(SESSILE_ERR_USAGE) X(SESSILE_ERR_NO_DEVICE) X(SESSILE_ERR_VULKAN)
    X(SESSILE_ERR_NO_MEMORY) X(SESSILE_ERR_TOO_LARGE) X(SESSILE_ERR_IO)
    X(SESSILE_ERR_UNSUPPORTED) X(SESSILE_ERR_NUMERIC) X(SESSILE_ERR_INTERNAL)
    X(SESSILE_ERR_INTERRUPTED)
#undef X
  }
  /* Outside the switch so -Wswitch still flags a newly added enumerator. */
  return "SESSILE_STATUS_UNKNOWN";
}

sessile_status sessile_error_set(sessile_status s, const char *fmt, ...) {
  /* Format into scratch first: a caller may pass error_message itself as an
   * argument ("iteration 3: %s", sessile_error_message()), and vsnprintf
   * into its own source is undefined (it printed "...: tory"). */
  char scratch[SESSILE_ERROR_MESSAGE_MAX];
  va_list ap;
  va_start(ap, fmt);
  /* vsnprintf truncates and always terminates: a long message is cut, never lost. */
  if (vsnprintf(scratch, sizeof scratch, fmt, ap) < 0) scratch[0] = '\0';
  va_end(ap);
  memcpy(error_message, scratch, sizeof error_message);
  return s;
}

const char *sessile_error_message(void) { return error_message; }

void sessile_error_clear(void) { error_message[0] = '\0'; }

sessile_status sessile_error_pass(sessile_status s, const char *fmt, ...) {
  char where[256], scratch[SESSILE_ERROR_MESSAGE_MAX];
  va_list ap;
  va_start(ap, fmt);
  if (vsnprintf(where, sizeof where, fmt, ap) < 0) where[0] = '\0';
  va_end(ap);
  /* an interruption is no failure: its message is the stop, unprefixed */
  if (s == SESSILE_ERR_INTERRUPTED || !where[0]) return s;
  snprintf(scratch, sizeof scratch, "%.200s: %.800s", where, error_message);
  memcpy(error_message, scratch, sizeof error_message);
  return s;
}
