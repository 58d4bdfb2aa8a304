/* Reference vector operations (BLAS-1).  Element-wise ops are trivially
 * deterministic; the reductions (dot, nrm2) use a summation order fixed by n
 * alone — fixed chunks, pairwise inside and across chunks — so the result is
 * bitwise the same for any OpenMP thread count, and the rounding error grows
 * like O(ε log n) instead of O(ε n) (Higham, "Accuracy and Stability of
 * Numerical Algorithms", §4.2). */
#include <math.h>
#include <stdint.h>

#include "sessile/la/la_ref.h"

/* Below this length a parallel region costs more than it saves. */
#define VEC_PAR_MIN 32768
/* Reduction layout: at most DOT_MAX_CHUNKS chunks of at least DOT_MIN_CHUNK
 * elements (except for n < DOT_MIN_CHUNK: one chunk); chunk boundaries are a
 * function of n only. */
#define DOT_MAX_CHUNKS 256
#define DOT_MIN_CHUNK 4096
/* Pairwise recursion stops at blocks this long, summed with 4 interleaved
 * accumulators (fixed order, so still deterministic; hides add latency). */
#define PAIRWISE_BASE 128

void sessile_ref_fill(uint64_t n, double value, double *y) {
#pragma omp parallel for schedule(static) if (n >= VEC_PAR_MIN)
  for (uint64_t i = 0; i < n; i++) y[i] = value;
}

void sessile_ref_copy(uint64_t n, const double *x, double *y) {
#pragma omp parallel for schedule(static) if (n >= VEC_PAR_MIN)
  for (uint64_t i = 0; i < n; i++) y[i] = x[i];
}

void sessile_ref_scale(uint64_t n, double alpha, double *y) {
#pragma omp parallel for schedule(static) if (n >= VEC_PAR_MIN)
  for (uint64_t i = 0; i < n; i++) y[i] = alpha * y[i];
}

void sessile_ref_axpy(uint64_t n, double alpha, const double *x, double *y) {
#pragma omp parallel for schedule(static) if (n >= VEC_PAR_MIN)
  for (uint64_t i = 0; i < n; i++) y[i] += alpha * x[i];
}

void sessile_ref_aypx(uint64_t n, double alpha, const double *x, double *y) {
#pragma omp parallel for schedule(static) if (n >= VEC_PAR_MIN)
  for (uint64_t i = 0; i < n; i++) y[i] = x[i] + alpha * y[i];
}

void sessile_ref_waxpy(uint64_t n, double alpha, const double *x, const double *y, double *w) {
#pragma omp parallel for schedule(static) if (n >= VEC_PAR_MIN)
  for (uint64_t i = 0; i < n; i++) w[i] = alpha * x[i] + y[i];
}

void sessile_ref_pmul(uint64_t n, const double *x, const double *y, double *w) {
#pragma omp parallel for schedule(static) if (n >= VEC_PAR_MIN)
  for (uint64_t i = 0; i < n; i++) w[i] = x[i] * y[i];
}

/* Σ x_i y_i over [0,n), pairwise: split in halves down to PAIRWISE_BASE. */
static double dot_pairwise(const double *x, const double *y, uint64_t n) {
  if (n <= PAIRWISE_BASE) {
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
    uint64_t i = 0;
    for (; i + 4 <= n; i += 4) {
      s0 += x[i] * y[i];
      s1 += x[i + 1] * y[i + 1];
      s2 += x[i + 2] * y[i + 2];
      s3 += x[i + 3] * y[i + 3];
    }
    for (; i < n; i++) s0 += x[i] * y[i];
    return (s0 + s1) + (s2 + s3);
  }
  uint64_t h = n / 2;
  return dot_pairwise(x, y, h) + dot_pairwise(x + h, y + h, n - h);
}

/* Pairwise sum of a short array (the chunk partials). */
static double sum_pairwise(const double *a, uint64_t n) {
  if (n == 0) return 0.0;
  if (n == 1) return a[0];
  uint64_t h = n / 2;
  return sum_pairwise(a, h) + sum_pairwise(a + h, n - h);
}

double sessile_ref_dot(uint64_t n, const double *x, const double *y) {
  uint64_t nchunks = (n + DOT_MIN_CHUNK - 1) / DOT_MIN_CHUNK;
  if (nchunks < 1) nchunks = 1;
  if (nchunks > DOT_MAX_CHUNKS) nchunks = DOT_MAX_CHUNKS;
  const uint64_t base = n / nchunks, rem = n % nchunks;
  double part[DOT_MAX_CHUNKS];
  /* Chunk c starts at c*base + min(c, rem): the first `rem` chunks get one
   * extra element.  Threads only decide who computes a chunk, never its order. */
#pragma omp parallel for schedule(static) if (n >= VEC_PAR_MIN)
  for (uint64_t c = 0; c < nchunks; c++) {
    uint64_t start = c * base + (c < rem ? c : rem);
    uint64_t len = base + (c < rem);
    part[c] = dot_pairwise(x + start, y + start, len);
  }
  return sum_pairwise(part, nchunks);
}

double sessile_ref_nrm2(uint64_t n, const double *x) {
  /* sqrt(x·x): overflow only beyond ~1e154 per entry, far outside any use here. */
  return sqrt(sessile_ref_dot(n, x, x));
}
