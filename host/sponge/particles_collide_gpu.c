/* The GPU collider: uploads the grid and the particles, records
 * shaders/sponge/collide.comp, downloads the hits (sessile/sponge/particles.h). */
#include <stdlib.h>
#include <string.h>
#include "sessile/sponge/particles.h"
#include "sponge_kernels.h"

_Static_assert(SPONGE_MAX_FEED == SESSILE_SPONGE_PARTICLES_MAX_FEED, "kernels.def and the header disagree");

enum { B_VTX, B_OFF, B_CELL, B_PART, B_HIT, B_COUNT, NB };

struct sessile_sponge_particles_gpu {
  sessile_gpu *gpu;
  sessile_kernel *k;
  sessile_cmd *cmd;
  sessile_buffer *b[NB];
};

void sessile_sponge_particles_gpu_destroy(sessile_sponge_particles_gpu *c) {
  if (!c) return;
  for (int i = 0; i < NB; i++) sessile_buffer_destroy(c->b[i]);
  sessile_cmd_destroy(c->cmd);
  sessile_kernel_destroy(c->k);
  free(c);
}

sessile_status sessile_sponge_particles_gpu_create(sessile_gpu *gpu, sessile_sponge_particles_gpu **out) {
  *out = NULL;
  SESSILE_CHECK(gpu, SESSILE_ERR_USAGE, "the GPU collider needs a device");
  sessile_sponge_particles_gpu *c = calloc(1, sizeof *c);
  SESSILE_CHECK(c, SESSILE_ERR_NO_MEMORY, "out of host memory for the GPU collider");
  c->gpu = gpu;
  sessile_status s = sessile_kernel_create_decl(gpu, &sessile_sponge_kernels[SPK_COLLIDE], 0, 0, &c->k);
  if (s == SESSILE_OK) s = sessile_cmd_create(gpu, &c->cmd);
  if (s != SESSILE_OK) {
    sessile_sponge_particles_gpu_destroy(c);
    return s;
  }
  *out = c;
  return SESSILE_OK;
}

/* Buffer i holds at least bytes (grown by half again when replaced). */
static sessile_status ensure(sessile_sponge_particles_gpu *c, int i, size_t bytes) {
  return sessile_buffer_reserve(c->gpu, &c->b[i], bytes < 16 ? 16 : bytes, SESSILE_BUFFER_DEVICE);
}

sessile_status sessile_sponge_particles_gpu_collide(sessile_sponge_particles_gpu *c, const sessile_sponge_particles_grid *g,
                                           const float *part4, uint32_t np, float radius,
                                           uint32_t feed, uint32_t *hit, uint32_t *count,
                                           double *kernel_ns) {
  if (kernel_ns) *kernel_ns = 0;
  SESSILE_CHECK(feed >= 1 && feed <= SESSILE_SPONGE_PARTICLES_MAX_FEED, SESSILE_ERR_USAGE,
                "collisions: feed %u must be in 1..%d", feed, SESSILE_SPONGE_PARTICLES_MAX_FEED);
  if (np == 0) return SESSILE_OK;
  size_t ncell = (size_t)g->d[0] * g->d[1] * g->d[2];
  SESSILE_CALL(ensure(c, B_VTX, (size_t)g->nv * 16));
  SESSILE_CALL(ensure(c, B_OFF, (ncell + 1) * 4));
  SESSILE_CALL(ensure(c, B_CELL, (size_t)g->nv * 4));
  SESSILE_CALL(ensure(c, B_PART, (size_t)np * 16));
  SESSILE_CALL(ensure(c, B_HIT, (size_t)np * feed * 4));
  SESSILE_CALL(ensure(c, B_COUNT, (size_t)np * 4));
  if (g->nv) {
    SESSILE_CALL(sessile_buffer_upload(c->b[B_VTX], 0, g->pos4, (size_t)g->nv * 16));
    SESSILE_CALL(sessile_buffer_upload(c->b[B_CELL], 0, g->cell_vtx, (size_t)g->nv * 4));
  }
  SESSILE_CALL(sessile_buffer_upload(c->b[B_OFF], 0, g->cell_off, (ncell + 1) * 4));
  SESSILE_CALL(sessile_buffer_upload(c->b[B_PART], 0, part4, (size_t)np * 16));
  collide_push push = {.n = np, .feed = feed, .d0 = g->d[0], .d1 = g->d[1], .d2 = g->d[2], .nv = g->nv,
                       .lo0 = g->lo[0], .lo1 = g->lo[1], .lo2 = g->lo[2], .inv_h = g->inv_h,
                       .radius = radius, .r2 = radius * radius, .margin = SESSILE_SPONGE_PARTICLES_CELL_MARGIN};
  uint32_t ls = sessile_kernel_local_size(c->k);
  SESSILE_CALL(sessile_cmd_begin(c->cmd));
  SESSILE_CALL(sessile_cmd_timestamp(c->cmd, 0));
  SESSILE_CALL(sessile_cmd_dispatch(c->cmd, c->k, (np + ls - 1) / ls, c->b, &push));
  SESSILE_CALL(sessile_cmd_timestamp(c->cmd, 1));
  SESSILE_CALL(sessile_cmd_end(c->cmd));
  SESSILE_CALL(sessile_cmd_submit_wait(c->cmd));
  if (kernel_ns) SESSILE_CALL(sessile_cmd_elapsed_ns(c->cmd, 0, 1, kernel_ns));
  SESSILE_CALL(sessile_buffer_download(c->b[B_HIT], 0, hit, (size_t)np * feed * 4));
  return sessile_buffer_download(c->b[B_COUNT], 0, count, (size_t)np * 4);
}
