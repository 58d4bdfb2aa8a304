/* Reference ILU(0): the incomplete LU factorisation on A's own sparsity
 * pattern (Saad, Iterative Methods for Sparse Linear Systems, 2nd ed.,
 * Algorithm 10.4, IKJ order), for scalar CSR and for 4x4 block CSR (block
 * ILU(0): pivots are dense 4x4 blocks, inverted with partial pivoting), and
 * the triangular solves z = (LU)⁻¹ r in natural row order.
 *
 * One code path for both: `bs` is the block size (1 or 4) and entry k of the
 * pattern holds bs*bs values, row-major.  Factors are stored in A's pattern:
 * the strict lower part holds L (unit diagonal implied), the diagonal and the
 * upper part hold U.  Sequential by nature (row i needs rows < i). */
#include <inttypes.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "la_internal.h"
#include "sessile/la/la_ref.h"

/* c = a b for bs x bs row-major blocks. */
static void bmul(int bs, const double *a, const double *b, double *c) {
  for (int i = 0; i < bs; i++)
    for (int j = 0; j < bs; j++) {
      double s = 0;
      for (int k = 0; k < bs; k++) s += a[i * bs + k] * b[k * bs + j];
      c[i * bs + j] = s;
    }
}

int la_block_inverse(int bs, const double *a, double *inv) {
  double m[16], amax = 0;
  memcpy(m, a, (size_t)(bs * bs) * sizeof *m);
  for (int i = 0; i < bs * bs; i++) {
    if (!isfinite(a[i])) return 0;
    if (fabs(a[i]) > amax) amax = fabs(a[i]);
    inv[i] = (i / bs == i % bs) ? 1.0 : 0.0;
  }
  if (amax == 0) return 0;
  /* Gauss-Jordan with partial pivoting; a pivot below 1e-14 of the block's
   * largest entry means the block is singular to working precision. */
  for (int c = 0; c < bs; c++) {
    int p = c;
    for (int r = c + 1; r < bs; r++)
      if (fabs(m[r * bs + c]) > fabs(m[p * bs + c])) p = r;
    double piv = m[p * bs + c];
    if (!(fabs(piv) > 1e-14 * amax)) return 0;
    if (p != c)
      for (int j = 0; j < bs; j++) {
        double t = m[c * bs + j]; m[c * bs + j] = m[p * bs + j]; m[p * bs + j] = t;
        t = inv[c * bs + j]; inv[c * bs + j] = inv[p * bs + j]; inv[p * bs + j] = t;
      }
    for (int j = 0; j < bs; j++) { m[c * bs + j] /= piv; inv[c * bs + j] /= piv; }
    for (int r = 0; r < bs; r++) {
      if (r == c) continue;
      double f = m[r * bs + c];
      if (f == 0) continue;
      for (int j = 0; j < bs; j++) {
        m[r * bs + j] -= f * m[c * bs + j];
        inv[r * bs + j] -= f * inv[c * bs + j];
      }
    }
  }
  for (int i = 0; i < bs * bs; i++)
    if (!isfinite(inv[i])) return 0;
  return 1;
}

static sessile_status pivot_error(int bs, uint32_t row, const char *why) {
  if (bs == 1)
    return sessile_error_set(SESSILE_ERR_NUMERIC,
                             "ILU(0): %s pivot at row %" PRIu32
                             ": the incomplete factorisation breaks down (use Jacobi, or a "
                             "diagonally stronger / reordered matrix)", why, row);
  return sessile_error_set(SESSILE_ERR_NUMERIC,
                           "ILU(0): %s 4x4 pivot block at block row %" PRIu32
                           " (scalar rows %" PRIu32 "..%" PRIu32
                           "): the incomplete factorisation breaks down (use Jacobi)",
                           why, row, 4 * row, 4 * row + 3);
}

/* The position of the diagonal entry in each row (pattern must contain it). */
static sessile_status find_diag(int bs, uint32_t n, const uint64_t *rowptr, const uint32_t *col,
                                uint64_t *diag) {
  for (uint32_t i = 0; i < n; i++) {
    diag[i] = UINT64_MAX;
    for (uint64_t k = rowptr[i]; k < rowptr[i + 1]; k++)
      if (col[k] == i) diag[i] = k;
    if (diag[i] == UINT64_MAX) return pivot_error(bs, i, "missing (no diagonal entry in the pattern)");
  }
  return SESSILE_OK;
}

