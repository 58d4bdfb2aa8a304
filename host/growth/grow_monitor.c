/* The growth loop's warnings for its caller: the library prints nothing; the
 * CLI decides where they go (progress is the run loop's report). */
#include <stdarg.h>
#include <stdio.h>
#include "grow_internal.h"

/* The growth monitor takes a kind as well: the line is formatted by la's
 * one formatter and handed on with it. */
typedef struct say_to {
  const grow_run *r;
  sessile_monitor_kind kind;
} say_to;

static void say_line(void *user, const char *line) {
  const say_to *t = user;
  t->r->o->monitor(t->r->o->monitor_user, t->kind, line);
}

static void vsay(const grow_run *r, sessile_monitor_kind kind, const char *fmt, va_list ap) {
  say_to t = {r, kind};
  sessile_monitor_vprintf(r->o->monitor ? say_line : NULL, &t, fmt, ap);
}

void grow_warn(const grow_run *r, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsay(r, SESSILE_MONITOR_WARNING, fmt, ap);
  va_end(ap);
}
