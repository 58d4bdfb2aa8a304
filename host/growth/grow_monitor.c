/* The growth loop's lines for its caller: the library prints nothing; the
 * CLI's monitor decides where progress and warnings go. */
#include <stdarg.h>
#include <stdio.h>
#include "grow_internal.h"

static void vsay(const grow_run *r, sessile_monitor_kind kind, const char *fmt, va_list ap) {
  if (!r->o->monitor) return;
  char line[1200];
  vsnprintf(line, sizeof line, fmt, ap);
  r->o->monitor(r->o->monitor_user, kind, line);
}

void grow_monitor(const grow_run *r, sessile_monitor_kind kind, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsay(r, kind, fmt, ap);
  va_end(ap);
}

void grow_warn(const grow_run *r, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsay(r, SESSILE_MONITOR_WARNING, fmt, ap);
  va_end(ap);
}
