/* The GPU nearest-node search (sessile/coral/venation.h): uploads nodes, the grid
 * and the auxins, records shaders/coral/nearest.comp, downloads the answer.
 * Buffers grow by doubling and are kept between iterations. */
#include <stdlib.h>
#include <string.h>
#include "coral_kernels.h"
#include "sessile/coral/venation.h"

enum { B_GP, B_NODE, B_OFF, B_CELL, B_PTS, B_NEAR, B_D2, B_ST, B_TODO, B_CAND, B_CD2, B_START, B_BLK, B_COUNT };

struct sessile_venation_gpu {
  sessile_gpu *gpu;
  sessile_kernel *k, *k_rn;
  sessile_cmd *cmd;
  sessile_buffer *b[B_COUNT];
  int real_bytes;
  uint64_t passes; /* of the last search */
};

void sessile_venation_gpu_destroy(sessile_venation_gpu *vg) {
  if (!vg) return;
  sessile_kernel_destroy(vg->k);
  sessile_kernel_destroy(vg->k_rn);
  sessile_cmd_destroy(vg->cmd);
  for (int i = 0; i < B_COUNT; i++) sessile_buffer_destroy(vg->b[i]);
  free(vg);
}

sessile_status sessile_venation_gpu_create(sessile_gpu *g, sessile_venation_gpu **out) {
  *out = NULL;
  sessile_venation_gpu *vg = calloc(1, sizeof *vg);
  SESSILE_CHECK(vg, SESSILE_ERR_NO_MEMORY, "out of host memory for the venation search");
  vg->gpu = g;
  vg->real_bytes = sessile_gpu_info_of(g)->precision == 64 ? 8 : 4;
  sessile_status s = sessile_kernel_create_decl(g, &sessile_coral_kernels[CK_NEAREST], (uint32_t)vg->real_bytes,
                                                0, &vg->k);
  if (s == SESSILE_OK)
    s = sessile_kernel_create_decl(g, &sessile_coral_kernels[CK_RN], (uint32_t)vg->real_bytes, 0, &vg->k_rn);
  if (s == SESSILE_OK) s = sessile_cmd_create(g, &vg->cmd);
  if (s == SESSILE_OK) s = sessile_buffer_create(g, NN_COUNT * 8, SESSILE_BUFFER_MAPPED, &vg->b[B_GP]);
  if (s == SESSILE_OK) s = sessile_buffer_create(g, 16, SESSILE_BUFFER_DEVICE, &vg->b[B_TODO]);
  if (s != SESSILE_OK) {
    sessile_venation_gpu_destroy(vg);
    return s;
  }
  *out = vg;
  return SESSILE_OK;
}

/* Buffer i holds at least `bytes` (contents not kept). */
static sessile_status ensure(sessile_venation_gpu *vg, int i, size_t bytes) {
  return sessile_buffer_reserve(vg->gpu, &vg->b[i], bytes < 16 ? 16 : bytes, SESSILE_BUFFER_DEVICE);
}

