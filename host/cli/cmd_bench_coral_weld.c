/* `sessile bench coral weld`: the welded surface of a random 10 k-segment
 * coral on a 256-cell grid, GPU by stage against the plain-C reference in
 * the same run (host/bench/weld_bench.c, docs/weld.md). */
#include "cli.h"
#include "sessile/bench/bench.h"

sessile_status bench_coral_weld(sessile_gpu *g, const bench_section_opts *o, FILE *out) {
  return sessile_bench_weld(g, o->quick, out);
}
