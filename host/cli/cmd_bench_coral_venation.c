/* `sessile bench coral venation`: one nearest-node pass, 10 k auxins among
 * 100 k vein nodes (--quick: 1 k among 10 k), on the device and by the two
 * plain-C references (brute force, the host grid search) in the same run,
 * with the ratios; the answers are compared too. */
#include <math.h>
#include <stdlib.h>
#include "cli.h"
#include "sessile/rng.h"
#include "sessile/coral/venation.h"

/* A vein-like cloud: random walks from the origin (nodes step 0.2 cm apart),
 * and auxins uniform in the walks' bounds. */
static void clouds(uint32_t n, uint32_t m, double *nodes, double *pts) {
  uint64_t r = sessile_rng_stream(7, 1);
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (uint32_t i = 0; i < n; i++) {
    double *q = nodes + 3 * i;
    if (i % 200 == 0) {
      q[0] = q[1] = q[2] = 0;
    } else {
      double d[3] = {sessile_rng_normal(&r), sessile_rng_normal(&r), sessile_rng_normal(&r) + 0.5};
      double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (int a = 0; a < 3; a++) q[a] = q[a - 3] + 0.2 * d[a] / l;
    }
    for (int a = 0; a < 3; a++) lo[a] = fmin(lo[a], q[a]), hi[a] = fmax(hi[a], q[a]);
  }
  for (uint32_t i = 0; i < 3 * m; i++) pts[i] = sessile_rng_range(&r, lo[i % 3], hi[i % 3]);
}

sessile_status bench_coral_venation(sessile_gpu *g, const bench_section_opts *o, FILE *out) {
  uint32_t n = o->quick ? 10000 : 100000, m = o->quick ? 1000 : 10000;
  double *nodes = malloc((size_t)3 * n * sizeof *nodes), *pts = malloc((size_t)3 * m * sizeof *pts);
  uint32_t *ig = malloc((size_t)m * sizeof *ig), *ih = malloc((size_t)m * sizeof *ih), *ib = malloc((size_t)m * 4);
  sessile_venation_grid grid = {0};
  sessile_venation_gpu *vg = NULL;
  sessile_status s = nodes && pts && ig && ih && ib ? SESSILE_OK
                                                    : sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (s == SESSILE_OK) {
    clouds(n, m, nodes, pts);
    s = sessile_venation_grid_build(nodes, n, &grid);
  }
  if (s == SESSILE_OK) s = sessile_venation_gpu_create(g, &vg);
  double t_gpu = INFINITY, t_kernel = INFINITY, t_grid = INFINITY, t_brute = 0;
  /* best of 3 (the first GPU call also makes its buffers) */
  for (int rep = 0; rep < 3 && s == SESSILE_OK; rep++) {
    double k = 0, t0 = sessile_wall_seconds();
    s = sessile_venation_gpu_nearest(vg, &grid, nodes, pts, m, ig, NULL, &k);
    double t1 = sessile_wall_seconds();
    sessile_venation_nearest_grid(&grid, nodes, pts, m, ih, NULL);
    double t2 = sessile_wall_seconds();
    t_gpu = fmin(t_gpu, t1 - t0), t_kernel = fmin(t_kernel, k * 1e-9), t_grid = fmin(t_grid, t2 - t1);
  }
  if (s == SESSILE_OK) {
    double t0 = sessile_wall_seconds();
    sessile_venation_nearest_ref(nodes, n, pts, m, ib, NULL);
    t_brute = sessile_wall_seconds() - t0;
    uint32_t diff_g = 0, diff_h = 0;
    for (uint32_t i = 0; i < m; i++) diff_g += ig[i] != ib[i], diff_h += ih[i] != ib[i];
    fprintf(out,
            "venation nearest node: %u auxins, %u vein nodes, grid %ux%ux%u cells of %.3g cm (device: %s)\n"
            "  gpu (upload+kernel+download) %.4f s, kernel %.4f s in %llu passes\n"
            "  host grid search (OpenMP)    %.4f s   gpu speed-up x%.2f (kernel x%.2f)\n"
            "  host brute force             %.4f s   gpu speed-up x%.1f (kernel x%.1f)\n"
            "  answers differing from brute force: gpu %u, host grid %u\n",
            m, n, grid.dims[0], grid.dims[1], grid.dims[2], grid.h, sessile_gpu_info_of(g)->name, t_gpu, t_kernel,
            (unsigned long long)sessile_venation_gpu_passes(vg),
            t_grid, t_grid / t_gpu, t_grid / t_kernel, t_brute, t_brute / t_gpu, t_brute / t_kernel, diff_g, diff_h);
    if (diff_g || diff_h)
      s = sessile_error_set(SESSILE_ERR_INTERNAL, "the nearest-node searches disagree with brute force");
  }
  sessile_venation_gpu_destroy(vg);
  sessile_venation_grid_free(&grid);
  free(nodes), free(pts), free(ig), free(ih), free(ib);
  return s;
}
