/* Point location in unstructured tet meshes (sessile/mesh/locate.h):
 * - on the structured box as a general mesh, the host query interpolates as
 *   sessile_box_interpolate (an independent locator) to 1e-12;
 * - on TetGen's conforming mesh of the box minus a dome, the binned host
 *   query agrees with a brute-force scan of all tets (same tet, or the same
 *   interpolated value to 1e-12; outside exactly where brute force finds no
 *   tet: inside the sponge, outside the box), and reproduces a linear field
 *   exactly (1e-12);
 * - the GPU kernel returns the host query's tets and values (fp64: 1e-12;
 *   with --fp32: values to 1e-4 where both find a tet). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "mesh/locate_internal.h"
#include "sessile/mesh/locate.h"
#include "sessile/mesh/tetgen.h"
#include "testutil.h"

static uint64_t rng = 0x9E3779B97F4A7C15ull;
static double urand(void) {
  rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
  return (double)(rng >> 11) / 9007199254740992.0;
}
static double fnl(const double *p) { return sin(p[0]) + cos(0.7 * p[1]) * p[2] + 0.1 * p[0] * p[1]; }
static double flin(const double *p) { return 1.0 + 2.0 * p[0] - 0.5 * p[1] + 0.25 * p[2]; }

static uint32_t brute(const sessile_tetmesh *m, const double p[3], double w[4]) {
  for (uint32_t t = 0; t < m->ntets; t++) {
    const uint32_t *v = m->tet + 4 * t;
    locate_weights(m->xyz + 3 * v[0], m->xyz + 3 * v[1], m->xyz + 3 * v[2], m->xyz + 3 * v[3], p, w);
    if (w[0] >= -SESSILE_LOCATE_EPS && w[1] >= -SESSILE_LOCATE_EPS && w[2] >= -SESSILE_LOCATE_EPS &&
        w[3] >= -SESSILE_LOCATE_EPS)
      return t;
  }
  return SESSILE_LOCATE_OUTSIDE;
}

int main(int argc, char **argv) {
  int fp32 = argc > 1 && !strcmp(argv[1], "--fp32");
  /* 1. the structured box against sessile_box_interpolate */
  const double origin[3] = {-1.0, 0.5, 0.0};
  const uint32_t cells[3] = {10, 10, 8};
  sessile_box box;
  t_ok("box", sessile_box_make(origin, 1.2, cells, 1, &box));
  double mx[3];
  sessile_box_max(&box, mx);
  sessile_tetmesh bm = {0};
  t_ok("box as tet mesh", sessile_tetmesh_from_box(&box, &bm));
  sessile_locator *bl = NULL;
  t_ok("locator on the box mesh", sessile_locator_build(&bm, 0, &bl));
  double *bf = malloc(bm.nnodes * sizeof *bf);
  for (uint32_t i = 0; i < bm.nnodes; i++) bf[i] = fnl(bm.xyz + 3 * i);
  double err = 0;
  int outside = 0;
  for (int i = 0; i < 20000; i++) {
    double p[3];
    for (int k = 0; k < 3; k++) p[k] = origin[k] + urand() * (mx[k] - origin[k]);
    double a = sessile_locator_interpolate(bl, bf, p, NAN), b = sessile_box_interpolate(&box, bf, p);
    if (isnan(a)) outside++;
    else err = fmax(err, fabs(a - b));
  }
  t_true("box mesh: every point in the box found", outside == 0);
  t_check("box mesh: interpolated values equal sessile_box_interpolate's", err, 1e-12);
  sessile_locator_destroy(bl);
  free(bf);
  sessile_tetmesh_free(&bm);

  /* 2. the conforming mesh of the box minus a dome */
  double c[3] = {(origin[0] + mx[0]) / 2, (origin[1] + mx[1]) / 2, origin[2]};
  sessile_surface s = {0};
  t_ok("icosphere", sessile_surface_icosphere(3, 3.0, c, &s));
  for (uint32_t v = 0; v < s.nv; v++)
    if (s.pos[3 * v + 2] < origin[2]) s.pos[3 * v + 2] = origin[2];
  sessile_tetmesh m = {0};
  t_ok("conforming mesh", sessile_tetgen_conforming(&box, &s, NULL, &m));
  sessile_locator *l = NULL;
  t_ok("locator", sessile_locator_build(&m, 0, &l));
  sessile_locator_grid g;
  sessile_locator_grid_of(l, &g);
  printf("mesh %u nodes, %u tets; bins %u x %u x %u, %.2f tets per bin (max %u)\n", m.nnodes, m.ntets,
         g.dims[0], g.dims[1], g.dims[2], g.mean_per_bin, g.max_per_bin);
  double *f = malloc(m.nnodes * sizeof *f), *fl = malloc(m.nnodes * sizeof *fl), fmaxabs = 0;
  for (uint32_t i = 0; i < m.nnodes; i++) {
    f[i] = fnl(m.xyz + 3 * i), fl[i] = flin(m.xyz + 3 * i);
    fmaxabs = fmax(fmaxabs, fabs(f[i]));
  }
  enum { N = 20000 };
  double *pts = malloc(3 * N * sizeof *pts), *host_val = malloc(N * sizeof *host_val);
  uint32_t *host_tet = malloc(N * sizeof *host_tet);
  int mismatch_out = 0, same_tet = 0, in_sponge = 0, in_sponge_found = 0, beyond = 0, beyond_found = 0;
  double verr = 0, lerr = 0;
  for (int i = 0; i < N; i++) {
    double *p = pts + 3 * i;
    /* the box widened by 10% on every side: some points lie beyond it */
    for (int k = 0; k < 3; k++) p[k] = origin[k] + (urand() * 1.2 - 0.1) * (mx[k] - origin[k]);
    /* every 8th point on a mesh node or a tet centroid (on faces and edges) */
    if (i % 16 == 1) memcpy(p, m.xyz + 3 * (size_t)(urand() * m.nnodes), 3 * sizeof *p);
    double w[4], wb[4];
    uint32_t t = sessile_locator_find(l, p, w), tb = brute(&m, p, wb);
    host_tet[i] = t;
    host_val[i] = sessile_locator_interpolate(l, f, p, -7.0);
    double r = sqrt((p[0] - c[0]) * (p[0] - c[0]) + (p[1] - c[1]) * (p[1] - c[1]) + (p[2] - c[2]) * (p[2] - c[2]));
    int out_box = 0;
    for (int k = 0; k < 3; k++) out_box |= p[k] < origin[k] - 1e-9 || p[k] > mx[k] + 1e-9;
    if (out_box) beyond++, beyond_found += t != SESSILE_LOCATE_OUTSIDE;
    else if (r < 2.5 && p[2] > origin[2]) in_sponge++, in_sponge_found += t != SESSILE_LOCATE_OUTSIDE;
    if ((t == SESSILE_LOCATE_OUTSIDE) != (tb == SESSILE_LOCATE_OUTSIDE)) {
      mismatch_out++;
      continue;
    }
    if (t == SESSILE_LOCATE_OUTSIDE) continue;
    same_tet += t == tb;
    const uint32_t *v = m.tet + 4 * tb;
    double vb = wb[0] * f[v[0]] + wb[1] * f[v[1]] + wb[2] * f[v[2]] + wb[3] * f[v[3]];
    verr = fmax(verr, fabs(host_val[i] - vb) / fmaxabs);
    lerr = fmax(lerr, fabs(sessile_locator_interpolate(l, fl, p, 0) - flin(p)));
  }
  printf("%d points: %d beyond the box, %d inside the dome, %d in the same tet as brute force\n", N, beyond,
         in_sponge, same_tet);
  t_true("host query and brute force agree on inside / outside", mismatch_out == 0);
  t_true("points beyond the box are outside", beyond > 0 && beyond_found == 0);
  t_true("points inside the sponge are outside", in_sponge > 0 && in_sponge_found == 0);
  t_check("host query vs brute force: interpolated value (relative to max |f|)", verr, 1e-12);
  t_check("linear field reproduced exactly (P1)", lerr, 1e-12);

  /* 3. the GPU kernel against the host query */
  sessile_gpu *gpu = t_gpu(fp32 ? 32 : 0);
  int f64 = sessile_gpu_info_of(gpu)->precision == 64;
  size_t rb = f64 ? 8 : 4;
  sessile_locate_gpu *lg = NULL;
  sessile_buffer *bp = NULL, *bfld = NULL, *bv = NULL, *bt = NULL;
  sessile_cmd *cmd = NULL;
  t_ok("GPU locator", sessile_locate_gpu_create(gpu, l, &lg));
  t_ok("points", sessile_buffer_create(gpu, 3 * N * rb, SESSILE_BUFFER_MAPPED, &bp));
  t_ok("field", sessile_buffer_create(gpu, m.nnodes * rb, SESSILE_BUFFER_MAPPED, &bfld));
  t_ok("values", sessile_buffer_create(gpu, N * rb, SESSILE_BUFFER_MAPPED, &bv));
  t_ok("tets", sessile_buffer_create(gpu, N * 4, SESSILE_BUFFER_MAPPED, &bt));
  if (bp && bfld && bv && bt && lg) {
    void *hp = sessile_buffer_host_ptr(bp), *hf = sessile_buffer_host_ptr(bfld);
    for (size_t i = 0; i < 3 * (size_t)N; i++)
      if (f64) ((double *)hp)[i] = pts[i];
      else ((float *)hp)[i] = (float)pts[i];
    for (uint32_t i = 0; i < m.nnodes; i++)
      if (f64) ((double *)hf)[i] = f[i];
      else ((float *)hf)[i] = (float)f[i];
    t_ok("cmd", sessile_cmd_create(gpu, &cmd));
    t_ok("begin", sessile_cmd_begin(cmd));
    t_ok("record", sessile_locate_gpu_record(lg, cmd, bp, N, bfld, bv, bt, -7.0));
    t_ok("end", sessile_cmd_end(cmd));
    double t0 = sessile_wall_seconds();
    t_ok("run", sessile_cmd_submit_wait(cmd));
    printf("GPU locate of %d points: %.1f ms (%s)\n", N, 1e3 * (sessile_wall_seconds() - t0), f64 ? "fp64" : "fp32");
    const uint32_t *gt = sessile_buffer_host_ptr(bt);
    const void *gv = sessile_buffer_host_ptr(bv);
    int tet_diff = 0, out_diff = 0;
    double gerr = 0;
    for (int i = 0; i < N; i++) {
      double v = f64 ? ((const double *)gv)[i] : ((const float *)gv)[i];
      int ho = host_tet[i] == SESSILE_LOCATE_OUTSIDE, go = gt[i] == SESSILE_LOCATE_OUTSIDE;
      tet_diff += gt[i] != host_tet[i];
      if (ho != go) {
        out_diff++;
        continue;
      }
      gerr = fmax(gerr, fabs(v - host_val[i]) / fmaxabs);
    }
    printf("GPU vs host: %d of %d tets differ, %d inside/outside differ\n", tet_diff, N, out_diff);
    if (f64) {
      t_true("GPU (fp64) finds the host query's tet for every point", tet_diff == 0);
      t_check("GPU (fp64) interpolated values vs host (relative to max |f|)", gerr, 1e-12);
    } else {
      t_true("GPU (fp32) agrees on inside/outside for >= 99.5% of the points", out_diff <= N / 200);
      t_check("GPU (fp32) interpolated values vs host where both find a tet", gerr, 1e-4);
    }
  }
  sessile_cmd_destroy(cmd);
  sessile_buffer_destroy(bp);
  sessile_buffer_destroy(bfld);
  sessile_buffer_destroy(bv);
  sessile_buffer_destroy(bt);
  sessile_locate_gpu_destroy(lg);
  sessile_locator_destroy(l);
  sessile_tetmesh_free(&m);
  sessile_surface_free(&s);
  free(f), free(fl), free(pts), free(host_val), free(host_tet);
  return t_finish(gpu);
}
