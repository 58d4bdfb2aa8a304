/* The venation's nearest-node search: the GPU kernel (shaders/coral/nearest.comp)
 * and the host grid search against brute force, index for index and squared
 * distance for squared distance (exact: fp64, the same operations), on random
 * clouds, exact ties (duplicate nodes, points equidistant from lattice nodes:
 * the lowest index wins), grids with mostly empty cells, points far outside
 * the grid, a flat (one cell thick) cloud and a single node.  The two
 * clusters (10 000 nodes in a cell) make the kernel stop and resume across
 * passes (its per-pass loop budget: shaders/coral/kernels.def).  Also the
 * closed venation's relative-neighbourhood kernel against its definition. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "sessile/rng.h"
#include "sessile/coral/venation.h"
#include "testutil.h"

static uint64_t compare(sessile_gpu *g, sessile_venation_gpu *vg, const char *what, const double *nodes, uint32_t n,
                    const double *pts, uint32_t m) {
  uint32_t *ib = t_xalloc((size_t)m * 4), *ih = t_xalloc((size_t)m * 4), *ig = t_xalloc((size_t)m * 4);
  double *db = t_dalloc(m), *dh = t_dalloc(m), *dg = t_dalloc(m);
  sessile_venation_grid grid;
  t_must("grid", sessile_venation_grid_build(nodes, n, &grid));
  sessile_venation_nearest_ref(nodes, n, pts, m, ib, db);
  sessile_venation_nearest_grid(&grid, nodes, pts, m, ih, dh);
  t_ok("gpu search", sessile_venation_gpu_nearest(vg, &grid, nodes, pts, m, ig, dg, NULL));
  uint32_t bad_h = 0, bad_g = 0;
  for (uint32_t i = 0; i < m; i++) {
    bad_h += ih[i] != ib[i] || dh[i] != db[i];
    bad_g += ig[i] != ib[i] || dg[i] != db[i];
  }
  char msg[256];
  snprintf(msg, sizeof msg, "%s (%u nodes, %u points, %ux%ux%u cells): host grid = brute force (mismatches)", what,
           n, m, grid.dims[0], grid.dims[1], grid.dims[2]);
  t_check(msg, bad_h, 0);
  snprintf(msg, sizeof msg, "%s: gpu (%llu passes) = brute force, index and squared distance (mismatches)", what,
           (unsigned long long)sessile_venation_gpu_passes(vg));
  t_check(msg, bad_g, 0);
  (void)g;
  sessile_venation_grid_free(&grid);
  free(ib), free(ih), free(ig), free(db), free(dh), free(dg);
  return sessile_venation_gpu_passes(vg);
}

typedef struct ent {
  double d2;
  uint32_t j;
} ent;
static int ent_cmp(const void *x, const void *y) {
  const ent *a = x, *b = y;
  return a->d2 < b->d2 ? -1 : a->d2 > b->d2 ? 1 : a->j < b->j ? -1 : a->j > b->j;
}

/* The relative-neighbourhood kernel against the definition, pair by pair:
 * candidate v of auxin s is blocked iff some candidate u of s has
 * |u - s|^2 < |v - s|^2 and |u - v|^2 < |v - s|^2.  Nodes on a lattice (exact
 * ties in both distances), every third auxin's list marked for the host. */
