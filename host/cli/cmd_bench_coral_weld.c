/* `sessile bench coral weld`: the welded surface of a random 10 k-segment
 * coral on a 256-cell grid, GPU by stage against the plain-C reference in
 * the same run (host/mesh/weld_bench.c, docs/weld.md). */
#include "cli.h"
#include "mesh/weld_bench.h"

sessile_status bench_coral_weld(sessile_gpu *g, const bench_coral_opts *o, FILE *out) {
  return weld_bench(g, o->quick, out);
}
