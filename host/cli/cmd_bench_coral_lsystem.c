/* `sessile bench coral lsystem`: 1 M turtle modules (100 k with --quick)
 * derived, interpreted and meshed as tubes (host/coral/lsystem_bench.c). */
#include "cli.h"
#include "sessile/bench/bench.h"

sessile_status bench_coral_lsystem(sessile_gpu *g, const bench_section_opts *o, FILE *out) {
  (void)g; /* every stage is host code */
  return sessile_coral_lsystem_bench(o->quick ? 100000 : 1000000, out);
}
