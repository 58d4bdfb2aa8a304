/* The cut-cell 7-point operator (la.h: sessile_mat_create_stencil7_cut):
 * zero-flux walls with half and quarter faces, Dirichlet nodes from a mask,
 * and a caller-supplied diagonal that carries the Shortley-Weller weights of
 * the edges a Dirichlet boundary cuts.  Matrix-free like stencil.c: mask and
 * diag are read at every application.  Kernels: shaders/la/stencil7_cut*.comp
 * (shared code in stencil7_cut.glsl); plain-C reference:
 * sessile_ref_stencil7_cut. */
#include <stdlib.h>
#include "la_internal.h"
#include "sessile/la/la_ref.h"

/* Texel reads need every view within maxTexelBufferElements. */
static int texel_fits(sessile_la *la, const sessile_buffer *mask, const sessile_vec *diag) {
  return la_texel_fits(la, mask, 4) && la_texel_fits(la, diag->buf, la->real_bytes);
}

sessile_status sessile_mat_create_stencil7_cut(sessile_la *la, uint32_t nx, uint32_t ny, uint32_t nz,
                                               double h, sessile_buffer *mask, const sessile_vec *diag,
                                               sessile_mat **out) {
  sessile_mat *m;
  SESSILE_CALL(la_stencil_mat(la, MAT_STENCIL7_CUT, "cut-cell operator", nx, ny, nz, h, mask, &m));
  double nodes = (double)nx * ny * nz;
  if (!diag || diag->la != la || diag->n != (uint32_t)nodes) {
    free(m);
    SESSILE_CHECK(diag, SESSILE_ERR_USAGE, "cut-cell operator needs its diagonal vector");
    return sessile_error_set(SESSILE_ERR_USAGE,
                             "cut-cell diagonal has %u entries%s, the %u x %u x %u grid needs %u",
                             diag->n, diag->la == la ? "" : " of another la", nx, ny, nz,
                             (uint32_t)nodes);
  }
  m->diag = diag;
  m->cut_texel = la->spmv_texel && texel_fits(la, mask, diag);
  *out = m;
  return SESSILE_OK;
}

cut_push la_cut_push_of(sessile_la *la, const sessile_mat *a, vref x, vref y, int guard) {
  cut_push p = {.n0 = a->grid[0], .n1 = a->grid[1], .n2 = a->grid[2],
                .m0 = la_div_magic(a->grid[0]), .m1 = la_div_magic(a->grid[1]),
                .xoff = x.off4 * 4, .yoff = y.off4 * 4, .guard = guard,
                .h = sessile_push_real_of(a->h, la->real_bytes)};
  return p;
}

sessile_status rec_stencil7_cut(sessile_la *la, sessile_cmd *c, const sessile_mat *a, vref x,
                                vref y, int guard, uint32_t *count) {
  if (a->coef) return rec_stencil7_cut_adv(la, c, a, x, y, guard, count);
  cut_push p = la_cut_push_of(la, a, x, y, guard);
  int tex = a->cut_texel && la_texel_fits(la, x.buf, la->real_bytes);
  la_kernel_id id = count ? (tex ? K_STENCIL7_CUT_TEX_DOT : K_STENCIL7_CUT_DOT)
                          : (tex ? K_STENCIL7_CUT_TEX : K_STENCIL7_CUT);
  sessile_kernel *k;
  SESSILE_CALL(la_kernel(la, id, &k));
  sessile_buffer *bufs[6] = {la->scalars, a->mask, a->diag->buf, x.buf, y.buf, la->partials};
  uint32_t groups = count ? la_fused_groups(la, id, a->nrows) : la_groups(la, id, a->nrows);
  if (count) *count = groups;
  return sessile_cmd_dispatch(c, k, groups, bufs, &p);
}

sessile_status la_stencil7_cut_jacobi(sessile_la *la, const sessile_mat *a, sessile_vec *dinv) {
  sessile_kernel *k;
  SESSILE_CALL(la_kernel(la, K_STENCIL7_CUT_JACOBI, &k));
  cut_push p = la_cut_push_of(la, a, vref_of(dinv), vref_of(dinv), -1);
  sessile_buffer *bufs[4] = {la->scalars, a->mask, a->diag->buf, dinv->buf};
  SESSILE_CALL(sessile_cmd_begin(la->cmd));
  SESSILE_CALL(sessile_cmd_dispatch(la->cmd, k, la_groups(la, K_STENCIL7_CUT_JACOBI, a->nrows), bufs, &p));
  SESSILE_CALL(sessile_cmd_end(la->cmd));
  return sessile_cmd_submit_wait(la->cmd);
}

sessile_status la_stencil7_cut_host_diag(const sessile_mat *a, double **diag) {
  *diag = malloc((size_t)a->nrows * sizeof **diag);
  SESSILE_CHECK(*diag, SESSILE_ERR_NO_MEMORY, "out of host memory copying the cut-cell diagonal");
  sessile_status s = sessile_vec_download((sessile_vec *)a->diag, *diag);
  if (s != SESSILE_OK) {
    free(*diag);
    *diag = NULL;
  }
  return s;
}

/* The operator with optional off-diagonal weights (coef NULL: all 1). */
void sessile_ref_stencil7_cut_adv(uint32_t nx, uint32_t ny, uint32_t nz, double h, const uint32_t *mask,
                           const double *diag, const double *coef, const double *x, double *y) {
  const int64_t s1 = nx, s2 = (int64_t)nx * ny;
#pragma omp parallel for schedule(static)
  for (int64_t k = 0; k < (int64_t)nz; k++)
    for (uint32_t j = 0; j < ny; j++)
      for (uint32_t i = 0; i < nx; i++) {
        int64_t n = i + s1 * j + s2 * k;
        if (mask[n]) {
          y[n] = x[n];
          continue;
        }
        double bx = i == 0 || i == nx - 1 ? 0.5 : 1, by = j == 0 || j == ny - 1 ? 0.5 : 1;
        double bz = k == 0 || k == nz - 1 ? 0.5 : 1;
        const double *w = coef ? coef + 6 * n : NULL;
#define NB(ok, m, d) ((ok) && !mask[m] ? (w ? w[d] : 1.0) * x[m] : 0.0)
        double sx = NB(i > 0, n - 1, 0) + NB(i + 1 < nx, n + 1, 1);
        double sy = NB(j > 0, n - s1, 2) + NB(j + 1 < ny, n + s1, 3);
        double sz = NB(k > 0, n - s2, 4) + NB(k + 1 < nz, n + s2, 5);
#undef NB
        y[n] = h * (diag[n] * x[n] - (by * bz * sx + bx * bz * sy + bx * by * sz));
      }
}

void sessile_ref_stencil7_cut(uint32_t nx, uint32_t ny, uint32_t nz, double h, const uint32_t *mask,
                              const double *diag, const double *x, double *y) {
  sessile_ref_stencil7_cut_adv(nx, ny, nz, h, mask, diag, NULL, x, y);
}
