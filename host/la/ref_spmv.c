/* Reference sparse matrix-vector products, Jacobi inverse diagonals and the
 * true relative residual.  Each row is summed in stored (column) order by one
 * thread, so results do not depend on the thread count. */
#include <inttypes.h>
#include <math.h>
#include <stdint.h>

#include "sessile/la/la_ref.h"

/* Parallelise once the matrix has this many stored entries. */
#define SPMV_PAR_MIN_NNZ 32768
/* true_relres: rows are reduced in at most this many fixed chunks. */
#define RES_MAX_CHUNKS 256
#define RES_MIN_CHUNK 4096

void sessile_ref_spmv_csr(const sessile_csr *a, const double *x, double *y) {
  const uint32_t n = a->nrows;
#pragma omp parallel for schedule(static) if (a->nnz >= SPMV_PAR_MIN_NNZ)
  for (uint32_t r = 0; r < n; r++) {
    double s = 0.0;
    for (uint64_t p = a->rowptr[r]; p < a->rowptr[r + 1]; p++) s += a->val[p] * x[a->col[p]];
    y[r] = s;
  }
}

void sessile_ref_spmv_bcsr4(const sessile_bcsr4 *a, const double *x, double *y) {
  const uint32_t n = a->nbrows;
#pragma omp parallel for schedule(static) if (16 * a->nnzb >= SPMV_PAR_MIN_NNZ)
  for (uint32_t r = 0; r < n; r++) {
    double s[4] = {0.0, 0.0, 0.0, 0.0};
    for (uint64_t b = a->rowptr[r]; b < a->rowptr[r + 1]; b++) {
      const double *blk = a->val + 16 * b;       /* row-major 4x4 */
      const double *xb = x + 4 * (uint64_t)a->col[b];
      for (int i = 0; i < 4; i++)
        s[i] += blk[4 * i] * xb[0] + blk[4 * i + 1] * xb[1] + blk[4 * i + 2] * xb[2] +
                blk[4 * i + 3] * xb[3];
    }
    for (int i = 0; i < 4; i++) y[4 * (uint64_t)r + i] = s[i];
  }
}

/* Stored diagonal of CSR row r, 0 when the row has none. */
static double csr_diag(const sessile_csr *a, uint32_t r) {
  for (uint64_t p = a->rowptr[r]; p < a->rowptr[r + 1]; p++)
    if (a->col[p] == r) return a->val[p];
  return 0.0;
}

/* Whether 1/d is a usable Jacobi scale (rejects 0, NaN, ±inf and subnormals
 * whose reciprocal overflows). */
static int invertible(double d) { return d != 0.0 && isfinite(d) && isfinite(1.0 / d); }

sessile_status sessile_ref_jacobi_csr(const sessile_csr *a, double *dinv) {
  const uint32_t n = a->nrows; /* a row past ncols has no diagonal: reported */
  uint64_t bad = UINT64_MAX; /* lowest failing row, found in parallel */
#pragma omp parallel for schedule(static) reduction(min : bad) if (a->nnz >= SPMV_PAR_MIN_NNZ)
  for (uint32_t r = 0; r < n; r++) {
    double d = csr_diag(a, r);
    if (invertible(d)) dinv[r] = 1.0 / d;
    else if (r < bad) bad = r;
  }
  if (bad != UINT64_MAX) {
    uint32_t r = (uint32_t)bad;
    return sessile_error_set(SESSILE_ERR_NUMERIC,
                             "Jacobi: diagonal entry of row %" PRIu32
                             " is %g (zero, missing or not finite): the matrix needs a "
                             "nonzero finite diagonal for Jacobi preconditioning",
                             r, csr_diag(a, r));
  }
  return SESSILE_OK;
}

/* Point Jacobi on the scalar matrix: dinv has 4*nbrows entries, the
 * reciprocals of the scalar diagonal (the diagonals of the diagonal blocks). */
static double bcsr4_diag(const sessile_bcsr4 *a, uint64_t s) {
  uint32_t r = (uint32_t)(s / 4);
  int i = (int)(s % 4);
  for (uint64_t b = a->rowptr[r]; b < a->rowptr[r + 1]; b++)
    if (a->col[b] == r) return a->val[16 * b + 4 * i + i];
  return 0.0;
}

sessile_status sessile_ref_jacobi_bcsr4(const sessile_bcsr4 *a, double *dinv) {
  const uint64_t n = 4 * (uint64_t)a->nbrows;
  uint64_t bad = UINT64_MAX;
#pragma omp parallel for schedule(static) reduction(min : bad) if (16 * a->nnzb >= SPMV_PAR_MIN_NNZ)
  for (uint64_t s = 0; s < n; s++) {
    double d = bcsr4_diag(a, s);
    if (invertible(d)) dinv[s] = 1.0 / d;
    else if (s < bad) bad = s;
  }
  if (bad != UINT64_MAX)
    return sessile_error_set(SESSILE_ERR_NUMERIC,
                             "Jacobi: diagonal entry %d of block row %" PRIu64
                             " (scalar row %" PRIu64
                             ") is %g (zero, missing or not finite): the matrix needs a "
                             "nonzero finite diagonal for Jacobi preconditioning",
                             (int)(bad % 4), bad / 4, bad, bcsr4_diag(a, bad));
  return SESSILE_OK;
}

/* Σ (b - A x)_r² over rows [lo, hi), pairwise over row ranges: no work vector,
 * so true_relres cannot fail for lack of memory. */
static double residual_sq(const sessile_csr *a, const double *b, const double *x, uint64_t lo,
                          uint64_t hi) {
  if (hi - lo <= 64) {
    double s = 0.0;
    for (uint64_t r = lo; r < hi; r++) {
      double ax = 0.0;
      for (uint64_t p = a->rowptr[r]; p < a->rowptr[r + 1]; p++) ax += a->val[p] * x[a->col[p]];
      double rr = b[r] - ax;
      s += rr * rr;
    }
    return s;
  }
  uint64_t mid = lo + (hi - lo) / 2;
  return residual_sq(a, b, x, lo, mid) + residual_sq(a, b, x, mid, hi);
}

double sessile_ref_true_relres(const sessile_csr *a, const double *b, const double *x) {
  const uint64_t n = a->nrows;
  uint64_t nchunks = (n + RES_MIN_CHUNK - 1) / RES_MIN_CHUNK;
  if (nchunks < 1) nchunks = 1;
  if (nchunks > RES_MAX_CHUNKS) nchunks = RES_MAX_CHUNKS;
  const uint64_t base = n / nchunks, rem = n % nchunks;
  double part[RES_MAX_CHUNKS];
#pragma omp parallel for schedule(static) if (a->nnz >= SPMV_PAR_MIN_NNZ)
  for (uint64_t c = 0; c < nchunks; c++) {
    uint64_t start = c * base + (c < rem ? c : rem);
    part[c] = residual_sq(a, b, x, start, start + base + (c < rem));
  }
  double rr = 0.0; /* 256 partials at most: fixed left-to-right order is enough */
  for (uint64_t c = 0; c < nchunks; c++) rr += part[c];
  double bnorm = sessile_ref_nrm2(n, b);
  return bnorm > 0.0 ? sqrt(rr) / bnorm : sqrt(rr);
}
