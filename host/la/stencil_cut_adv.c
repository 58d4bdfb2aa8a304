/* The cut-cell 7-point operator with off-diagonal weights (la.h:
 * sessile_mat_create_stencil7_cut_adv): the nonsymmetric operator of the
 * advected nutrient (exponentially fitted fluxes, docs/nutrient.md).  The
 * symmetric operator of stencil_cut.c with a third per-node array, coef (6
 * reals per node), read through texel buffers only: its kernels are few
 * (the operator, with and without x·y, and the multigrid's sweep and
 * residual), and the multigrid needs texels anyway.  Plain-C reference:
 * sessile_ref_stencil7_cut_adv (stencil_cut.c). */
#include <stdlib.h>
#include "la_internal.h"

sessile_status sessile_mat_create_stencil7_cut_adv(sessile_la *la, uint32_t nx, uint32_t ny,
                                                   uint32_t nz, double h, sessile_buffer *mask,
                                                   const sessile_vec *diag, const sessile_vec *coef,
                                                   sessile_mat **out) {
  *out = NULL;
  uint64_t nodes = (uint64_t)nx * ny * nz;
  SESSILE_CHECK(coef && coef->la == la && coef->n == 6 * nodes, SESSILE_ERR_USAGE,
                "advective cut-cell operator: coef needs 6 entries per node of the %u x %u x %u "
                "grid in the same la (got %u)", nx, ny, nz, coef ? coef->n : 0);
  uint64_t maxt = sessile_gpu_info_of(la->gpu)->max_texel_buffer_elements; /* for the message */
  SESSILE_CHECK(la_texel_fits(la, coef->buf, la->real_bytes), SESSILE_ERR_TOO_LARGE,
                "advective cut-cell operator: %u x %u x %u nodes exceed the device's texel buffer "
                "limit (%llu texels) for 6 weights per node", nx, ny, nz, (unsigned long long)maxt);
  sessile_mat *m;
  SESSILE_CALL(sessile_mat_create_stencil7_cut(la, nx, ny, nz, h, mask, diag, &m));
  m->coef = coef;
  *out = m;
  return SESSILE_OK;
}

sessile_status rec_stencil7_cut_adv(sessile_la *la, sessile_cmd *c, const sessile_mat *a, vref x,
                                    vref y, int guard, uint32_t *count) {
  SESSILE_CHECK(la_texel_fits(la, x.buf, la->real_bytes), SESSILE_ERR_TOO_LARGE, "advective cut-cell operator: x exceeds the texel limit");
  cut_push p = la_cut_push_of(la, a, x, y, guard);
  la_kernel_id id = count ? K_STENCIL7_CUT_ADV_DOT : K_STENCIL7_CUT_ADV;
  sessile_kernel *k;
  SESSILE_CALL(la_kernel(la, id, &k));
  sessile_buffer *bufs[7] = {la->scalars, a->mask, a->diag->buf, a->coef->buf, x.buf, y.buf, la->partials};
  uint32_t groups = count ? la_fused_groups(la, id, a->nrows) : la_groups(la, id, a->nrows);
  if (count) *count = groups;
  return sessile_cmd_dispatch(c, k, groups, bufs, &p);
}

sessile_status la_stencil7_cut_host_coef(const sessile_mat *a, double **coef) {
  *coef = NULL;
  if (!a->coef) return SESSILE_OK;
  *coef = malloc((size_t)a->coef->n * sizeof **coef);
  SESSILE_CHECK(*coef, SESSILE_ERR_NO_MEMORY, "out of host memory copying the advective weights");
  sessile_status s = sessile_vec_download((sessile_vec *)a->coef, *coef);
  if (s != SESSILE_OK) {
    free(*coef);
    *coef = NULL;
  }
  return s;
}
