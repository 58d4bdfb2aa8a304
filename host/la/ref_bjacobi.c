/* Reference block Jacobi for 4x4 block CSR: the inverse of every diagonal
 * block (la_block_inverse, Gauss-Jordan with partial pivoting, the same as
 * block ILU(0)'s pivots) and z = blockdiag(D⁻¹) r.  The device pc
 * (pc_bjacobi.c) uploads exactly these inverses. */
#include <stdint.h>
#include <string.h>

#include "la_internal.h"
#include "sessile/la/la_ref.h"

sessile_status sessile_ref_bjacobi_bcsr4(const sessile_bcsr4 *a, double *dinv) {
  /* A failure in a worker is reduced to the lowest failing block row and
   * reported once, on the calling thread, after the parallel loop: the error
   * message is thread-local, so a worker's sessile_error_set would be lost. */
  uint32_t bad = UINT32_MAX;
#pragma omp parallel for schedule(static) reduction(min : bad)
  for (uint32_t i = 0; i < a->nbrows; i++) {
    const double *d = NULL;
    for (uint64_t e = a->rowptr[i]; e < a->rowptr[i + 1]; e++)
      if (a->col[e] == i) d = a->val + 16 * e;
    if (!d || !la_block_inverse(4, d, dinv + 16 * (size_t)i))
      if (i < bad) bad = i;
  }
  SESSILE_CHECK(bad == UINT32_MAX, SESSILE_ERR_NUMERIC,
                "block Jacobi: singular diagonal block at block row %u (missing, not finite, or "
                "singular to working precision)", bad);
  return SESSILE_OK;
}

void sessile_ref_bjacobi_apply(uint32_t nbrows, const double *dinv, const double *r, double *z) {
#pragma omp parallel for schedule(static) if (nbrows >= 8192)
  for (uint32_t i = 0; i < nbrows; i++) {
    const double *d = dinv + 16 * (size_t)i, *ri = r + 4 * (size_t)i;
    for (int k = 0; k < 4; k++)
      z[4 * (size_t)i + k] = d[4 * k] * ri[0] + d[4 * k + 1] * ri[1] + d[4 * k + 2] * ri[2] + d[4 * k + 3] * ri[3];
  }
}
