/* Shared by the benchmarks of host/bench (not public). */
#ifndef SESSILE_BENCH_INTERNAL_H
#define SESSILE_BENCH_INTERNAL_H
#include <stdio.h>
#include "la/mg_internal.h"
#include "sessile/bench/matrix_gen.h"

/* `sessile bench la`'s multigrid table (bench_mg.c): the first `sizes` of
 * 33x33x25, 65x65x49, 129x129x97. */
sessile_status la_bench_mg(sessile_la *la, unsigned sizes, FILE *out);
#endif
