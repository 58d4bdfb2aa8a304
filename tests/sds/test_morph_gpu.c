/* The morphogen kernel (shaders/sds/morph_step.comp) against its plain-C
 * reference (sessile_morph_step) on a jittered 12x10x8 lattice with three
 * morphogens (diffusing, diffusing + decaying with sources, an uncapped
 * timer), with caps binding in part of the lattice.
 * Tolerances: fp64 1e-12 relative after 50 steps (same operations in the
 * same order; sqrt and the constant 4/3 pi may round differently by an ulp);
 * --fp32 1e-4 (float amounts, 50 steps).  Also: the GPU's total of a
 * diffusion-only morphogen is conserved (1e-12 relative), the same input
 * gives the same bytes twice and through either kernel (texel or storage
 * reads), and dt above the bound is refused; the loop's morphogen step is
 * one submission, uploads included, and uploads left without a step are run
 * by get_phi and set_cells. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "morph_lattice.h"
#include "testutil.h"

int main(int argc, char **argv) {
  int fp32 = argc > 1 && !strcmp(argv[1], "--fp32");
  sessile_gpu *g = t_gpu(fp32 ? 32 : 64);
  lattice L = lattice_make(12, 10, 8, 1.0, 0.2, 0.1, 7);
  int n = L.cells.ncells, nm = 3;
  double D[3] = {0.1, 0.05, 0.0}, C[3] = {0.0, 0.02, 0.05};
  int capped[3] = {1, 1, 0};
  sessile_morph_coef co = {nm, D, C, capped};
  double *phi = t_dalloc((size_t)n * nm), *src = t_dalloc((size_t)n * nm), *ref = t_dalloc((size_t)n * nm),
         *tmp = t_dalloc((size_t)n * nm), *gpu = t_dalloc((size_t)n * nm), *gpu2 = t_dalloc((size_t)n * nm);
  uint64_t s = sessile_rng_stream(11, 2);
  for (int c = 0; c < n; c++) {
    double v = sessile_morph_vol(L.radius[c]);
    /* morphogen 0: full cells in one corner (caps bind there), else a fraction */
    phi[c * nm] = L.pos[3 * c] < 3 ? v : sessile_rng_range(&s, 0, 0.3) * v;
    phi[c * nm + 1] = sessile_rng_range(&s, 0, 0.5) * v;
    phi[c * nm + 2] = sessile_rng_range(&s, 0, 2.0);
    src[c * nm + 1] = c % 17 == 0 ? 0.01 : 0.0;
  }
  double dtm = sessile_morph_dt_max(&L.cells, &co), dt = 0.9 * dtm;
  printf("dt_max = %.6g, dt = %.6g\n", dtm, dt);
  int steps = 50;
  memcpy(ref, phi, sizeof(double) * n * nm);
  size_t clamped = 0, cl = 0;
  for (int i = 0; i < steps; i++) {
    t_must("host step", sessile_morph_step(&L.cells, &co, ref, src, dt, tmp, &cl));
    clamped += cl;
    memcpy(ref, tmp, sizeof(double) * n * nm);
  }
  printf("host: %zu clamped values over %d steps\n", clamped, steps);
  sessile_morph_gpu *m = NULL;
  t_must("create", sessile_morph_gpu_create(g, &m));
  t_must("set cells", sessile_morph_gpu_set_cells(m, &L.cells, &co));
  t_must("set phi", sessile_morph_gpu_set_phi(m, phi, src));
  t_must("gpu steps", sessile_morph_gpu_step(m, dt, steps));
  t_must("get", sessile_morph_gpu_get_phi(m, gpu));
  double tol = fp32 ? 1e-4 : 1e-12;
  t_check("gpu vs host, 3 morphogens, 50 steps (relative)", t_relerr(gpu, ref, (size_t)n * nm), tol);
  /* twice the same: the same bytes */
  t_must("set phi", sessile_morph_gpu_set_phi(m, phi, src));
  t_must("gpu steps", sessile_morph_gpu_step(m, dt, 20));
  t_must("gpu steps", sessile_morph_gpu_step(m, dt, 30));
  t_must("get", sessile_morph_gpu_get_phi(m, gpu2));
  t_true("same bytes twice (50 steps in one call vs 20 + 30)", !memcmp(gpu, gpu2, sizeof(double) * n * nm));
  /* the storage-read kernel gives the texel-read one's bytes */
  sessile_morph_gpu_set_reads(m, 1);
  t_must("set phi", sessile_morph_gpu_set_phi(m, phi, src));
  t_must("gpu steps, storage reads", sessile_morph_gpu_step(m, dt, steps));
  t_must("get", sessile_morph_gpu_get_phi(m, gpu2));
  sessile_morph_gpu_set_reads(m, 0);
  t_true("storage reads give the texel reads' bytes (50 steps)", !memcmp(gpu, gpu2, sizeof(double) * n * nm));
  double t0 = sessile_morph_total(n, nm, phi, 0), t1 = sessile_morph_total(n, nm, gpu, 0);
  t_check("gpu: total of the diffusion-only morphogen conserved (relative)", fabs(t1 - t0) / t0,
          fp32 ? 1e-5 : 1e-12);
  t_true("gpu refuses dt above the bound", sessile_morph_gpu_step(m, 1.01 * dtm, 1) == SESSILE_ERR_USAGE);
  /* move_cells (the loop between topology changes: positions and radii
   * only) gives the bytes of set_cells with the moved cells, and its bound */
  double *pos0 = t_dalloc(3 * (size_t)n), *rad0 = t_dalloc((size_t)n);
  memcpy(pos0, L.cells.pos, 3 * (size_t)n * sizeof *pos0), memcpy(rad0, L.cells.radius, (size_t)n * sizeof *rad0);
  sessile_morph_cells moved = L.cells;
  double *pos1 = t_dalloc(3 * (size_t)n), *rad1 = t_dalloc((size_t)n);
  for (int k = 0; k < 3 * n; k++) pos1[k] = pos0[k] + sessile_rng_range(&s, -0.05, 0.05);
  for (int c = 0; c < n; c++) rad1[c] = rad0[c] * sessile_rng_range(&s, 0.9, 1.1);
  moved.pos = pos1, moved.radius = rad1;
  double dtm1 = sessile_morph_dt_max(&moved, &co);
  uint64_t q0 = sessile_gpu_submissions(g);
  t_must("move cells", sessile_morph_gpu_move_cells(m, &moved, &co));
  t_true("move_cells: the moved cells' step bound", sessile_morph_gpu_dt_max(m) == dtm1);
  t_must("set phi", sessile_morph_gpu_set_phi(m, phi, src));
  t_must("gpu steps", sessile_morph_gpu_step(m, 0.9 * dtm1, 20));
  t_must("get", sessile_morph_gpu_get_phi(m, gpu));
  uint64_t nq = sessile_gpu_submissions(g) - q0;
  printf("move_cells, set_phi, 20 steps, get_phi: %llu submission(s)\n", (unsigned long long)nq);
  t_true("the loop's morphogen step (move_cells, set_phi, step, get_phi) is one submission", nq == 1);
  sessile_morph_gpu *m2 = NULL;
  t_must("create", sessile_morph_gpu_create(g, &m2));
  t_must("set cells", sessile_morph_gpu_set_cells(m2, &moved, &co));
  t_must("set phi", sessile_morph_gpu_set_phi(m2, phi, src));
  t_must("gpu steps", sessile_morph_gpu_step(m2, 0.9 * dtm1, 20));
  t_must("get", sessile_morph_gpu_get_phi(m2, gpu2));
  t_true("move_cells gives set_cells' bytes with the moved cells (20 steps)",
         !memcmp(gpu, gpu2, sizeof(double) * n * nm));
  /* uploads without a step: get_phi runs them, and set_cells (the buffers
   * may be replaced) too */
  for (int k = 0; k < n * nm; k++) gpu[k] = phi[k] * 0.5;
  t_must("set phi", sessile_morph_gpu_set_phi(m2, gpu, src));
  t_must("get", sessile_morph_gpu_get_phi(m2, gpu2));
  int same = 1;
  for (int k = 0; k < n * nm; k++) same &= gpu2[k] == (fp32 ? (double)(float)gpu[k] : gpu[k]);
  t_true("set_phi then get_phi without a step: the amounts set", same);
  t_must("set phi", sessile_morph_gpu_set_phi(m2, phi, src));
  t_must("set cells", sessile_morph_gpu_set_cells(m2, &moved, &co));
  t_must("get", sessile_morph_gpu_get_phi(m2, gpu2));
  same = 1;
  for (int k = 0; k < n * nm; k++) same &= gpu2[k] == (fp32 ? (double)(float)phi[k] : phi[k]);
  t_true("set_phi then set_cells: the amounts set survive", same);
  moved.ncells = n - 1;
  t_true("move_cells refuses another cell count",
         sessile_morph_gpu_move_cells(m2, &moved, &co) == SESSILE_ERR_USAGE);
  sessile_morph_gpu_destroy(m2);
  free(pos0), free(rad0), free(pos1), free(rad1);
  sessile_morph_gpu_destroy(m);
  free(phi), free(src), free(ref), free(tmp), free(gpu), free(gpu2);
  lattice_free(&L);
  return t_finish(g);
}