sessile_status sessile_venation_gpu_nearest(sessile_venation_gpu *vg, const sessile_venation_grid *g,
                                            const double *nodes, const double *pts, uint32_t m,
                                            uint32_t *idx, double *d2, double *kernel_ns) {
  if (kernel_ns) *kernel_ns = 0;
  if (m == 0) return SESSILE_OK;
  size_t rb = (size_t)vg->real_bytes;
  SESSILE_CALL(ensure(vg, B_NODE, 3 * (size_t)g->n * rb));
  SESSILE_CALL(ensure(vg, B_OFF, ((size_t)g->ncells + 1) * sizeof(uint32_t)));
  SESSILE_CALL(ensure(vg, B_CELL, (size_t)g->n * sizeof(uint32_t)));
  SESSILE_CALL(ensure(vg, B_PTS, 3 * (size_t)m * rb));
  SESSILE_CALL(ensure(vg, B_NEAR, (size_t)m * sizeof(uint32_t)));
  SESSILE_CALL(ensure(vg, B_D2, (size_t)m * rb));
  double pr[NN_COUNT] = {g->lo[0], g->lo[1], g->lo[2], g->h, rb == 8 ? 1e-9 : 1e-4};
  SESSILE_CALL(sessile_buffer_upload_reals(vg->b[B_GP], 0, pr, NN_COUNT));
  SESSILE_CALL(sessile_buffer_upload_reals(vg->b[B_NODE], 0, nodes, 3 * (size_t)g->n));
  SESSILE_CALL(sessile_buffer_upload(vg->b[B_OFF], 0, g->cell_off, ((size_t)g->ncells + 1) * sizeof(uint32_t)));
  SESSILE_CALL(sessile_buffer_upload(vg->b[B_CELL], 0, g->cell_node, (size_t)g->n * sizeof(uint32_t)));
  SESSILE_CALL(sessile_buffer_upload_reals(vg->b[B_PTS], 0, pts, 3 * (size_t)m));
  /* every auxin starts anew (status 0) */
  size_t stb = (size_t)NN_ST_COUNT * m * sizeof(uint32_t);
  SESSILE_CALL(ensure(vg, B_ST, stb));
  uint32_t *zero = calloc(1, stb);
  SESSILE_CHECK(zero, SESSILE_ERR_NO_MEMORY, "out of host memory");
  sessile_status s = sessile_buffer_upload(vg->b[B_ST], 0, zero, stb);
  free(zero);
  SESSILE_CALL(s);
  nearest_push push = {.m = m, .d0 = g->dims[0], .d1 = g->dims[1], .d2 = g->dims[2]};
  uint32_t ls = sessile_kernel_local_size(vg->k);
  SESSILE_CALL(sessile_cmd_begin(vg->cmd));
  SESSILE_CALL(sessile_cmd_timestamp(vg->cmd, 0));
  SESSILE_CALL(sessile_cmd_dispatch(vg->cmd, vg->k, (m + ls - 1) / ls, vg->b, &push));
  SESSILE_CALL(sessile_cmd_timestamp(vg->cmd, 1));
  SESSILE_CALL(sessile_cmd_end(vg->cmd));
  /* passes until no auxin is left: each does at most NN_BUDGET loop
   * iterations per auxin, so the whole search needs at most this many */
  uint64_t max_pass = 16 + 4 * ((uint64_t)g->ncells + g->n) / NN_BUDGET + 4 * (uint64_t)g->ncells;
  uint32_t todo = 1;
  for (uint64_t pass = 0; todo; pass++) {
    SESSILE_CHECK(pass < max_pass, SESSILE_ERR_INTERNAL, "the nearest-node search did not finish in %llu passes",
                  (unsigned long long)max_pass);
    todo = 0;
    SESSILE_CALL(sessile_buffer_upload(vg->b[B_TODO], 0, &todo, sizeof todo));
    SESSILE_CALL(sessile_cmd_submit_wait(vg->cmd));
    double ns = 0;
    if (kernel_ns) SESSILE_CALL(sessile_cmd_elapsed_ns(vg->cmd, 0, 1, &ns));
    if (kernel_ns) *kernel_ns += ns;
    SESSILE_CALL(sessile_buffer_download(vg->b[B_TODO], 0, &todo, sizeof todo));
    vg->passes = pass + 1;
  }
  if (idx) SESSILE_CALL(sessile_buffer_download(vg->b[B_NEAR], 0, idx, (size_t)m * sizeof(uint32_t)));
  if (d2) SESSILE_CALL(sessile_buffer_download_reals(vg->b[B_D2], 0, d2, m));
  return SESSILE_OK;
}

uint64_t sessile_venation_gpu_passes(const sessile_venation_gpu *vg) { return vg ? vg->passes : 0; }

sessile_status sessile_venation_gpu_rn(sessile_venation_gpu *vg, const double *nodes, uint32_t n,
                                       const uint32_t *j, const double *d2, const uint32_t *start,
                                       uint32_t total, uint32_t *blocked) {
  _Static_assert(SESSILE_VENATION_RN_MAX_CAND == RN_MAX_CAND, "the host and the kernel agree on the list limit");
  if (total == 0) return SESSILE_OK;
  size_t rb = (size_t)vg->real_bytes;
  SESSILE_CALL(ensure(vg, B_NODE, 3 * (size_t)n * rb));
  SESSILE_CALL(ensure(vg, B_CAND, (size_t)total * sizeof(uint32_t)));
  SESSILE_CALL(ensure(vg, B_CD2, (size_t)total * rb));
  SESSILE_CALL(ensure(vg, B_START, (size_t)total * sizeof(uint32_t)));
  SESSILE_CALL(ensure(vg, B_BLK, (size_t)total * sizeof(uint32_t)));
  SESSILE_CALL(sessile_buffer_upload_reals(vg->b[B_NODE], 0, nodes, 3 * (size_t)n));
  SESSILE_CALL(sessile_buffer_upload(vg->b[B_CAND], 0, j, (size_t)total * sizeof(uint32_t)));
  SESSILE_CALL(sessile_buffer_upload_reals(vg->b[B_CD2], 0, d2, total));
  SESSILE_CALL(sessile_buffer_upload(vg->b[B_START], 0, start, (size_t)total * sizeof(uint32_t)));
  sessile_buffer *b[5] = {vg->b[B_NODE], vg->b[B_CAND], vg->b[B_CD2], vg->b[B_START], vg->b[B_BLK]};
  rn_push push = {.total = total};
  uint32_t ls = sessile_kernel_local_size(vg->k_rn);
  SESSILE_CALL(sessile_cmd_begin(vg->cmd));
  SESSILE_CALL(sessile_cmd_dispatch(vg->cmd, vg->k_rn, (total + ls - 1) / ls, b, &push));
  SESSILE_CALL(sessile_cmd_end(vg->cmd));
  SESSILE_CALL(sessile_cmd_submit_wait(vg->cmd));
  /* skipped entries keep what the host writes after */
  return sessile_buffer_download(vg->b[B_BLK], 0, blocked, (size_t)total * sizeof(uint32_t));
}
