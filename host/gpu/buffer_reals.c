/* Transfers of reals in the context's precision (sessile_gpu_info.precision):
 * the host always holds doubles; fp32 contexts store floats, converted here,
 * so every layer shares one conversion path. */
#include <stdlib.h>
#include "gpu_internal.h"

sessile_status sessile_buffer_upload_reals(sessile_buffer *b, size_t offset_reals, const double *src,
                                           size_t n) {
  if (n == 0) return SESSILE_OK;
  if (b->gpu->info.precision == 64)
    return sessile_buffer_upload(b, offset_reals * 8, src, n * sizeof(double));
  float *t = malloc(n * sizeof *t);
  SESSILE_CHECK(t, SESSILE_ERR_NO_MEMORY, "out of host memory converting %zu values", n);
  for (size_t i = 0; i < n; i++) t[i] = (float)src[i];
  sessile_status s = sessile_buffer_upload(b, offset_reals * 4, t, n * sizeof *t);
  free(t);
  return s;
}

sessile_status sessile_buffer_download_reals(sessile_buffer *b, size_t offset_reals, double *dst,
                                             size_t n) {
  if (n == 0) return SESSILE_OK;
  if (b->gpu->info.precision == 64)
    return sessile_buffer_download(b, offset_reals * 8, dst, n * sizeof(double));
  float *t = malloc(n * sizeof *t);
  SESSILE_CHECK(t, SESSILE_ERR_NO_MEMORY, "out of host memory converting %zu values", n);
  sessile_status s = sessile_buffer_download(b, offset_reals * 4, t, n * sizeof *t);
  for (size_t i = 0; s == SESSILE_OK && i < n; i++) dst[i] = t[i];
  free(t);
  return s;
}
