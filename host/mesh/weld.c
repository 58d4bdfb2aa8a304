/* The welded surface on the GPU (sessile/mesh/skeleton.h, docs/weld.md): the
 * host builds the grid and the brick lists (weld_grid.c); the kernels
 * shaders/mesh/weld_*.comp sample the signed distance per brick, count per
 * node into row totals, and after the host's scan of those number the rows
 * and write vertices and triangles in node order, so the mesh does not
 * depend on scheduling. */
#include <stdlib.h>
#include <string.h>
#include "weld_internal.h"

#define NK 5 /* kernels: sdf, count, rowscan, vert, tri */

typedef struct weld_dev {
  sessile_kernel *k[NK];
  sessile_buffer *cap, *boff, *blist, *field, *nnear, *packed, *rows, *vbase, *vnode, *clist, *ctri, *pos, *nearest, *tri;
  sessile_cmd *cmd;
} weld_dev;

static void weld_dev_free(weld_dev *d) {
  for (int i = 0; i < NK; i++) sessile_kernel_destroy(d->k[i]);
  sessile_buffer *b[14] = {d->cap,   d->boff,  d->blist, d->field, d->nnear,   d->packed, d->rows,
                           d->vbase, d->vnode, d->clist, d->ctri,  d->pos,     d->nearest, d->tri};
  for (int i = 0; i < 14; i++) sessile_buffer_destroy(b[i]);
  sessile_cmd_destroy(d->cmd);
}

static sessile_status buf(sessile_gpu *g, size_t bytes, sessile_buffer **b) {
  return sessile_buffer_create(g, bytes < 16 ? 16 : bytes, SESSILE_BUFFER_DEVICE, b);
}

static weld_push push_of(const weld_grid *g, uint32_t rb) {
  weld_push p = {.nx = g->n[0], .ny = g->n[1], .nz = g->n[2], .bx = g->nb[0], .by = g->nb[1], .bz = g->nb[2],
                 .brick = WELD_BRICK};
  p.lox = sessile_push_real_of(g->lo[0], rb), p.loy = sessile_push_real_of(g->lo[1], rb);
  p.loz = sessile_push_real_of(g->lo[2], rb), p.h = sessile_push_real_of(g->h, rb);
  p.clampv = sessile_push_real_of(g->clampv, rb), p.blend = sessile_push_real_of(g->blend, rb);
  p.tmin = sessile_push_real_of(WELD_TMIN, rb);
  return p;
}

static uint32_t groups(uint64_t n, const sessile_kernel *k) {
  uint32_t ls = sessile_kernel_local_size(k);
  return (uint32_t)((n + ls - 1) / ls);
}

/* Refuses what would not fit: any one array over maxStorageBufferRange, or
 * the whole above half the device's memory (it shares it with the rest). */
static sessile_status fits(const weld_grid *g, const sessile_gpu_info *in, double total, double largest,
                           const char *what) {
  double limit = 0.5 * (double)in->device_local_bytes;
  if (total > limit) return weld_refuse(g, total, limit, what);
  if (largest > (double)in->max_storage_buffer_range)
    return weld_refuse(g, largest, (double)in->max_storage_buffer_range, "one device buffer (its largest array)");
  return SESSILE_OK;
}

/* Records one dispatch and runs it (each stage is its own submission so
 * that the stages can be timed). */
static sessile_status dispatch1(weld_dev *d, int k, uint64_t n, sessile_buffer *const *b, const weld_push *pc) {
  SESSILE_CALL(sessile_cmd_begin(d->cmd));
  SESSILE_CALL(sessile_cmd_dispatch(d->cmd, d->k[k], groups(n, d->k[k]), b, pc));
  SESSILE_CALL(sessile_cmd_end(d->cmd));
  return sessile_cmd_submit_wait(d->cmd);
}

