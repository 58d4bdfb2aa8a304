/* The masked 7-point operator: the P1 Laplacian of the uniform Kuhn box
 * (docs/fem.md: the assembled P1 stiffness there *is* the 7-point stencil
 * times h), applied matrix-free on the grid.  Wall nodes and masked nodes
 * are Dirichlet nodes, eliminated symmetrically: identity rows and columns.
 * No matrix is stored, so the mask can change between solves (a growing
 * sponge) at no cost; the kernels read it at every application.  Kernels:
 * shaders/la/stencil7*.comp; plain-C reference: sessile_ref_stencil7. */
#include <stdlib.h>
#include "la_internal.h"
#include "sessile/la/la_ref.h"

sessile_status la_stencil_mat(sessile_la *la, mat_kind kind, const char *what, uint32_t nx,
                              uint32_t ny, uint32_t nz, double h, sessile_buffer *mask,
                              sessile_mat **out) {
  *out = NULL;
  SESSILE_CHECK(nx >= 2 && ny >= 2 && nz >= 2, SESSILE_ERR_USAGE,
                "%s needs at least 2 nodes per axis (got %u x %u x %u)", what, nx, ny, nz);
  double nodes = (double)nx * ny * nz;
  SESSILE_CHECK(nodes <= 2147483647.0, SESSILE_ERR_TOO_LARGE,
                "grid of %u x %u x %u nodes is too large for 32-bit indices", nx, ny, nz);
  SESSILE_CHECK(h > 0 && h < 1e300, SESSILE_ERR_USAGE, "grid spacing must be positive (got %g)", h);
  SESSILE_CHECK(mask, SESSILE_ERR_USAGE, "%s needs a Dirichlet mask buffer", what);
  SESSILE_CHECK(sessile_buffer_size(mask) >= (size_t)nodes * 4, SESSILE_ERR_USAGE,
                "Dirichlet mask has %zu bytes, the %u x %u x %u grid needs %zu",
                sessile_buffer_size(mask), nx, ny, nz, (size_t)nodes * 4);
  sessile_mat *m = calloc(1, sizeof *m);
  SESSILE_CHECK(m, SESSILE_ERR_NO_MEMORY, "out of host memory");
  m->la = la;
  m->kind = kind;
  m->nrows = (uint32_t)nodes;
  m->nnz = 7 * (uint64_t)m->nrows; /* the stencil's entries (nothing is stored) */
  m->grid[0] = nx;
  m->grid[1] = ny;
  m->grid[2] = nz;
  m->h = h;
  m->mask = mask;
  *out = m;
  return SESSILE_OK;
}

sessile_status sessile_mat_create_stencil7(sessile_la *la, uint32_t nx, uint32_t ny, uint32_t nz,
                                           double h, sessile_buffer *mask, sessile_mat **out) {
  return la_stencil_mat(la, MAT_STENCIL7, "7-point operator", nx, ny, nz, h, mask, out);
}

static stencil_push push_of(sessile_la *la, const sessile_mat *a, vref x, vref y, int guard) {
  stencil_push p = {.n0 = a->grid[0], .n1 = a->grid[1], .n2 = a->grid[2], .xoff = x.off4 * 4,
                    .yoff = y.off4 * 4, .guard = guard, .h = sessile_push_real_of(a->h, la->real_bytes)};
  return p;
}

sessile_status rec_stencil7(sessile_la *la, sessile_cmd *c, const sessile_mat *a, vref x, vref y,
                            int guard, uint32_t *count) {
  stencil_push p = push_of(la, a, x, y, guard);
  sessile_kernel *k;
  if (!count) {
    SESSILE_CALL(la_kernel(la, K_STENCIL7, &k));
    sessile_buffer *bufs[4] = {la->scalars, a->mask, x.buf, y.buf};
    return sessile_cmd_dispatch(c, k, la_groups(la, K_STENCIL7, a->nrows), bufs, &p);
  }
  SESSILE_CALL(la_kernel(la, K_STENCIL7_DOT, &k));
  sessile_buffer *bufs[5] = {la->scalars, a->mask, x.buf, y.buf, la->partials};
  *count = la_groups(la, K_STENCIL7_DOT, a->nrows);
  if (*count > MAXG) *count = MAXG;
  return sessile_cmd_dispatch(c, k, *count, bufs, &p);
}

sessile_status la_stencil7_jacobi(sessile_la *la, const sessile_mat *a, sessile_vec *dinv) {
  sessile_kernel *k;
  SESSILE_CALL(la_kernel(la, K_STENCIL7_JACOBI, &k));
  stencil_push p = push_of(la, a, vref_of(dinv), vref_of(dinv), -1);
  sessile_buffer *bufs[4] = {la->scalars, a->mask, dinv->buf, dinv->buf};
  SESSILE_CALL(sessile_cmd_begin(la->cmd));
  SESSILE_CALL(sessile_cmd_dispatch(la->cmd, k, la_groups(la, K_STENCIL7_JACOBI, a->nrows), bufs, &p));
  SESSILE_CALL(sessile_cmd_end(la->cmd));
  return sessile_cmd_submit_wait(la->cmd);
}

sessile_status la_stencil7_host_mask(const sessile_mat *a, uint32_t **mask) {
  *mask = malloc((size_t)a->nrows * sizeof **mask);
  SESSILE_CHECK(*mask, SESSILE_ERR_NO_MEMORY, "out of host memory copying the Dirichlet mask");
  sessile_status s = sessile_buffer_download(a->mask, 0, *mask, (size_t)a->nrows * sizeof **mask);
  if (s != SESSILE_OK) {
    free(*mask);
    *mask = NULL;
  }
  return s;
}

void sessile_ref_stencil7(uint32_t nx, uint32_t ny, uint32_t nz, double h, const uint32_t *mask,
                          const double *x, double *y) {
  const int64_t s1 = nx, s2 = (int64_t)nx * ny;
#pragma omp parallel for schedule(static)
  for (int64_t k = 0; k < (int64_t)nz; k++)
    for (uint32_t j = 0; j < ny; j++)
      for (uint32_t i = 0; i < nx; i++) {
        int64_t n = i + s1 * j + s2 * k;
#define DIR(ii, jj, kk, nn)                                                                  \
  ((ii) == 0 || (jj) == 0 || (kk) == 0 || (ii) == nx - 1 || (jj) == ny - 1 ||              \
   (kk) == (int64_t)nz - 1 || (mask && mask[nn]))
        if (DIR(i, j, k, n)) {
          y[n] = x[n];
          continue;
        }
        double sum = 0;
        if (!DIR(i - 1, j, k, n - 1)) sum += x[n - 1];
        if (!DIR(i + 1, j, k, n + 1)) sum += x[n + 1];
        if (!DIR(i, j - 1, k, n - s1)) sum += x[n - s1];
        if (!DIR(i, j + 1, k, n + s1)) sum += x[n + s1];
        if (!DIR(i, j, k - 1, n - s2)) sum += x[n - s2];
        if (!DIR(i, j, k + 1, n + s2)) sum += x[n + s2];
#undef DIR
        y[n] = h * (6.0 * x[n] - sum);
      }
}
