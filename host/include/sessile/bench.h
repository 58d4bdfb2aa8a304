/* sessile — benchmarks (`sessile bench ...`): figures and ratios against a
 * plain-C baseline measured in the same run.  Never asserted in tests. */
#ifndef SESSILE_BENCH_H
#define SESSILE_BENCH_H
#include <stdio.h>
#include "sessile/gpu.h"

typedef struct sessile_bench_la_options {
  unsigned size;    /* grid edge: vectors of size^3, 7-point and P1-tet matrices on size^3 */
  unsigned repeat;  /* repetitions per kernel (GPU: recorded in one submit) */
  int solvers;      /* also time PCG, BiCGSTAB, GMRES */
  unsigned mg_sizes; /* with solvers: multigrid PCG beside Jacobi-PCG on the cut-cell sphere
                        problem at the first mg_sizes of 33x33x25, 65x65x49, 129x129x97 (0: none) */
} sessile_bench_la_options;

/* The 1, 5 and 15 minute load averages (/proc/loadavg); 0 and -1s when
 * unavailable. */
int sessile_load_average(double load[3]);

sessile_status sessile_bench_la(sessile_gpu *g, const sessile_bench_la_options *o, FILE *out);
#endif