static sessile_status ilu0(int bs, uint32_t n, const uint64_t *rowptr, const uint32_t *col,
                           const double *val, double *lu) {
  const int b2 = bs * bs;
  uint64_t nnz = rowptr[n];
  memcpy(lu, val, (size_t)nnz * b2 * sizeof *lu);
  uint64_t *diag = malloc(((size_t)n + 1) * sizeof *diag);
  uint64_t *pos = malloc(((size_t)n + 1) * sizeof *pos);
  double *dinv = malloc(((size_t)n * b2 + 1) * sizeof *dinv);
  sessile_status s = SESSILE_OK;
  if (!diag || !pos || !dinv) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "ILU(0): out of host memory");
  if (s == SESSILE_OK) s = find_diag(bs, n, rowptr, col, diag);
  if (s == SESSILE_OK)
    for (uint32_t i = 0; i < n; i++) pos[i] = UINT64_MAX;
  double l[16], t[16];
  for (uint32_t i = 0; s == SESSILE_OK && i < n; i++) {
    for (uint64_t k = rowptr[i]; k < rowptr[i + 1]; k++) pos[col[k]] = k;
    /* Columns are sorted, so the entries left of the diagonal are the k < i. */
    for (uint64_t kk = rowptr[i]; kk < diag[i]; kk++) {
      uint32_t c = col[kk];
      bmul(bs, lu + kk * b2, dinv + (size_t)c * b2, l); /* L_ic = A_ic U_cc⁻¹ */
      memcpy(lu + kk * b2, l, (size_t)b2 * sizeof *l);
      for (uint64_t jj = diag[c] + 1; jj < rowptr[c + 1]; jj++) {
        uint64_t p = pos[col[jj]];
        if (p == UINT64_MAX) continue; /* fill-in outside the pattern: dropped */
        bmul(bs, l, lu + jj * b2, t);
        for (int q = 0; q < b2; q++) lu[p * b2 + q] -= t[q];
      }
    }
    for (uint64_t k = rowptr[i]; k < rowptr[i + 1]; k++) {
      pos[col[k]] = UINT64_MAX;
      for (int q = 0; q < b2; q++)
        if (!isfinite(lu[k * b2 + q])) s = pivot_error(bs, i, "non-finite values reaching the");
    }
    if (s != SESSILE_OK) break;
    const double *u = lu + diag[i] * b2;
    if (bs == 1) {
      if (u[0] == 0) s = pivot_error(bs, i, "zero");
      else dinv[i] = 1.0 / u[0];
    } else if (!la_block_inverse(bs, u, dinv + (size_t)i * b2))
      s = pivot_error(bs, i, "singular");
  }
  free(diag);
  free(pos);
  free(dinv);
  return s;
}

sessile_status sessile_ref_ilu0_csr(const sessile_csr *a, double *lu) {
  SESSILE_CHECK(a->nrows == a->ncols, SESSILE_ERR_USAGE, "ILU(0) needs a square matrix (got %u x %u)",
                a->nrows, a->ncols);
  return ilu0(1, a->nrows, a->rowptr, a->col, a->val, lu);
}

sessile_status sessile_ref_ilu0_bcsr4(const sessile_bcsr4 *a, double *lu) {
  SESSILE_CHECK(a->nbrows == a->nbcols, SESSILE_ERR_USAGE,
                "ILU(0) needs a square block matrix (got %u x %u blocks)", a->nbrows, a->nbcols);
  return ilu0(4, a->nbrows, a->rowptr, a->col, a->val, lu);
}

/* Solves the bs x bs system u x = b by Gaussian elimination with partial
 * pivoting (independent of the Gauss-Jordan inverse the factorisation and
 * the device use). */
static void block_solve(int bs, const double *u, const double *b, double *x) {
  double m[16], y[4];
  memcpy(m, u, (size_t)(bs * bs) * sizeof *m);
  memcpy(y, b, (size_t)bs * sizeof *y);
  for (int c = 0; c < bs; c++) {
    int p = c;
    for (int r = c + 1; r < bs; r++)
      if (fabs(m[r * bs + c]) > fabs(m[p * bs + c])) p = r;
    if (p != c) {
      for (int j = 0; j < bs; j++) { double t = m[c * bs + j]; m[c * bs + j] = m[p * bs + j]; m[p * bs + j] = t; }
      double t = y[c]; y[c] = y[p]; y[p] = t;
    }
    for (int r = c + 1; r < bs; r++) {
      double f = m[r * bs + c] / m[c * bs + c];
      for (int j = c; j < bs; j++) m[r * bs + j] -= f * m[c * bs + j];
      y[r] -= f * y[c];
    }
  }
  for (int r = bs - 1; r >= 0; r--) {
    double s = y[r];
    for (int j = r + 1; j < bs; j++) s -= m[r * bs + j] * x[j];
    x[r] = s / m[r * bs + r];
  }
}

static void ilu0_solve(int bs, uint32_t n, const uint64_t *rowptr, const uint32_t *col,
                       const double *lu, const double *r, double *z) {
  const int b2 = bs * bs;
  double s[4];
  for (uint32_t i = 0; i < n; i++) { /* L y = r, L unit lower */
    for (int q = 0; q < bs; q++) s[q] = r[(size_t)i * bs + q];
    for (uint64_t k = rowptr[i]; k < rowptr[i + 1] && col[k] < i; k++)
      for (int p = 0; p < bs; p++)
        for (int q = 0; q < bs; q++) s[p] -= lu[k * b2 + p * bs + q] * z[(size_t)col[k] * bs + q];
    for (int q = 0; q < bs; q++) z[(size_t)i * bs + q] = s[q];
  }
  for (uint32_t i = n; i-- > 0;) { /* U z = y */
    uint64_t d = UINT64_MAX;
    for (int q = 0; q < bs; q++) s[q] = z[(size_t)i * bs + q];
    for (uint64_t k = rowptr[i]; k < rowptr[i + 1]; k++) {
      if (col[k] == i) d = k;
      if (col[k] <= i) continue;
      for (int p = 0; p < bs; p++)
        for (int q = 0; q < bs; q++) s[p] -= lu[k * b2 + p * bs + q] * z[(size_t)col[k] * bs + q];
    }
    block_solve(bs, lu + d * b2, s, z + (size_t)i * bs);
  }
}

void sessile_ref_ilu0_solve_csr(const sessile_csr *a, const double *lu, const double *r, double *z) {
  ilu0_solve(1, a->nrows, a->rowptr, a->col, lu, r, z);
}

void sessile_ref_ilu0_solve_bcsr4(const sessile_bcsr4 *a, const double *lu, const double *r,
                                  double *z) {
  ilu0_solve(4, a->nbrows, a->rowptr, a->col, lu, r, z);
}
