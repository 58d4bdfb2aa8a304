/* The exposure kernel's host side (shaders/reef/exposure.comp): one
 * dispatch, one invocation per organism. */
#include <stdlib.h>
#include "reef/reef_internal.h"
#include "reef_kernels.h"

enum { B_H, B_POS, B_CUR, B_EXPO, B_COUNT };

static sessile_status run(sessile_gpu *gpu, sessile_kernel *k, sessile_cmd *cmd, sessile_buffer **bf,
                          const sessile_reef_scene *s, const sessile_reef_seabed *b, sessile_reef_placements *pl,
                          uint32_t first, double *scratch) {
  uint32_t n = pl->n - first, rb = sessile_gpu_info_of(gpu)->precision == 64 ? 8 : 4;
  size_t nh = (size_t)b->nx * b->ny, nc = (size_t)s->ncurrents * RC_COUNT;
  size_t bytes[B_COUNT] = {nh * rb, 3 * (size_t)n * rb, (nc ? nc : 1) * rb, (size_t)n * rb};
  for (int i = 0; i < B_COUNT; i++) SESSILE_CALL(sessile_buffer_create(gpu, bytes[i], SESSILE_BUFFER_DEVICE, &bf[i]));
  SESSILE_CALL(sessile_buffer_upload_reals(bf[B_H], 0, b->h, nh));
  for (uint32_t i = 0; i < n; i++)
    for (int a = 0; a < 3; a++) scratch[3 * i + a] = pl->p[first + i].pos[a];
  SESSILE_CALL(sessile_buffer_upload_reals(bf[B_POS], 0, scratch, 3 * (size_t)n));
  for (int c = 0; c < s->ncurrents; c++) {
    const sessile_reef_current *q = &s->currents[c];
    double *x = scratch + (size_t)c * RC_COUNT;
    for (int a = 0; a < 3; a++) x[RC_OX + a] = q->origin[a], x[RC_DX + a] = q->dir[a];
    x[RC_STRENGTH] = q->strength, x[RC_RANGE] = q->range;
  }
  if (nc) SESSILE_CALL(sessile_buffer_upload_reals(bf[B_CUR], 0, scratch, nc));
  exposure_push push = {.n = n, .ncur = (uint32_t)s->ncurrents, .nx = b->nx, .ny = b->ny,
                       .dx = sessile_push_real_of(b->extent[0] / (b->nx - 1), rb),
                       .dy = sessile_push_real_of(b->extent[1] / (b->ny - 1), rb),
                       .ex = sessile_push_real_of(b->extent[0], rb), .ey = sessile_push_real_of(b->extent[1], rb)};
  uint32_t ls = sessile_kernel_local_size(k);
  SESSILE_CALL(sessile_cmd_begin(cmd));
  SESSILE_CALL(sessile_cmd_dispatch(cmd, k, (n + ls - 1) / ls, bf, &push));
  SESSILE_CALL(sessile_cmd_end(cmd));
  SESSILE_CALL(sessile_cmd_submit_wait(cmd));
  SESSILE_CALL(sessile_buffer_download_reals(bf[B_EXPO], 0, scratch, n));
  for (uint32_t i = 0; i < n; i++) pl->p[first + i].exposure = scratch[i];
  return SESSILE_OK;
}

sessile_status sessile_reef_exposure_gpu(sessile_gpu *gpu, const sessile_reef_scene *s, const sessile_reef_seabed *b,
                                         sessile_reef_placements *pl, uint32_t first) {
  if (first >= pl->n) return SESSILE_OK;
  size_t n = pl->n - first, m = 3 * n > (size_t)s->ncurrents * RC_COUNT ? 3 * n : (size_t)s->ncurrents * RC_COUNT;
  double *scratch = malloc(m * sizeof *scratch);
  SESSILE_CHECK(scratch, SESSILE_ERR_NO_MEMORY, "out of host memory");
  sessile_kernel *k = NULL;
  sessile_cmd *cmd = NULL;
  sessile_buffer *bf[B_COUNT] = {0};
  sessile_status st = sessile_kernel_create_decl(gpu, &sessile_reef_kernels[RK_EXPOSURE], 0, 0, &k);
  if (st == SESSILE_OK) st = sessile_cmd_create(gpu, &cmd);
  if (st == SESSILE_OK) st = run(gpu, k, cmd, bf, s, b, pl, first, scratch);
  for (int i = 0; i < B_COUNT; i++) sessile_buffer_destroy(bf[i]);
  sessile_cmd_destroy(cmd);
  sessile_kernel_destroy(k);
  free(scratch);
  return st;
}
