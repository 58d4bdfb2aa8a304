/* PLACEHOLDER until the weld generator lands (replaced by its owner). */
#include "cli.h"
sessile_status bench_coral_weld(sessile_gpu *g, const bench_coral_opts *o, FILE *out) {
  (void)g, (void)o, (void)out;
  return sessile_error_set(SESSILE_ERR_USAGE, "bench coral weld: not built yet");
}
