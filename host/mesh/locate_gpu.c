/* The GPU point locator: uploads a locator's mesh and bins, records
 * shaders/mesh/locate.comp (sessile/mesh/locate.h). */
#include <stdlib.h>
#include <string.h>
#include "locate_internal.h"
#include "mesh_kernels.h"

struct sessile_locate_gpu {
  sessile_gpu *gpu;
  sessile_kernel *k;
  sessile_buffer *params, *xyz, *tet, *off, *cell;
  uint32_t dims[3];
  int real_bytes;
  double eps;
};

void sessile_locate_gpu_destroy(sessile_locate_gpu *lg) {
  if (!lg) return;
  sessile_kernel_destroy(lg->k);
  sessile_buffer_destroy(lg->params);
  sessile_buffer_destroy(lg->xyz);
  sessile_buffer_destroy(lg->tet);
  sessile_buffer_destroy(lg->off);
  sessile_buffer_destroy(lg->cell);
  free(lg);
}

/* Uploads n doubles in the context precision. */
static sessile_status make_buffer(sessile_gpu *g, size_t bytes, sessile_buffer **b) {
  return sessile_buffer_create(g, bytes < 16 ? 16 : bytes, SESSILE_BUFFER_DEVICE, b);
}

sessile_status sessile_locate_gpu_create(sessile_gpu *gpu, const sessile_locator *l, sessile_locate_gpu **out) {
  *out = NULL;
  sessile_locate_gpu *lg = calloc(1, sizeof *lg);
  SESSILE_CHECK(lg, SESSILE_ERR_NO_MEMORY, "out of host memory for a GPU locator");
  lg->gpu = gpu;
  int f64 = sessile_gpu_info_of(gpu)->precision == 64;
  lg->real_bytes = f64 ? 8 : 4;
  lg->eps = f64 ? SESSILE_LOCATE_EPS : 1e-5;
  memcpy(lg->dims, l->dims, sizeof lg->dims);
  const sessile_tetmesh *m = l->m;
  sessile_status s = sessile_kernel_create_decl(gpu, &sessile_mesh_kernels[MK_LOCATE], lg->real_bytes,
                                                0, &lg->k);
  if (s == SESSILE_OK) s = sessile_buffer_create(gpu, LOC_COUNT * 8, SESSILE_BUFFER_MAPPED, &lg->params);
  if (s == SESSILE_OK) s = make_buffer(gpu, (size_t)3 * m->nnodes * lg->real_bytes, &lg->xyz);
  if (s == SESSILE_OK) s = make_buffer(gpu, (size_t)4 * m->ntets * sizeof(uint32_t), &lg->tet);
  if (s == SESSILE_OK) s = make_buffer(gpu, ((size_t)l->nbins + 1) * sizeof(uint32_t), &lg->off);
  if (s == SESSILE_OK) s = make_buffer(gpu, (size_t)l->nentries * sizeof(uint32_t), &lg->cell);
  if (s == SESSILE_OK) s = sessile_buffer_upload_reals(lg->xyz, 0, m->xyz, (size_t)3 * m->nnodes);
  if (s == SESSILE_OK) s = sessile_buffer_upload(lg->tet, 0, m->tet, (size_t)4 * m->ntets * sizeof(uint32_t));
  if (s == SESSILE_OK)
    s = sessile_buffer_upload(lg->off, 0, l->cell_off, ((size_t)l->nbins + 1) * sizeof(uint32_t));
  if (s == SESSILE_OK && l->nentries)
    s = sessile_buffer_upload(lg->cell, 0, l->cell_tet, (size_t)l->nentries * sizeof(uint32_t));
  if (s == SESSILE_OK) {
    double pr[LOC_COUNT] = {0};
    for (int a = 0; a < 3; a++) pr[LOC_LO + a] = l->lo[a], pr[LOC_INV_H + a] = l->inv_h[a];
    pr[LOC_EPS] = lg->eps;
    s = sessile_buffer_upload_reals(lg->params, 0, pr, LOC_COUNT);
  }
  if (s != SESSILE_OK) {
    sessile_locate_gpu_destroy(lg);
    return s;
  }
  *out = lg;
  return SESSILE_OK;
}

sessile_status sessile_locate_gpu_record(sessile_locate_gpu *lg, sessile_cmd *c, sessile_buffer *points,
                                         uint32_t n, sessile_buffer *field, sessile_buffer *values,
                                         sessile_buffer *tets, double outside_value) {
  if (n == 0) return SESSILE_OK;
  /* the outside value is a parameter slot (mapped: visible at submission) */
  void *hp = sessile_buffer_host_ptr(lg->params);
  SESSILE_CHECK(hp, SESSILE_ERR_INTERNAL, "locator parameter buffer is not mapped");
  if (lg->real_bytes == 8) ((double *)hp)[LOC_OUTSIDE] = outside_value;
  else ((float *)hp)[LOC_OUTSIDE] = (float)outside_value;
  sessile_buffer *b[9] = {lg->params, lg->xyz, lg->tet, lg->off, lg->cell, points, field, values, tets};
  locate_push push = {.n = n, .d0 = lg->dims[0], .d1 = lg->dims[1], .d2 = lg->dims[2]};
  uint32_t ls = sessile_kernel_local_size(lg->k);
  return sessile_cmd_dispatch(c, lg->k, (n + ls - 1) / ls, b, &push);
}
