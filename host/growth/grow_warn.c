/* The growth run's warnings (grow_warn.h): the only place in host/growth's
 * flow code that reaches the terminal, so that rerouting warnings (to a
 * callback of the run) is a change here alone. */
#include <stdarg.h>
#include <stdio.h>
#include "grow_warn.h"

void grow_warn(grow_run *r, const char *fmt, ...) {
  if (r->o->quiet) return;
  char msg[1024];
  va_list ap;
  va_start(ap, fmt);
  if (vsnprintf(msg, sizeof msg, fmt, ap) < 0) msg[0] = '\0';
  va_end(ap);
  fprintf(stderr, "\nsessile grow: warning: %s\n", msg);
}