static void check_rn(sessile_venation_gpu *vg, uint64_t *r) {
  enum { NN = 4096, NA = 200, R = 4 };
  double *nodes = t_dalloc(3 * NN);
  for (int i = 0; i < NN; i++)
    for (int a = 0; a < 3; a++) nodes[3 * i + a] = (double)(sessile_rng_next(r) % 16);
  ent *e = t_xalloc((size_t)NA * NN * sizeof *e);
  uint32_t *off = t_xalloc((NA + 1) * sizeof *off), total = 0;
  double *aux = t_dalloc(3 * NA);
  for (int s = 0; s < NA; s++) {
    for (int a = 0; a < 3; a++) aux[3 * s + a] = 0.5 * (double)(sessile_rng_next(r) % 32);
    off[s] = total;
    for (uint32_t j = 0; j < NN; j++) {
      double dx = aux[3 * s] - nodes[3 * j], dy = aux[3 * s + 1] - nodes[3 * j + 1], dz = aux[3 * s + 2] - nodes[3 * j + 2];
      double d = dx * dx + dy * dy + dz * dz;
      if (d <= R * R) e[total++] = (ent){d, j};
    }
    qsort(e + off[s], total - off[s], sizeof *e, ent_cmp);
  }
  off[NA] = total;
  uint32_t *j = t_xalloc((size_t)total * 4), *start = t_xalloc((size_t)total * 4), *blk = t_xalloc((size_t)total * 4);
  double *d2 = t_dalloc(total);
  for (int s = 0; s < NA; s++)
    for (uint32_t k = off[s]; k < off[s + 1]; k++)
      j[k] = e[k].j, d2[k] = e[k].d2, start[k] = s % 3 == 2 ? SESSILE_VENATION_NONE : off[s];
  t_ok("gpu relative neighbourhood", sessile_venation_gpu_rn(vg, nodes, NN, j, d2, start, total, blk));
  uint32_t bad = 0, members = 0, checked = 0;
  for (int s = 0; s < NA; s++) {
    if (s % 3 == 2) continue;
    for (uint32_t k = off[s]; k < off[s + 1]; k++) {
      uint32_t want = 0;
      for (uint32_t u = off[s]; u < off[s + 1] && !want; u++) {
        const double *pu = nodes + 3 * e[u].j, *pv = nodes + 3 * e[k].j;
        double dx = pu[0] - pv[0], dy = pu[1] - pv[1], dz = pu[2] - pv[2];
        want = e[u].d2 < e[k].d2 && dx * dx + dy * dy + dz * dz < e[k].d2;
      }
      bad += blk[k] != want, members += !want, checked++;
    }
  }
  char msg[200];
  snprintf(msg, sizeof msg, "relative neighbourhood: gpu = the definition on %u entries (%u members, lattice ties; mismatches)",
           checked, members);
  t_check(msg, bad, 0);
  t_true("... both blocked and free candidates occur", members > 0 && members < checked);
  free(nodes), free(e), free(off), free(aux), free(j), free(start), free(blk), free(d2);
}

int main(void) {
  sessile_gpu *g = t_gpu(64);
  sessile_venation_gpu *vg = NULL;
  t_must("create the search", sessile_venation_gpu_create(g, &vg));
  uint64_t r = sessile_rng_stream(3, 9);
  enum { N = 20000, M = 2000 };
  double *nodes = t_dalloc(3 * N), *pts = t_dalloc(3 * M);

  /* uniform cloud; points over a box twice as large (outside the grid too) */
  for (int i = 0; i < 3 * N; i++) nodes[i] = sessile_rng_range(&r, 0, 10);
  for (int i = 0; i < 3 * M; i++) pts[i] = sessile_rng_range(&r, -5, 15);
  compare(g, vg, "uniform cloud", nodes, N, pts, M);

  /* two tight clusters far apart: almost every cell empty */
  for (int i = 0; i < N; i++)
    for (int a = 0; a < 3; a++) nodes[3 * i + a] = (i % 2 ? 100 : 0) + sessile_rng_range(&r, 0, 1);
  for (int i = 0; i < 3 * M; i++) pts[i] = sessile_rng_range(&r, -10, 110);
  t_true("two clusters: the search resumed across passes (mid-cell, mid-ring)",
         compare(g, vg, "two clusters (empty cells)", nodes, N, pts, M) > 1);

  /* exact ties: a 10^3 lattice stored twice (duplicates at i and i + 1000),
   * points at lattice nodes, mid-edges, mid-faces and cell centres */
  uint32_t nl = 0;
  for (int copy = 0; copy < 2; copy++)
    for (int z = 0; z < 10; z++)
      for (int y = 0; y < 10; y++)
        for (int x = 0; x < 10; x++, nl++) nodes[3 * nl] = x, nodes[3 * nl + 1] = y, nodes[3 * nl + 2] = z;
  for (int i = 0; i < M; i++)
    for (int a = 0; a < 3; a++) pts[3 * i + a] = 0.5 * (double)(sessile_rng_next(&r) % 22) - 1;
  compare(g, vg, "lattice with duplicates (ties: lowest index)", nodes, nl, pts, M);

  /* flat: all y = 0 (a planar blade) */
  for (int i = 0; i < N; i++)
    nodes[3 * i] = sessile_rng_range(&r, -5, 5), nodes[3 * i + 1] = 0, nodes[3 * i + 2] = sessile_rng_range(&r, 0, 10);
  for (int i = 0; i < M; i++)
    pts[3 * i] = sessile_rng_range(&r, -6, 6), pts[3 * i + 1] = 0, pts[3 * i + 2] = sessile_rng_range(&r, -1, 11);
  compare(g, vg, "flat cloud", nodes, N, pts, M);

  /* one node */
  nodes[0] = 1, nodes[1] = 2, nodes[2] = 3;
  compare(g, vg, "one node", nodes, 1, pts, M);

  check_rn(vg, &r);

  /* m = 0 is a no-op */
  t_ok("no points", sessile_venation_gpu_nearest(vg, NULL, nodes, pts, 0, NULL, NULL, NULL));
  free(nodes), free(pts);
  sessile_venation_gpu_destroy(vg);
  return t_finish(g);
}
