/* The welded surface's benchmark, apart from weld_internal.h so that the
 * CLI can call it without sessile/skeleton.h (whose sessile_skeleton clashes
 * with the growth parameters' enum of the same name in sessile/grow_params.h). */
#ifndef SESSILE_WELD_BENCH_H
#define SESSILE_WELD_BENCH_H
#include <stdio.h>
#include "sessile/gpu.h"
/* Times the GPU weld by stage and the reference; prints to out.  quick:
 * 500 segments on 64 cells (a smoke run). */
sessile_status weld_bench(sessile_gpu *g, int quick, FILE *out);
#endif
