/* Solid classification and cut cells on the GPU: the host bins triangles by
 * box line (O(T), classify_ref.c), the kernel does one line per invocation:
 * along z for the solid mask, along x, y and z for the cut fractions. */
#include <stdlib.h>
#include <string.h>
#include "growth_internal.h"

/* The surface exactly as the kernels see it (the uploaded positions may be
 * rounded to float), for binning. */
static sessile_status download_surface(sessile_growth_gpu *g, sessile_surface *s) {
  SESSILE_CALL(sessile_surface_reserve(s, g->nv, g->nf));
  s->nv = g->nv;
  s->nf = g->nf;
  SESSILE_CALL(sessile_buffer_download_reals(g->pos, 0, s->pos, 3 * (size_t)g->nv));
  return sessile_buffer_download(g->tri, 0, s->tri, (size_t)g->nf * 12);
}

/* Uploads the bins of `axis` into the buffers of that axis. */
static sessile_status upload_bins(sessile_growth_gpu *g, const sessile_box *box,
                                  const sessile_surface *s, int axis) {
  uint32_t *off = NULL, *list = NULL;
  SESSILE_CALL(sessile_growth_bin_lines(box, s, axis, &off, &list));
  int u = (axis + 1) % 3, v = (axis + 2) % 3;
  size_t nl = (size_t)box->n[u] * box->n[v], entries = off[nl];
  sessile_status st = growth_ensure(g, &g->col_off[axis], (nl + 1) * 4);
  if (st == SESSILE_OK) st = growth_ensure(g, &g->col_tri[axis], entries * 4);
  if (st == SESSILE_OK) st = sessile_buffer_upload(g->col_off[axis], 0, off, (nl + 1) * 4);
  if (st == SESSILE_OK && entries) st = sessile_buffer_upload(g->col_tri[axis], 0, list, entries * 4);
  free(off), free(list);
  return st;
}

static sessile_status cut(sessile_growth_gpu *g, const sessile_box *box, sessile_buffer *solid,
                          sessile_buffer *theta) {
  SESSILE_CHECK(g->nv > 0, SESSILE_ERR_USAGE, "classify: no surface uploaded (call set_surface)");
  size_t nodes = sessile_box_nodes(box);
  SESSILE_CHECK(solid && sessile_buffer_size(solid) >= nodes * 4, SESSILE_ERR_USAGE,
                "classify: the solid mask buffer holds %zu bytes, the box needs %zu",
                solid ? sessile_buffer_size(solid) : (size_t)0, nodes * 4);
  SESSILE_CHECK(!theta || sessile_buffer_size(theta) >= nodes * 6 * g->real_bytes, SESSILE_ERR_USAGE,
                "cut cells: the fraction buffer holds %zu bytes, the box needs %zu",
                theta ? sessile_buffer_size(theta) : (size_t)0, nodes * 6 * g->real_bytes);
  double t0 = sessile_wall_seconds();
  int first = theta ? 0 : 2;
  sessile_surface s = {0};
  sessile_status st = download_surface(g, &s);
  for (int a = first; a < 3 && st == SESSILE_OK; a++) st = upload_bins(g, box, &s, a);
  sessile_surface_free(&s);
  SESSILE_CALL(st);
  if (!theta) SESSILE_CALL(growth_ensure(g, &g->theta_dummy, 16));

  growth_set_params(g, box, NULL);
  memset(sessile_buffer_host_ptr(g->status), 0, 16);
  SESSILE_CALL(sessile_cmd_begin(g->cmd));
  for (int a = first; a < 3; a++) {
    growth_push p = growth_push_of(g, box);
    int u = (a + 1) % 3, v = (a + 2) % 3;
    p.ncols = box->n[u] * box->n[v];
    p.axis = (uint32_t)a;
    p.want_theta = theta != NULL;
    sessile_buffer *b[8] = {g->params, g->pos,   g->tri,    g->col_off[a],
                            g->col_tri[a], solid, g->status, theta ? theta : g->theta_dummy};
    SESSILE_CALL(sessile_cmd_dispatch(g->cmd, g->k[GK_CLASSIFY], growth_groups(p.ncols), b, &p));
  }
  SESSILE_CALL(sessile_cmd_end(g->cmd));
  SESSILE_CALL(sessile_cmd_submit_wait(g->cmd));
  g->classify_seconds = sessile_wall_seconds() - t0;
  const volatile uint32_t *bad = sessile_buffer_host_ptr(g->status);
  for (int a = first; a < 3; a++) {
    static const char *const name[3] = {"x", "y", "z"};
    int u = (a + 1) % 3;
    SESSILE_CHECK(bad[a] == 0, SESSILE_ERR_NUMERIC,
                  "the box line along %s through node (%u, %u) crosses the sponge surface more "
                  "than %d times; the surface is too folded for solid classification",
                  name[a], (bad[a] - 1) % box->n[u], (bad[a] - 1) / box->n[u],
                  SESSILE_GROWTH_MAX_CROSSINGS);
  }
  return SESSILE_OK;
}

sessile_status sessile_growth_gpu_classify(sessile_growth_gpu *g, const sessile_box *box,
                                           sessile_buffer *solid) {
  return cut(g, box, solid, NULL);
}

sessile_status sessile_growth_gpu_cut(sessile_growth_gpu *g, const sessile_box *box,
                                      sessile_buffer *solid, sessile_buffer *theta) {
  SESSILE_CHECK(theta, SESSILE_ERR_USAGE, "cut cells: no fraction buffer given");
  return cut(g, box, solid, theta);
}

double sessile_growth_gpu_classify_seconds(const sessile_growth_gpu *g) { return g->classify_seconds; }
