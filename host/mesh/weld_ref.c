/* The welded surface's plain-C reference (OpenMP): the same grid, brick
 * lists, node values and passes as the GPU path (weld.c), so the two give
 * the same mesh; the test oracle and the benchmark's baseline. */
#include <stdlib.h>
#include <string.h>
#include "weld_internal.h"

typedef struct ref_arrays {
  double *field, *pos;
  uint32_t *nnear, *packed, *vbase, *rows, *vnode, *clist, *ctri, *tri, *nearest;
} ref_arrays;

static sessile_status run(const sessile_skeleton *s, weld_grid *g, double bytes, ref_arrays *a,
                          sessile_surface *out, double **vertex_value) {
  SESSILE_CALL(weld_grid_lists(s, g));
  size_t nodes = (size_t)g->nodes;
  int64_t nn = (int64_t)nodes, nrows = (int64_t)g->n[1] * g->n[2];
  a->field = malloc(nodes * sizeof *a->field);
  a->packed = malloc(nodes * sizeof *a->packed);
  a->nnear = malloc(nodes * sizeof *a->nnear);
  a->vbase = malloc(nodes * sizeof *a->vbase);
  a->rows = calloc((size_t)nrows * 3, sizeof *a->rows);
  if (!a->field || !a->nnear || !a->packed || !a->vbase || !a->rows) return weld_refuse(g, bytes, bytes, "host memory (allocation failed)");
#pragma omp parallel for schedule(dynamic, 4096)
  for (int64_t i = 0; i < nn; i++)
    a->field[i] = weld_node_value(g, (uint32_t)(i % g->n[0]), (uint32_t)(i / g->n[0] % g->n[1]),
                                  (uint32_t)(i / g->n[0] / g->n[1]), a->nnear + i);
#pragma omp parallel for schedule(dynamic, 4096)
  for (int64_t i = 0; i < nn; i++) a->packed[i] = weld_count_node(g, a->field, (size_t)i);
#pragma omp parallel for schedule(dynamic, 64)
  for (int64_t r = 0; r < nrows; r++)
    for (uint32_t x = 0; x < g->n[0]; x++) {
      uint32_t w = a->packed[x + (size_t)g->n[0] * r], t = (w >> WP_TRI_SHIFT) & 15u;
      a->rows[3 * r] += (uint32_t)__builtin_popcount(w & 127u), a->rows[3 * r + 1] += t, a->rows[3 * r + 2] += t != 0;
    }
  uint32_t tot[3];
  SESSILE_CALL(weld_scan_rows(a->rows, (uint32_t)nrows, tot));
  uint32_t nv = tot[0], nf = tot[1], nc = tot[2];
  a->pos = malloc(((size_t)nv * 3 + 1) * sizeof *a->pos);
  a->nearest = malloc(((size_t)nv + 1) * sizeof *a->nearest);
  a->vnode = malloc(((size_t)nv + 1) * sizeof *a->vnode);
  a->tri = malloc(((size_t)nf * 3 + 1) * sizeof *a->tri);
  a->clist = malloc(((size_t)nc + 1) * sizeof *a->clist);
  a->ctri = malloc(((size_t)nc + 1) * sizeof *a->ctri);
  SESSILE_CHECK(a->pos && a->nearest && a->vnode && a->tri && a->clist && a->ctri, SESSILE_ERR_NO_MEMORY,
                "welded surface: out of host memory for %u vertices and %u triangles", nv, nf);
#pragma omp parallel for schedule(dynamic, 64)
  for (int64_t r = 0; r < nrows; r++)
    weld_rowscan_row(g, a->packed, (uint32_t)r, a->rows + 3 * r, a->vbase, a->vnode, a->clist, a->ctri);
#pragma omp parallel for schedule(dynamic, 1024)
  for (int64_t v = 0; v < (int64_t)nv; v++)
    weld_vertex(g, a->field, a->nnear, a->packed, a->vbase, a->vnode, (uint32_t)v, a->pos, a->nearest);
#pragma omp parallel for schedule(dynamic, 1024)
  for (int64_t c = 0; c < (int64_t)nc; c++) weld_cell_tris(g, a->packed, a->vbase, a->clist[c], a->ctri[c], a->tri);
  SESSILE_CALL(weld_output(s, g->h, nv, nf, a->pos, a->tri, a->nearest, out, vertex_value));
  a->pos = NULL, a->tri = NULL; /* owned by out now */
  return SESSILE_OK;
}

sessile_status sessile_skeleton_weld_ref(const sessile_skeleton *s, const sessile_weld_params *p,
                                         sessile_surface *out, double **vertex_value) {
  if (vertex_value) *vertex_value = NULL;
  weld_grid g;
  double bytes;
  SESSILE_CALL(weld_grid_plan(s, p, &g, &bytes));
  if (s->n == 0) return weld_output(s, 0, 0, 0, NULL, NULL, NULL, out, vertex_value);
  ref_arrays a;
  memset(&a, 0, sizeof a);
  sessile_status st = run(s, &g, bytes, &a, out, vertex_value);
  free(a.field), free(a.nnear), free(a.pos), free(a.packed), free(a.vbase), free(a.rows), free(a.vnode), free(a.clist);
  free(a.ctri), free(a.tri), free(a.nearest);
  weld_grid_free(&g);
  return st;
}
