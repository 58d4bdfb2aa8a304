/* `sessile bench sds` (physics part): time per force + integrate step for
 * icosphere imports of about 1 k, 10 k and 100 k cells, GPU against the C
 * reference.  GPU_ms/step: one submission per step with the move check
 * (sessile_sds_gpu_step); GPU_batched: all steps in one submission
 * (sessile_sds_gpu_steps); the ratio is C over batched. */
#include <stdlib.h>
#include "sds/sds_internal.h"

typedef struct bench_size {
  int level;        /* icosphere level */
  double max_volume; /* TetGen volume bound (0: none), u^3 on a sphere of radius 1 */
  int host_steps, gpu_steps;
} bench_size;

static sessile_status bench_one(sessile_gpu *g, const bench_size *b, FILE *out) {
  const double ctr[3] = {0, 0, 0};
  sessile_sds o = {0};
  double t0 = sessile_wall_seconds();
  SESSILE_CALL(sessile_sds_from_icosphere(b->level, 1.0, ctr, b->max_volume, 0, 0, 1.0, &o));
  double t_import = sessile_wall_seconds() - t0;
  /* a small perturbation so that every force term is non-trivial */
  for (size_t k = 0; k < 3 * (size_t)o.ncells; k++) o.v[k] = 0.01 * (double)((k * 2654435761u) % 1000) / 1000.0;
  sessile_sds_params p;
  sessile_sds_params_default(&p);
  p.box = 1;
  for (int i = 0; i < 3; i++) p.box_lo[i] = -2, p.box_hi[i] = 2;
  double dt = 0.5 * sessile_sds_stable_dt(&o, &p);
  sessile_sds_gpu *s = NULL;
  sessile_status st = sessile_sds_gpu_create(g, &o, &p, &s);
  double tg = 0, tb = 0, th = 0;
  if (st == SESSILE_OK) st = sessile_sds_gpu_step(s, dt, NULL); /* warm-up */
  if (st == SESSILE_OK) {
    t0 = sessile_wall_seconds();
    for (int k = 0; k < b->gpu_steps && st == SESSILE_OK; k++) st = sessile_sds_gpu_step(s, dt, NULL);
    tg = (sessile_wall_seconds() - t0) / b->gpu_steps;
    t0 = sessile_wall_seconds();
    if (st == SESSILE_OK) st = sessile_sds_gpu_steps(s, (uint32_t)b->gpu_steps, dt);
    tb = (sessile_wall_seconds() - t0) / b->gpu_steps;
  }
  if (st == SESSILE_OK) {
    t0 = sessile_wall_seconds();
    for (int k = 0; k < b->host_steps; k++) sessile_sds_step_ref(&o, &p, dt);
    th = (sessile_wall_seconds() - t0) / b->host_steps;
    fprintf(out, "%8u %9u %9u %10.2f %12.3f %12.3f %12.3f %8.2f\n", o.ncells, o.ntets, o.nedges, t_import,
            1e3 * th, 1e3 * tg, 1e3 * tb, th / tb);
    fflush(out);
  }
  sessile_sds_gpu_destroy(s);
  sessile_sds_free(&o);
  return st;
}

sessile_status sessile_sds_bench_physics(sessile_gpu *g, FILE *out) {
  static const bench_size sizes[] = {{4, 0, 200, 200}, {5, 1e-4, 20, 40}, {7, 2e-5, 3, 10}};
  const sessile_gpu_info *i = sessile_gpu_info_of(g);
  fprintf(out, "sds physics: force + integrate step (edge, tet, gather kernels), device %s, fp%d\n", i->name,
          i->precision);
  fprintf(out, "%8s %9s %9s %10s %12s %12s %12s %8s\n", "cells", "tets", "edges", "import_s", "C_ms/step",
          "GPU_ms/step", "GPU_batched", "C/GPU");
  for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++) SESSILE_CALL(bench_one(g, &sizes[k], out));
  return SESSILE_OK;
}
