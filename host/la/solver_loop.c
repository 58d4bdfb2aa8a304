/* The host side of every device Krylov loop: submit the recorded block of
 * iterations, read the mapped scalars, repeat until the device says stop.
 * The device checks convergence itself every iteration and turns the rest
 * of a block into no-ops, so the host only decides when to look. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include "la_internal.h"

sessile_status la_solver_loop(sessile_la *la, sessile_cmd *iter, int per_submit, int max_it,
                              const sessile_ksp_options *o, const char *name, int est_slot,
                              int est_is_sq) {
  /* Each submit advances at least one iteration until the device stops, so
   * this bound is never reached by a correct solver: it guards against hangs. */
  long bound = (long)max_it / (per_submit > 0 ? per_submit : 1) + (long)max_it + 4;
  for (long k = 0; la_scalar_read(la, S_STOP) == STOP_RUNNING; k++) {
    SESSILE_CHECK(k < bound, SESSILE_ERR_INTERNAL,
                  "%s did not stop after %ld submits of %d iterations (max_it %d)", name, k,
                  per_submit, max_it);
    SESSILE_CALL(sessile_cmd_submit_wait(iter));
    if (o->monitor) {
      double est = la_scalar_read(la, est_slot);
      if (est_is_sq) est = sqrt(fmax(est, 0));
      la_monitorf(o, "%s %5d  |r|/|b| %.6e", name, (int)la_scalar_read(la, S_ITER),
                  est / sqrt(la_scalar_read(la, S_BB)));
    }
  }
  return SESSILE_OK;
}

/* Common start: STOP = 0 and the limits the device tests against. */
void la_solver_reset(sessile_la *la, const sessile_ksp_options *o) {
  la_scalar_set(la, S_STOP, STOP_RUNNING);
  la_scalar_set(la, S_ITER, 0);
  la_scalar_set(la, S_REASON, 0);
  la_scalar_set(la, S_MAXIT, o->max_it);
  la_scalar_set(la, S_RTOL2, o->rtol * o->rtol);
}

void sessile_monitor_vprintf(sessile_monitor_fn fn, void *user, const char *fmt, va_list ap) {
  if (!fn) return;
  char line[SESSILE_MONITOR_LINE];
  if (vsnprintf(line, sizeof line, fmt, ap) < 0) line[0] = '\0';
  fn(user, line);
}

void la_monitorf(const sessile_ksp_options *o, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  sessile_monitor_vprintf(o->monitor, o->monitor_user, fmt, ap);
  va_end(ap);
}