static sessile_status run(sessile_gpu *gpu, const sessile_skeleton *s, weld_grid *g, double grid_bytes,
                          weld_dev *d, sessile_surface *out, double **vertex_value, weld_times *tm) {
  const sessile_gpu_info *in = sessile_gpu_info_of(gpu);
  uint32_t rb = in->precision == 64 ? 8 : 4;
  size_t nodes = (size_t)g->nodes;
  SESSILE_CALL(fits(g, in, grid_bytes, (double)rb * (double)nodes, "device memory"));
  double t0 = sessile_wall_seconds();
  SESSILE_CALL(weld_grid_lists(s, g));
  uint32_t nb = g->nb[0] * g->nb[1] * g->nb[2], nrows = g->n[1] * g->n[2];
  size_t nlist = g->boff[nb];
  for (int i = 0; i < NK; i++)
    SESSILE_CALL(sessile_kernel_create_decl(gpu, &sessile_mesh_kernels[MK_WELD_SDF + i], rb, 0, &d->k[i]));
  for (int i = 0; i < 2; i++)
    SESSILE_CHECK(sessile_kernel_local_size(d->k[i]) == WELD_LOCAL, SESSILE_ERR_INTERNAL,
                  "welded surface: weld_sdf and weld_count need workgroups of %d (one per brick of 8^3 nodes), "
                  "the device gave %u",
                  WELD_LOCAL, sessile_kernel_local_size(d->k[i]));
  SESSILE_CALL(buf(gpu, (size_t)g->ncap * WC_STRIDE * rb, &d->cap));
  SESSILE_CALL(buf(gpu, ((size_t)nb + 1) * 4, &d->boff));
  SESSILE_CALL(buf(gpu, nlist * 4, &d->blist));
  SESSILE_CALL(buf(gpu, nodes * rb, &d->field));
  SESSILE_CALL(buf(gpu, nodes * 4, &d->nnear));
  SESSILE_CALL(buf(gpu, nodes * 4, &d->packed));
  SESSILE_CALL(buf(gpu, nodes * 4, &d->vbase));
  SESSILE_CALL(buf(gpu, (size_t)nrows * 12, &d->rows));
  SESSILE_CALL(sessile_buffer_upload_reals(d->cap, 0, g->cap, (size_t)g->ncap * WC_STRIDE));
  SESSILE_CALL(sessile_buffer_upload(d->boff, 0, g->boff, ((size_t)nb + 1) * 4));
  if (nlist) SESSILE_CALL(sessile_buffer_upload(d->blist, 0, g->blist, nlist * 4));
  SESSILE_CALL(sessile_cmd_create(gpu, &d->cmd));
  weld_push pc = push_of(g, rb);

  /* the node values; the count pass (rows start zeroed: fresh buffer) */
  double t1 = sessile_wall_seconds();
  sessile_buffer *b_sdf[5] = {d->cap, d->boff, d->blist, d->field, d->nnear};
  SESSILE_CALL(dispatch1(d, 0, (uint64_t)nb * sessile_kernel_local_size(d->k[0]), b_sdf, &pc));
  double t2 = sessile_wall_seconds();
  sessile_buffer *b_cnt[4] = {d->boff, d->field, d->packed, d->rows};
  SESSILE_CALL(dispatch1(d, 1, (uint64_t)nb * sessile_kernel_local_size(d->k[1]), b_cnt, &pc));

  /* the scan of the row totals (three per row: small) */
  uint32_t *rows = malloc((size_t)nrows * 12), tot[3] = {0, 0, 0};
  SESSILE_CHECK(rows, SESSILE_ERR_NO_MEMORY, "welded surface: out of host memory for %u rows", nrows);
  sessile_status st = sessile_buffer_download(d->rows, 0, rows, (size_t)nrows * 12);
  if (st == SESSILE_OK) st = weld_scan_rows(rows, nrows, tot);
  if (st == SESSILE_OK) st = sessile_buffer_upload(d->rows, 0, rows, (size_t)nrows * 12);
  free(rows);
  SESSILE_CALL(st);
  uint32_t nv = tot[0], nf = tot[1], nc = tot[2];
  double pos_bytes = 3.0 * nv * rb, tri_bytes = 12.0 * nf, more = pos_bytes + 8.0 * nv + tri_bytes + 8.0 * nc;
  SESSILE_CALL(fits(g, in, grid_bytes + more, pos_bytes > tri_bytes ? pos_bytes : tri_bytes,
                    "device memory (grid and surface)"));
  SESSILE_CALL(buf(gpu, (size_t)pos_bytes, &d->pos));
  SESSILE_CALL(buf(gpu, (size_t)nv * 4, &d->nearest));
  SESSILE_CALL(buf(gpu, (size_t)nv * 4, &d->vnode));
  SESSILE_CALL(buf(gpu, (size_t)tri_bytes, &d->tri));
  SESSILE_CALL(buf(gpu, (size_t)nc * 4, &d->clist));
  SESSILE_CALL(buf(gpu, (size_t)nc * 4, &d->ctri));
  double t3 = sessile_wall_seconds();

  /* numbering, then vertices and triangles, in one submission */
  SESSILE_CALL(sessile_cmd_begin(d->cmd));
  sessile_buffer *b_rs[6] = {d->packed, d->rows, d->vbase, d->vnode, d->clist, d->ctri};
  SESSILE_CALL(sessile_cmd_dispatch(d->cmd, d->k[2], groups(nrows, d->k[2]), b_rs, &pc));
  pc.count = nv;
  sessile_buffer *b_v[8] = {d->cap, d->nnear, d->field, d->packed, d->vbase, d->vnode, d->pos, d->nearest};
  if (nv) SESSILE_CALL(sessile_cmd_dispatch(d->cmd, d->k[3], groups(nv, d->k[3]), b_v, &pc));
  pc.count = nc;
  sessile_buffer *b_t[5] = {d->packed, d->vbase, d->clist, d->ctri, d->tri};
  if (nc) SESSILE_CALL(sessile_cmd_dispatch(d->cmd, d->k[4], groups(nc, d->k[4]), b_t, &pc));
  SESSILE_CALL(sessile_cmd_end(d->cmd));
  SESSILE_CALL(sessile_cmd_submit_wait(d->cmd));
  double t4 = sessile_wall_seconds();

  double *pos = malloc(((size_t)nv * 3 + 1) * sizeof *pos);
  uint32_t *tri = malloc(((size_t)nf * 3 + 1) * sizeof *tri), *nearest = malloc(((size_t)nv + 1) * 4);
  st = pos && tri && nearest ? SESSILE_OK
                             : sessile_error_set(SESSILE_ERR_NO_MEMORY, "welded surface: out of host memory for %u vertices", nv);
  if (st == SESSILE_OK && nv) st = sessile_buffer_download_reals(d->pos, 0, pos, (size_t)nv * 3);
  if (st == SESSILE_OK && nv) st = sessile_buffer_download(d->nearest, 0, nearest, (size_t)nv * 4);
  if (st == SESSILE_OK && nf) st = sessile_buffer_download(d->tri, 0, tri, (size_t)nf * 12);
  if (st == SESSILE_OK) st = weld_output(s, g->h, nv, nf, pos, tri, nearest, out, vertex_value);
  if (st == SESSILE_OK) pos = NULL, tri = NULL;
  free(pos), free(tri), free(nearest);
  double t5 = sessile_wall_seconds();
  if (tm) {
    tm->sdf = t2 - t1, tm->count = t3 - t2, tm->emit = t4 - t3, tm->download = t5 - t4;
    tm->total = t5 - t0;
  }
  return st;
}

sessile_status weld_gpu(sessile_gpu *gpu, const sessile_skeleton *s, const sessile_weld_params *p,
                        sessile_surface *out, double **vertex_value, weld_times *tm) {
  if (vertex_value) *vertex_value = NULL;
  if (tm) memset(tm, 0, sizeof *tm);
  weld_grid g;
  double bytes;
  SESSILE_CALL(weld_grid_plan(s, p, &g, &bytes));
  if (s->n == 0) return weld_output(s, 0, 0, 0, NULL, NULL, NULL, out, vertex_value);
  weld_dev d;
  memset(&d, 0, sizeof d);
  sessile_status st = run(gpu, s, &g, bytes, &d, out, vertex_value, tm);
  weld_dev_free(&d);
  weld_grid_free(&g);
  return st;
}

sessile_status sessile_skeleton_weld(sessile_gpu *g, const sessile_skeleton *s, const sessile_weld_params *p,
                                     sessile_surface *out, double **vertex_value) {
  return weld_gpu(g, s, p, out, vertex_value, NULL);
}
