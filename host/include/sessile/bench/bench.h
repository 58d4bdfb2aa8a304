/* sessile — benchmarks (`sessile bench ...`, host/bench): figures and ratios
 * against a plain-C baseline measured in the same run.  Never asserted in
 * tests. */
#ifndef SESSILE_BENCH_H
#define SESSILE_BENCH_H
#include <stdint.h>
#include <signal.h>
#include <stdio.h>
#include "sessile/gpu/gpu.h"
#include "sessile/load.h"

typedef struct sessile_bench_la_options {
  unsigned size;    /* grid edge: vectors of size^3, 7-point and P1-tet matrices on size^3 */
  unsigned repeat;  /* repetitions per kernel (GPU: recorded in one submit) */
  int solvers;      /* also time PCG, BiCGSTAB, GMRES */
  unsigned mg_sizes; /* with solvers: multigrid PCG beside Jacobi-PCG on the cut-cell sphere
                        problem at the first mg_sizes of 33x33x25, 65x65x49, 129x129x97 (0: none) */
} sessile_bench_la_options;

sessile_status sessile_bench_la(sessile_gpu *g, const sessile_bench_la_options *o, FILE *out);

/* Times the GPU weld by stage and the reference; prints to out.  quick:
 * 500 segments on 64 cells (a smoke run). */
sessile_status sessile_bench_weld(sessile_gpu *g, int quick, FILE *out);

/* The L-system benchmark: a lophelia-like grammar derived until it holds at
 * least target modules, interpreted and meshed as tubes; stage times to out. */
sessile_status sessile_coral_lsystem_bench(uint32_t target, FILE *out);

/* Times force + integrate steps for icosphere imports of levels 2-5 (and
 * the Figure 9 body over its rock), GPU against the C reference, with the
 * contact stages' share (medians of 5 repeats); prints one line per size. */
sessile_status sessile_sds_bench_physics(sessile_gpu *g, FILE *out);
/* Runs the shipped rock model (Figure 9) through sessile_sds_run to t_end
 * (< 0: the model's) in a temporary run directory made under scratch (the
 * CLI's $TMPDIR or /tmp; removed after) and prints wall time, cells, tets,
 * steps and the ratio to the paper's 5.7 minutes (extrapolated, and labelled
 * so, when t_end is short of the model's). */
/* stop (may be NULL): a signal's flag, polled by the run; when it is raised
 * the run ends early with SESSILE_ERR_INTERRUPTED and the folder is removed
 * all the same.  mass_dt > 0: a third run, the host-driven loop with
 * mass_scaling_dt mass_dt, against the first (another trajectory).
 * repeats, 1..SESSILE_SDS_BENCH_REPEAT_MAX: the runs made that many times, the loops alternating, then
 * each loop's median and minimum wall and the median of the ratios. */
#define SESSILE_SDS_BENCH_REPEAT_MAX 9
sessile_status sessile_sds_bench_rock(sessile_gpu *g, double t_end, double mass_dt, unsigned repeats,
                                      const char *scratch, const volatile sig_atomic_t *stop, FILE *out);
#endif
