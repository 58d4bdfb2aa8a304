/* The welded surface's plain-C reference (OpenMP): the same grid, brick
 * lists, node values and row passes as the GPU path (weld.c), so the two
 * give the same mesh; the test oracle and the benchmark's baseline. */
#include <stdlib.h>
#include <string.h>
#include "weld_internal.h"

sessile_status sessile_skeleton_weld_ref(const sessile_skeleton *s, const sessile_weld_params *p,
                                         sessile_surface *out, double **vertex_value) {
  if (vertex_value) *vertex_value = NULL;
  weld_grid g;
  double bytes;
  SESSILE_CALL(weld_grid_plan(s, p, &g, &bytes));
  if (s->n == 0) return weld_output(s, 0, 0, NULL, NULL, NULL, out, vertex_value);
  sessile_status st = weld_grid_lists(s, &g);
  size_t nodes = (size_t)g.nodes;
  uint32_t nrows = g.n[1] * g.n[2], nv = 0, nf = 0;
  double *field = NULL;
  uint32_t *packed = NULL, *vbase = NULL, *rows = NULL, *tri = NULL, *nearest = NULL;
  double *pos = NULL;
  if (st == SESSILE_OK) {
    field = malloc(nodes * sizeof *field);
    packed = malloc(nodes * sizeof *packed);
    vbase = malloc(nodes * sizeof *vbase);
    rows = malloc((size_t)nrows * 2 * sizeof *rows);
    if (!field || !packed || !vbase || !rows) st = weld_refuse(&g, bytes, bytes, "host memory (allocation failed)");
  }
  if (st == SESSILE_OK) {
    int64_t nn = (int64_t)nodes;
#pragma omp parallel for schedule(dynamic, 4096)
    for (int64_t i = 0; i < nn; i++) {
      uint32_t x = (uint32_t)(i % g.n[0]), y = (uint32_t)(i / g.n[0] % g.n[1]), z = (uint32_t)(i / g.n[0] / g.n[1]);
      field[i] = weld_node_value(&g, x, y, z);
    }
#pragma omp parallel for schedule(dynamic, 64)
    for (int64_t r = 0; r < (int64_t)nrows; r++) weld_count_row(&g, field, (uint32_t)r, packed, rows + 2 * r);
    st = weld_scan_rows(rows, nrows, &nv, &nf);
  }
  if (st == SESSILE_OK) {
    pos = malloc(((size_t)nv * 3 + 1) * sizeof *pos);
    nearest = malloc(((size_t)nv + 1) * sizeof *nearest);
    tri = malloc(((size_t)nf * 3 + 1) * sizeof *tri);
    if (!pos || !nearest || !tri)
      st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "welded surface: out of host memory for %u vertices", nv);
  }
  if (st == SESSILE_OK) {
#pragma omp parallel for schedule(dynamic, 64)
    for (int64_t r = 0; r < (int64_t)nrows; r++)
      weld_vert_row(&g, field, packed, (uint32_t)r, rows[2 * r], vbase, pos, nearest);
#pragma omp parallel for schedule(dynamic, 64)
    for (int64_t r = 0; r < (int64_t)nrows; r++) weld_tri_row(&g, packed, vbase, (uint32_t)r, rows[2 * r + 1], tri);
    st = weld_output(s, nv, nf, pos, tri, nearest, out, vertex_value);
    if (st == SESSILE_OK) pos = NULL, tri = NULL; /* owned by out now */
  }
  free(field), free(packed), free(vbase), free(rows), free(pos), free(tri), free(nearest);
  weld_grid_free(&g);
  return st;
}
