/* Internal to host/growth: the growth run's warnings (a step that went on
 * in a degraded way: a TetGen fallback, a flow that did not converge).
 * Library code never prints directly; the flow code (grow_flow*.c) calls
 * grow_warn, the single place that decides where warnings go. */
#ifndef SESSILE_GROW_WARN_H
#define SESSILE_GROW_WARN_H

#include "grow_internal.h"

/* One warning of run r (a sentence without the trailing newline).  For now it
 * is printed to stderr unless the run is quiet (r->o->quiet); it is meant to
 * be routed through the growth run's own reporting callback. */
void grow_warn(grow_run *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#endif
