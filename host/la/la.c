/* The la context: kernels (created on first use), the mapped scalar-slot
 * buffer that solvers use to decide on the device and report to the host,
 * and the reduction partials. */
#include <stdlib.h>
#include <string.h>
#include "la_internal.h"

static sessile_status la_init(sessile_la *la) {
  SESSILE_CALL(sessile_buffer_create(la->gpu, (size_t)NSLOTS * la->real_bytes,
                                     SESSILE_BUFFER_MAPPED, &la->scalars));
  SESSILE_CALL(sessile_buffer_create(la->gpu, (size_t)NSETS * MAXG * 2 * la->real_bytes,
                                     SESSILE_BUFFER_DEVICE, &la->partials));
  SESSILE_CALL(sessile_cmd_create(la->gpu, &la->cmd));
  return SESSILE_OK;
}

void sessile_la_options_default(sessile_la_options *o) { memset(o, 0, sizeof *o); }

sessile_status sessile_la_create(sessile_gpu *g, sessile_la **out) {
  return sessile_la_create_with(g, NULL, out);
}

sessile_status sessile_la_create_with(sessile_gpu *g, const sessile_la_options *opt, sessile_la **out) {
  *out = NULL;
  sessile_la_options o;
  if (opt) o = *opt;
  else sessile_la_options_default(&o);
  sessile_la *la = calloc(1, sizeof *la);
  SESSILE_CHECK(la, SESSILE_ERR_NO_MEMORY, "out of host memory");
  la->gpu = g;
  la->real_bytes = sessile_gpu_info_of(g)->precision == 64 ? 8 : 4;
  la->fused_groups = strcmp(sessile_gpu_info_of(g)->type, "cpu") == 0 ? 128 : MAXG;
  sessile_la_set_options(la, &o);
  sessile_status s = la_init(la);
  if (s != SESSILE_OK) {
    sessile_la_destroy(la);
    return s;
  }
  *out = la;
  return SESSILE_OK;
}

void sessile_la_set_options(sessile_la *la, const sessile_la_options *opt) {
  la->spmv_texel = !opt->spmv_storage;
  la->max_chunk_bytes = opt->max_matrix_chunk_bytes;
  la->gm_textbook = opt->gmres_textbook_update;
}

void sessile_la_destroy(sessile_la *la) {
  if (!la) return;
  for (int i = 0; i < K_COUNT; i++) sessile_kernel_destroy(la->k[i]);
  la_vstore_free(&la->gm_v);
  la_vstore_free(&la->gm_zs);
  sessile_vec_destroy(la->gm_z);
  sessile_vec_destroy(la->gm_ones);
  sessile_cmd_destroy(la->cmd);
  sessile_buffer_destroy(la->partials);
  sessile_buffer_destroy(la->scalars);
  free(la);
}

sessile_gpu *sessile_la_gpu(sessile_la *la) { return la->gpu; }
uint32_t sessile_la_real_bytes(const sessile_la *la) { return la->real_bytes; }

sessile_status la_kernel(sessile_la *la, la_kernel_id id, sessile_kernel **out) {
  if (!la->k[id])
    SESSILE_CALL(sessile_kernel_create_decl(la->gpu, &sessile_la_kernels[id], la->real_bytes, 0,
                                            &la->k[id]));
  *out = la->k[id];
  return SESSILE_OK;
}

void la_scalar_set(sessile_la *la, int slot, double v) {
  void *p = sessile_buffer_host_ptr(la->scalars);
  if (la->real_bytes == 8) ((double *)p)[slot] = v;
  else ((float *)p)[slot] = (float)v;
}

double la_scalar_read(sessile_la *la, int slot) {
  const void *p = sessile_buffer_host_ptr(la->scalars);
  return la->real_bytes == 8 ? ((const double *)p)[slot] : (double)((const float *)p)[slot];
}
