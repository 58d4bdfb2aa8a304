/* Solid classification on the GPU: the host bins triangles by box column
 * (O(T), classify_ref.c), the kernel does one column per invocation. */
#include <stdlib.h>
#include <string.h>
#include "growth_internal.h"

sessile_status sessile_growth_gpu_classify(sessile_growth_gpu *g, const sessile_box *box,
                                           sessile_buffer *solid) {
  SESSILE_CHECK(g->nv > 0, SESSILE_ERR_USAGE, "classify: no surface uploaded (call set_surface)");
  size_t nodes = sessile_box_nodes(box);
  SESSILE_CHECK(sessile_buffer_size(solid) >= nodes * 4, SESSILE_ERR_USAGE,
                "classify: the solid mask buffer holds %zu bytes, the box needs %zu",
                sessile_buffer_size(solid), nodes * 4);
  double t0 = sessile_wall_seconds();
  /* The bins need the host positions: the uploaded ones may be rounded to
   * float, so bin from a download to see exactly what the kernel sees. */
  sessile_surface s = {0};
  uint32_t *off = NULL, *list = NULL;
  sessile_status st = sessile_surface_reserve(&s, g->nv, g->nf);
  if (st == SESSILE_OK) {
    s.nv = g->nv;
    s.nf = g->nf;
    st = sessile_buffer_download_reals(g->pos, 0, s.pos, 3 * (size_t)g->nv);
  }
  if (st == SESSILE_OK) st = sessile_buffer_download(g->tri, 0, s.tri, (size_t)g->nf * 12);
  if (st == SESSILE_OK) st = sessile_growth_bin_columns(box, &s, &off, &list);
  size_t ncol = (size_t)box->n[0] * box->n[1];
  if (st == SESSILE_OK) {
    size_t entries = off[ncol];
    st = growth_ensure(g, &g->col_off, &g->col_off_bytes, (ncol + 1) * 4);
    if (st == SESSILE_OK) st = growth_ensure(g, &g->col_tri, &g->col_tri_bytes, entries * 4);
    if (st == SESSILE_OK) st = sessile_buffer_upload(g->col_off, 0, off, (ncol + 1) * 4);
    if (st == SESSILE_OK && entries) st = sessile_buffer_upload(g->col_tri, 0, list, entries * 4);
  }
  free(off), free(list);
  sessile_surface_free(&s);
  SESSILE_CALL(st);

  growth_set_params(g, box, NULL);
  memset(sessile_buffer_host_ptr(g->status), 0, 16);
  growth_push p = growth_push_of(g, box);
  sessile_buffer *b[7] = {g->params, g->pos, g->tri, g->col_off, g->col_tri, solid, g->status};
  SESSILE_CALL(sessile_cmd_begin(g->cmd));
  SESSILE_CALL(sessile_cmd_dispatch(g->cmd, g->k[GK_CLASSIFY], growth_groups(p.ncols), b, &p));
  SESSILE_CALL(sessile_cmd_end(g->cmd));
  SESSILE_CALL(sessile_cmd_submit_wait(g->cmd));
  g->classify_seconds = sessile_wall_seconds() - t0;
  uint32_t bad = ((volatile uint32_t *)sessile_buffer_host_ptr(g->status))[0];
  SESSILE_CHECK(bad == 0, SESSILE_ERR_NUMERIC,
                "the vertical line through box column (%u, %u) crosses the sponge surface more "
                "than %d times; the surface is too folded for solid classification",
                (bad - 1) % box->n[0], (bad - 1) / box->n[0], SESSILE_GROWTH_MAX_CROSSINGS);
  return SESSILE_OK;
}

double sessile_growth_gpu_classify_seconds(const sessile_growth_gpu *g) { return g->classify_seconds; }
