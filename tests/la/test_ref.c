/* Tests of the host reference: status/error path, matrix allocation, the
 * generators (structure, symmetry, the P1 K+M split), vector kernels (accuracy
 * and thread-count determinism of dot), SpMV and the three Krylov solvers.
 * Each check prints what it verifies, the tolerance and the error found; the
 * exit status is the number of failed checks (capped at 1). */
#include <inttypes.h>
#include <math.h>
#include <omp.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/la/la_ref.h"
#include "sessile/la/matrix.h"
#include "sessile/bench/matrix_gen.h"
#include "sessile/status.h"

static int failures = 0;
static int checks = 0;

/* Reports "err <= tol" (NaN fails). */
static void check_le(const char *what, double err, double tol) {
  int ok = err <= tol;
  checks++;
  failures += !ok;
  printf("[%s] %-66s err %-10.3g tol %.3g\n", ok ? "PASS" : "FAIL", what, err, tol);
}

/* Reports a boolean property with a free-form detail. */
static void check_true(int ok, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void check_true(int ok, const char *fmt, ...) {
  char buf[256];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  checks++;
  failures += !ok;
  printf("[%s] %s\n", ok ? "PASS" : "FAIL", buf);
}

/* A status call that must succeed; aborts the test program otherwise (the
 * remaining checks would only dereference garbage). */
static void must(sessile_status s, const char *what) {
  if (s == SESSILE_OK) return;
  printf("[FAIL] %s: %s: %s\n", what, sessile_status_name(s), sessile_error_message());
  exit(1);
}

static double *dalloc(uint64_t n) {
  double *p = malloc((size_t)(n ? n : 1) * sizeof *p);
  if (!p) {
    printf("[FAIL] test harness: out of memory for %" PRIu64 " doubles\n", n);
    exit(1);
  }
  return p;
}

/* ---- structural helpers ---- */

/* rowptr monotone from 0 to nnz, columns in range, sorted, unique. */
static int csr_valid(const sessile_csr *a) {
  if (a->rowptr[0] != 0 || a->rowptr[a->nrows] != a->nnz) return 0;
  for (uint32_t r = 0; r < a->nrows; r++) {
    if (a->rowptr[r + 1] < a->rowptr[r]) return 0;
    for (uint64_t p = a->rowptr[r]; p < a->rowptr[r + 1]; p++) {
      if (a->col[p] >= a->ncols) return 0;
      if (p > a->rowptr[r] && a->col[p] <= a->col[p - 1]) return 0;
    }
  }
  return 1;
}

/* Entry (r,c) by binary search; *found says whether it is stored. */
static double csr_get(const sessile_csr *a, uint32_t r, uint32_t c, int *found) {
  uint64_t lo = a->rowptr[r], hi = a->rowptr[r + 1];
  while (lo < hi) {
    uint64_t mid = lo + (hi - lo) / 2;
    if (a->col[mid] < c) lo = mid + 1;
    else hi = mid;
  }
  *found = lo < a->rowptr[r + 1] && a->col[lo] == c;
  return *found ? a->val[lo] : 0.0;
}

/* Largest |a_ij - a_ji| (structure included: a missing transpose counts as
 * the whole value); 0 means bitwise symmetric values and pattern. */
static double csr_asym(const sessile_csr *a) {
  double worst = 0.0;
  for (uint32_t r = 0; r < a->nrows; r++)
    for (uint64_t p = a->rowptr[r]; p < a->rowptr[r + 1]; p++) {
      int found;
      double t = csr_get(a, a->col[p], r, &found);
      double d = found ? fabs(a->val[p] - t) : fabs(a->val[p]) + 1.0;
      if (d > worst) worst = d;
    }
  return worst;
}

static double max_abs_diff(uint64_t n, const double *x, const double *y) {
  double m = 0.0;
  for (uint64_t i = 0; i < n; i++) {
    double d = fabs(x[i] - y[i]);
    if (!(d <= m)) m = d; /* propagates NaN */
  }
  return m;
}

static double max_abs(uint64_t n, const double *x) {
  double m = 0.0;
  for (uint64_t i = 0; i < n; i++)
    if (fabs(x[i]) > m) m = fabs(x[i]);
  return m;
}

static double min_abs(uint64_t n, const double *x) {
  double m = INFINITY;
  for (uint64_t i = 0; i < n; i++)
    if (!(fabs(x[i]) >= m)) m = fabs(x[i]); /* propagates NaN */
  return m;
}

static int all_finite(uint64_t n, const double *x) {
  for (uint64_t i = 0; i < n; i++)
    if (!isfinite(x[i])) return 0;
  return 1;
}

/* ---- status and allocation ---- */

static void test_status(void) {
  printf("-- status / allocation\n");
  check_true(strcmp(sessile_status_name(SESSILE_ERR_VULKAN), "SESSILE_ERR_VULKAN") == 0 &&
                 strcmp(sessile_status_name(SESSILE_OK), "SESSILE_OK") == 0 &&
                 strcmp(sessile_status_name(SESSILE_ERR_INTERNAL), "SESSILE_ERR_INTERNAL") == 0,
             "sessile_status_name returns the enum identifiers");
  sessile_error_clear();
  sessile_status s = sessile_error_set(SESSILE_ERR_IO, "file %s line %d", "x.mtx", 7);
  check_true(s == SESSILE_ERR_IO && strcmp(sessile_error_message(), "file x.mtx line 7") == 0,
             "sessile_error_set formats and returns its status: \"%s\"", sessile_error_message());
  char big[2000];
  memset(big, 'a', sizeof big - 1);
  big[sizeof big - 1] = '\0';
  (void)sessile_error_set(SESSILE_ERR_IO, "%s", big);
  check_true(strlen(sessile_error_message()) == 1023, "long messages truncated to 1023 chars");
  sessile_error_clear();
  check_true(sessile_error_message()[0] == '\0', "sessile_error_clear empties the message");

  /* A request whose byte count overflows size_t fails cleanly (no malloc). */
  sessile_csr a;
  s = sessile_csr_alloc(10, 10, UINT64_MAX / 4, &a);
  check_true(s == SESSILE_ERR_NO_MEMORY && a.rowptr == NULL && strstr(sessile_error_message(),
                                                                      "nonzeros") != NULL,
             "csr_alloc of 2^62 nonzeros -> %s: \"%.60s...\"", sessile_status_name(s),
             sessile_error_message());
  sessile_bcsr4 bb;
  s = sessile_bcsr4_alloc(10, 10, UINT64_MAX / 8, &bb);
  check_true(s == SESSILE_ERR_NO_MEMORY && bb.val == NULL, "bcsr4_alloc of 2^61 blocks -> %s",
             sessile_status_name(s));
  must(sessile_csr_alloc(3, 3, 0, &a), "csr_alloc empty");
  sessile_csr_free(&a);
  sessile_csr_free(&a); /* second free: no-op */
  sessile_csr_free(NULL);
  sessile_bcsr4_free(NULL);
  check_true(a.rowptr == NULL && a.nnz == 0,
             "csr_free zeroes the struct; double free and NULL safe");
}

/* ---- 7-point matrices ---- */

static void test_stencil7(void) {
  printf("-- laplacian7 / convdiff\n");
  sessile_csr a;
  must(sessile_csr_laplacian7(5, 4, 3, &a), "laplacian7 5x4x3");
  check_true(csr_valid(&a) && a.nrows == 60 && a.nnz == 7 * 60 - 2 * (12 + 15 + 20),
             "laplacian7 5x4x3: 60 rows, nnz %" PRIu64 ", sorted unique columns", a.nnz);
  check_le("laplacian7 5x4x3 symmetric (max |a_ij - a_ji|)", csr_asym(&a), 0.0);
  int found;
  uint32_t r = 2 + 5 * (1 + 4 * 1); /* interior node (2,1,1) */
  double d = csr_get(&a, r, r, &found), e = csr_get(&a, r, r + 5, &found);
  check_true(a.rowptr[r + 1] - a.rowptr[r] == 7 && d == 6.0 && e == -1.0,
             "laplacian7 interior row: 7 entries, diagonal %g, y-neighbour %g", d, e);
  sessile_csr_free(&a);

  must(sessile_csr_laplacian7(16, 16, 16, &a), "laplacian7 16^3");
  check_true(csr_valid(&a), "laplacian7 16^3: sorted unique columns, nnz %" PRIu64, a.nnz);
  check_le("laplacian7 16^3 symmetric", csr_asym(&a), 0.0);
  sessile_csr_free(&a);

  must(sessile_csr_convdiff(16, 16, 16, 2.0, &a), "convdiff 16^3");
  check_true(csr_valid(&a), "convdiff 16^3 Pe=2: sorted unique columns, nnz %" PRIu64, a.nnz);
  r = 5 + 16 * (5 + 16 * 5);
  double east = csr_get(&a, r, r + 1, &found), west = csr_get(&a, r, r - 1, &found);
  check_true(east == 1.0 && west == -3.0,
             "convdiff Pe=2 x-coefficients -1+Pe = %g (east), -1-Pe = %g (west)", east, west);
  double asym = csr_asym(&a);
  check_true(asym >= 1.0, "convdiff is nonsymmetric: max |a_ij - a_ji| = %g", asym);
  sessile_csr_free(&a);

  sessile_status s = sessile_csr_laplacian7(0, 4, 4, &a);
  check_true(s == SESSILE_ERR_USAGE, "laplacian7 with nx = 0 -> %s", sessile_status_name(s));
  s = sessile_csr_laplacian7(65536, 65536, 2, &a);
  check_true(s == SESSILE_ERR_TOO_LARGE, "laplacian7 65536x65536x2 -> %s", sessile_status_name(s));
}

/* ---- P1 tetrahedra ---- */

/* Number of Kuhn tetrahedra that contain node (i,j,k), straight from the
 * definition (tet = monotone path 000 -> ... -> 111 in a cube). */
static int tets_at_node(int64_t i, int64_t j, int64_t k, uint32_t nx, uint32_t ny, uint32_t nz) {
  static const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  int count = 0;
  for (int c = 0; c < 8; c++) {
    int64_t ox = i - (c & 1), oy = j - ((c >> 1) & 1), oz = k - ((c >> 2) & 1);
    if (ox < 0 || oy < 0 || oz < 0 || ox >= nx || oy >= ny || oz >= nz) continue;
    for (int t = 0; t < 6; t++) {
      int c1 = 1 << axes[t][0], c2 = c1 | 1 << axes[t][1];
      count += c == 0 || c == c1 || c == c2 || c == 7;
    }
  }
  return count;
}

static void test_p1tet_on(uint32_t nx, uint32_t ny, uint32_t nz, double hx, double hy, double hz) {
  char what[128];
  sessile_csr a, a2;
  must(sessile_csr_p1tet(nx, ny, nz, hx, hy, hz, &a), "p1tet");
  /* Mass scales with h³, stiffness with h: A(h) = K + M, A(2h) = 2K + 8M, so
   * K = (8A(h) − A(2h))/6 and M = (A(2h) − 2A(h))/6 on the same pattern. */
  must(sessile_csr_p1tet(nx, ny, nz, 2 * hx, 2 * hy, 2 * hz, &a2), "p1tet 2h");
  const uint32_t mx = nx + 1, my = ny + 1, mz = nz + 1;
  const double cellvol = hx * hy * hz, volume = cellvol * nx * ny * nz;

  int rows_ok = 1, pattern_same = a.nnz == a2.nnz;
  uint64_t interior = 0;
  double ksum_err = 0.0, mrow_err = 0.0, interior_err = 0.0, msum = 0.0, asum = 0.0;
  double mmin = INFINITY;
  for (uint32_t r = 0; r < a.nrows; r++) {
    int64_t i = r % mx, j = (r / mx) % my, k = r / mx / my;
    /* Expected count: self + the 14 same-sign offsets that stay in the box. */
    uint64_t expect = 0;
    for (int dz = -1; dz <= 1; dz++)
      for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
          int mixed = (dx < 0 || dy < 0 || dz < 0) && (dx > 0 || dy > 0 || dz > 0);
          if (!mixed && i + dx >= 0 && i + dx < mx && j + dy >= 0 && j + dy < my && k + dz >= 0 &&
              k + dz < mz)
            expect++;
        }
    int is_interior = i > 0 && j > 0 && k > 0 && i < nx && j < ny && k < nz;
    uint64_t len = a.rowptr[r + 1] - a.rowptr[r];
    rows_ok &= len == expect && (!is_interior || len == 15);
    interior += (uint64_t)is_interior;
    double krow = 0.0, kabs = 0.0, mrow = 0.0, arow = 0.0;
    for (uint64_t p = a.rowptr[r]; p < a.rowptr[r + 1]; p++) {
      pattern_same &= a.col[p] == a2.col[p];
      double kv = (8.0 * a.val[p] - a2.val[p]) / 6.0, mv = (a2.val[p] - 2.0 * a.val[p]) / 6.0;
      krow += kv;
      kabs += fabs(kv);
      mrow += mv;
      arow += a.val[p];
      if (mv < mmin) mmin = mv;
    }
    msum += mrow;
    asum += arow;
    if (fabs(krow) / kabs > ksum_err) ksum_err = fabs(krow) / kabs;
    /* Row sum of M = Σ_T∋node |T|/20·(2+1+1+1) = (#tets)·|T|/4, |T| = cell/6. */
    double share = tets_at_node(i, j, k, nx, ny, nz) * (cellvol / 6.0) / 4.0;
    if (fabs(mrow - share) / share > mrow_err) mrow_err = fabs(mrow - share) / share;
    /* Interior: 24 tets, so the row sum of K+M is exactly one cell volume. */
    if (is_interior && fabs(arow - cellvol) / cellvol > interior_err)
      interior_err = fabs(arow - cellvol) / cellvol;
  }
  snprintf(what, sizeof what, "p1tet %ux%ux%u: rows %u, nnz %" PRIu64 ", sorted unique columns",
           nx, ny, nz, a.nrows, a.nnz);
  check_true(csr_valid(&a) && a.nrows == mx * my * mz, "%s", what);
  check_true(rows_ok && pattern_same,
             "p1tet %ux%ux%u: every row has the 15-point pattern clipped to the box "
             "(%" PRIu64 " interior rows with exactly 15)",
             nx, ny, nz, interior);
  snprintf(what, sizeof what, "p1tet %ux%ux%u symmetric (max |a_ij - a_ji|, bitwise)", nx, ny, nz);
  check_le(what, csr_asym(&a), 0.0);
  snprintf(what, sizeof what, "p1tet %ux%ux%u stiffness annihilates constants (|ΣK_r|/Σ|K_r|)",
           nx, ny, nz);
  check_le(what, ksum_err, 1e-12);
  snprintf(what, sizeof what, "p1tet %ux%ux%u mass row sums = nodal volume share (rel)", nx, ny,
           nz);
  check_le(what, mrow_err, 1e-12);
  snprintf(what, sizeof what, "p1tet %ux%ux%u interior row sums of K+M = hx*hy*hz (rel)", nx, ny,
           nz);
  check_le(what, interior_err, 1e-12);
  snprintf(what, sizeof what, "p1tet %ux%ux%u sum of M = box volume (rel)", nx, ny, nz);
  check_le(what, fabs(msum - volume) / volume, 1e-12);
  snprintf(what, sizeof what, "p1tet %ux%ux%u sum of K+M = box volume (rel)", nx, ny, nz);
  check_le(what, fabs(asum - volume) / volume, 1e-12);
  check_true(mmin > 0.0, "p1tet mass entries all positive on the 15-point graph (min %g)", mmin);
  sessile_csr_free(&a);
  sessile_csr_free(&a2);
}

static void test_p1tet(void) {
  printf("-- p1tet\n");
  test_p1tet_on(4, 3, 5, 0.3, 0.5, 0.7);
  test_p1tet_on(1, 1, 1, 1.0, 2.0, 3.0);
  test_p1tet_on(6, 6, 6, 0.125, 0.125, 0.125);

  /* Cubic cells: the Kuhn P1 stiffness is exactly h·(7-point Laplacian); the
   * 8 face/body-diagonal couplings cancel to (explicit) zeros. */
  sessile_csr a, a2;
  const double h = 0.5;
  must(sessile_csr_p1tet(4, 4, 4, h, h, h, &a), "p1tet cubic");
  must(sessile_csr_p1tet(4, 4, 4, 2 * h, 2 * h, 2 * h, &a2), "p1tet cubic 2h");
  const uint32_t r = 2 + 5 * (2 + 5 * 2);
  double err = 0.0;
  for (uint64_t p = a.rowptr[r]; p < a.rowptr[r + 1]; p++) {
    double kv = (8.0 * a.val[p] - a2.val[p]) / 6.0;
    uint32_t c = a.col[p];
    uint32_t dist = c > r ? c - r : r - c;
    double expect = c == r ? 6.0 * h : (dist == 1 || dist == 5 || dist == 25) ? -h : 0.0;
    if (fabs(kv - expect) > err) err = fabs(kv - expect);
  }
  check_le("p1tet cubic h=0.5: interior K row = h*(6, -1 x6, 0 x8)", err, 1e-14);
  sessile_csr_free(&a);
  sessile_csr_free(&a2);

  double t0 = omp_get_wtime();
  must(sessile_csr_p1tet(64, 64, 64, 1.0 / 64, 1.0 / 64, 1.0 / 64, &a), "p1tet 64^3");
  double dt = omp_get_wtime() - t0;
  check_true(csr_valid(&a) && a.nrows == 65 * 65 * 65,
             "p1tet 64^3: %u rows, %" PRIu64 " nonzeros in %.3f s (%d threads)", a.nrows, a.nnz,
             dt, omp_get_max_threads());
  /* its time is printed, never asserted: tests do not time (sessile bench la does) */
  sessile_csr_free(&a);

  sessile_status s = sessile_csr_p1tet(2, 2, 2, 1.0, -1.0, 1.0, &a);
  check_true(s == SESSILE_ERR_USAGE, "p1tet with hy < 0 -> %s", sessile_status_name(s));
}

/* ---- random matrices and fills ---- */

static int csr_identical(const sessile_csr *a, const sessile_csr *b) {
  return a->nrows == b->nrows && a->nnz == b->nnz &&
         memcmp(a->rowptr, b->rowptr, (a->nrows + 1) * sizeof *a->rowptr) == 0 &&
         memcmp(a->col, b->col, a->nnz * sizeof *a->col) == 0 &&
         memcmp(a->val, b->val, a->nnz * sizeof *a->val) == 0;
}

static void test_random(void) {
  printf("-- random matrices / fill\n");
  sessile_csr a, b;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  must(sessile_csr_random(20000, 9, 1.5, 42, &a), "random");
  omp_set_num_threads(threads > 1 ? threads : 2);
  must(sessile_csr_random(20000, 9, 1.5, 42, &b), "random");
  omp_set_num_threads(threads);
  check_true(csr_valid(&a) && a.nnz == 20000u * 9, "random 20000 x 9/row: sorted unique columns");
  check_true(csr_identical(&a, &b), "random: identical with 1 and %d threads",
             threads > 1 ? threads : 2);
  double worst = INFINITY;
  int diag_ok = 1;
  for (uint32_t r = 0; r < a.nrows; r++) {
    double off = 0.0, dg = 0.0;
    int found = 0;
    for (uint64_t p = a.rowptr[r]; p < a.rowptr[r + 1]; p++) {
      if (a.col[p] == r) {
        dg = a.val[p];
        found = 1;
      } else {
        off += fabs(a.val[p]);
        diag_ok &= a.val[p] >= -1.0 && a.val[p] <= 1.0;
      }
    }
    diag_ok &= found;
    if (off > 0 && dg / off < worst) worst = dg / off;
  }
  check_true(diag_ok && fabs(worst - 1.5) < 1e-12,
             "random: diagonal present, off-diagonals in [-1,1], min a_rr/Σ|a_rj| = %.15g", worst);
  sessile_csr_free(&b);
  must(sessile_csr_random(20000, 9, 1.5, 43, &b), "random");
  check_true(!csr_identical(&a, &b), "random: another seed gives another matrix");
  sessile_csr_free(&a);
  sessile_csr_free(&b);
  must(sessile_csr_random(7, 100, 2.0, 1, &a), "random dense");
  check_true(csr_valid(&a) && a.nnz == 49, "random n=7 per_row=100: capped to dense 7x7");
  sessile_csr_free(&a);

  const uint64_t n = 100000;
  double *u = dalloc(n), *v = dalloc(n);
  omp_set_num_threads(1);
  sessile_fill_random(u, n, -2.0, 3.0, 9);
  omp_set_num_threads(threads > 1 ? threads : 2);
  sessile_fill_random(v, n, -2.0, 3.0, 9);
  omp_set_num_threads(threads);
  double lo = INFINITY, hi = -INFINITY, mean = 0.0;
  for (uint64_t i = 0; i < n; i++) {
    lo = fmin(lo, u[i]);
    hi = fmax(hi, u[i]);
    mean += u[i] / (double)n;
  }
  check_true(memcmp(u, v, n * sizeof *u) == 0 && lo >= -2.0 && hi < 3.0,
             "fill_random: in [-2,3) (min %.6f max %.6f), identical for 1 and N threads", lo, hi);
  check_le("fill_random: |mean - 0.5| for 1e5 samples", fabs(mean - 0.5), 0.03);
  free(u);
  free(v);
}

/* ---- vector kernels ---- */

static void test_vec(void) {
  printf("-- vector kernels\n");
  const uint64_t n = 1000000;
  double *x = dalloc(n), *y = dalloc(n), *w = dalloc(n), *t = dalloc(n);
  sessile_fill_random(x, n, -1.0, 1.0, 1);
  sessile_fill_random(y, n, -1.0, 1.0, 2);

  /* Element-wise kernels against direct loops (bitwise: same single op). */
  int ok = 1;
  sessile_ref_waxpy(n, 0.5, x, y, w);
  for (uint64_t i = 0; i < n; i++) ok &= w[i] == 0.5 * x[i] + y[i];
  sessile_ref_copy(n, y, t);
  sessile_ref_axpy(n, -3.0, x, t);
  for (uint64_t i = 0; i < n; i++) ok &= t[i] == y[i] + -3.0 * x[i];
  sessile_ref_copy(n, y, t);
  sessile_ref_aypx(n, 2.0, x, t);
  for (uint64_t i = 0; i < n; i++) ok &= t[i] == x[i] + 2.0 * y[i];
  sessile_ref_pmul(n, x, y, t);
  for (uint64_t i = 0; i < n; i++) ok &= t[i] == x[i] * y[i];
  sessile_ref_copy(n, x, t);
  sessile_ref_scale(n, -0.25, t);
  for (uint64_t i = 0; i < n; i++) ok &= t[i] == -0.25 * x[i];
  sessile_ref_fill(n, 7.0, t);
  for (uint64_t i = 0; i < n; i++) ok &= t[i] == 7.0;
  check_true(ok, "fill/copy/scale/axpy/aypx/waxpy/pmul match direct loops bitwise (n=1e6)");

  /* dot against a long double naive sum. */
  long double ref = 0.0L, refabs = 0.0L;
  for (uint64_t i = 0; i < n; i++) {
    ref += (long double)x[i] * (long double)y[i];
    refabs += fabsl((long double)x[i] * (long double)y[i]);
  }
  double d = sessile_ref_dot(n, x, y);
  printf("       dot = %.17g, long double = %.17Lg, cond = Σ|xy|/|Σxy| = %.3Lg\n", d, ref,
         refabs / fabsl(ref));
  check_le("dot vs long double naive sum, n=1e6 (relative)", (double)(fabsl((long double)d - ref) /
                                                                      fabsl(ref)),
           1e-14);
  long double nref = 0.0L;
  for (uint64_t i = 0; i < n; i++) nref += (long double)x[i] * x[i];
  check_le("nrm2 vs long double sqrt(Σx²), n=1e6 (relative)",
           (double)(fabsl((long double)sessile_ref_nrm2(n, x) - sqrtl(nref)) / sqrtl(nref)), 1e-15);

  /* Bitwise thread-count independence, also for lengths that split unevenly. */
  const int threads = omp_get_max_threads();
  const uint64_t lens[] = {n, 999983, 40000, 5000, 1};
  int same = 1;
  for (size_t l = 0; l < sizeof lens / sizeof lens[0]; l++) {
    omp_set_num_threads(1);
    double d1 = sessile_ref_dot(lens[l], x, y);
    for (int nt = 2; nt <= 4; nt++) {
      omp_set_num_threads(nt);
      double dn = sessile_ref_dot(lens[l], x, y);
      same &= memcmp(&d1, &dn, sizeof d1) == 0;
    }
  }
  omp_set_num_threads(threads);
  check_true(same, "dot bitwise identical with 1, 2, 3, 4 threads (n = 1e6, 999983, 4e4, 5e3, 1)");
  check_true(sessile_ref_dot(0, x, y) == 0.0, "dot of empty vectors is 0");
  free(x);
  free(y);
  free(w);
  free(t);
}

/* ---- SpMV and Jacobi ---- */

/* Scalar CSR of a BCSR4 matrix, to check the block kernels against. */
static void bcsr4_to_csr(const sessile_bcsr4 *b, sessile_csr *a) {
  must(sessile_csr_alloc(4 * b->nbrows, 4 * b->nbcols, 16 * b->nnzb, a), "expand bcsr4");
  uint64_t p = 0;
  for (uint32_t br = 0; br < b->nbrows; br++)
    for (int i = 0; i < 4; i++) {
      for (uint64_t k = b->rowptr[br]; k < b->rowptr[br + 1]; k++)
        for (int j = 0; j < 4; j++) {
          a->col[p] = 4 * b->col[k] + (uint32_t)j;
          a->val[p++] = b->val[16 * k + 4 * i + j];
        }
      a->rowptr[4 * br + i + 1] = p;
    }
}

static void test_spmv(void) {
  printf("-- SpMV / Jacobi\n");
  sessile_csr a;
  must(sessile_csr_random(50000, 12, 1.2, 5, &a), "random");
  double *x = dalloc(4 * (uint64_t)a.nrows), *y = dalloc(4 * (uint64_t)a.nrows),
         *z = dalloc(4 * (uint64_t)a.nrows);
  sessile_fill_random(x, a.nrows, -1.0, 1.0, 3);
  sessile_ref_spmv_csr(&a, x, y);
  double err = 0.0;
  for (uint32_t r = 0; r < a.nrows; r++) {
    long double s = 0.0L;
    for (uint64_t p = a.rowptr[r]; p < a.rowptr[r + 1]; p++)
      s += (long double)a.val[p] * x[a.col[p]];
    err = fmax(err, (double)fabsl(s - y[r]));
  }
  check_le("spmv_csr vs long double rows (random 5e4 x 12/row), max abs", err, 1e-13);
  double rr = sessile_ref_true_relres(&a, y, x);
  check_le("true_relres(A, A x, x)", rr, 1e-15);

  /* BCSR4 on the random pattern vs its scalar expansion. */
  sessile_bcsr4 b;
  sessile_csr e;
  must(sessile_bcsr4_random_on(&a, 77, &b), "bcsr4_random_on");
  bcsr4_to_csr(&b, &e);
  check_true(csr_valid(&e), "bcsr4 expansion is a valid CSR (%" PRIu64 " blocks)", b.nnzb);
  sessile_fill_random(x, e.nrows, -1.0, 1.0, 4);
  sessile_ref_spmv_bcsr4(&b, x, y);
  sessile_ref_spmv_csr(&e, x, z);
  check_le("spmv_bcsr4 vs spmv_csr of the expanded matrix, max abs", max_abs_diff(e.nrows, y, z),
           1e-12);
  must(sessile_ref_jacobi_bcsr4(&b, y), "jacobi_bcsr4");
  must(sessile_ref_jacobi_csr(&e, z), "jacobi_csr");
  check_le("jacobi_bcsr4 vs jacobi_csr of the expansion, max abs", max_abs_diff(e.nrows, y, z),
           0.0);
  /* Dominant scalar diagonal: Jacobi on the block matrix must contract. */
  double dmin = INFINITY;
  for (uint32_t r = 0; r < e.nrows; r++) {
    double off = 0.0, dg = 0.0;
    for (uint64_t p = e.rowptr[r]; p < e.rowptr[r + 1]; p++)
      if (e.col[p] == r) dg = e.val[p];
      else off += fabs(e.val[p]);
    dmin = fmin(dmin, dg / off);
  }
  check_le("bcsr4_random_on: 2 - min diag/offdiag ratio", fabs(2.0 - dmin), 1e-12);
  sessile_bcsr4_free(&b);
  sessile_csr_free(&e);

  /* Jacobi names the failing row. */
  a.val[a.rowptr[1234]] = 0.0; /* may or may not be the diagonal: find it */
  for (uint64_t p = a.rowptr[1234]; p < a.rowptr[1235]; p++)
    if (a.col[p] == 1234) a.val[p] = 0.0;
  sessile_error_clear();
  sessile_status s = sessile_ref_jacobi_csr(&a, y);
  check_true(s == SESSILE_ERR_NUMERIC && strstr(sessile_error_message(), "row 1234") != NULL,
             "jacobi_csr with a zero diagonal -> %s: \"%.70s...\"", sessile_status_name(s),
             sessile_error_message());
  sessile_csr_free(&a);
  free(x);
  free(y);
  free(z);
}

/* ---- solvers ---- */

static const char *solve_status_name(sessile_ref_solve_status s) {
  return s == SESSILE_REF_CONVERGED ? "converged" : s == SESSILE_REF_MAX_ITER ? "max_iter"
                                                                               : "breakdown";
}

static void report_solve(const char *what, sessile_ref_result r, uint64_t n, const double *x,
                         double tol) {
  char buf[160];
  snprintf(buf, sizeof buf, "%s: %s in %d it, true relres", what, solve_status_name(r.status),
           r.iterations);
  const int ok = r.status == SESSILE_REF_CONVERGED && all_finite(n, x);
  check_le(buf, ok ? r.true_relres : (double)INFINITY, tol);
}

static void test_solvers(void) {
  printf("-- solvers\n");
  const double rtol = 1e-9, want = 1e-8;
  sessile_csr a;
  must(sessile_csr_laplacian7(16, 16, 16, &a), "laplacian7");
  const uint64_t n = a.nrows;
  double *b = dalloc(n), *x = dalloc(n), *x2 = dalloc(n), *dinv = dalloc(n);
  sessile_fill_random(b, n, -1.0, 1.0, 11);
  must(sessile_ref_jacobi_csr(&a, dinv), "jacobi");

  sessile_ref_fill(n, 0.0, x);
  sessile_ref_result r = sessile_ref_pcg(&a, dinv, b, x, rtol, 1000);
  report_solve("PCG(Jacobi) laplacian7 16^3", r, n, x, want);
  sessile_ref_fill(n, 0.0, x);
  r = sessile_ref_pcg(&a, NULL, b, x, rtol, 1000);
  report_solve("CG (no preconditioner) laplacian7 16^3", r, n, x, want);

  /* The whole solve is thread-count independent, not only dot. */
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  sessile_ref_fill(n, 0.0, x2);
  sessile_ref_result r1 = sessile_ref_pcg(&a, NULL, b, x2, rtol, 1000);
  omp_set_num_threads(threads);
  check_true(r1.iterations == r.iterations && memcmp(x, x2, n * sizeof *x) == 0,
             "CG: same iterations (%d) and bitwise same x with 1 and %d threads", r1.iterations,
             threads);

  /* Zero right-hand side: x = 0 exactly, converged at once. */
  sessile_ref_fill(n, 0.0, b);
  sessile_ref_fill(n, 3.0, x);
  r = sessile_ref_pcg(&a, dinv, b, x, rtol, 1000);
  check_true(r.status == SESSILE_REF_CONVERGED && r.iterations == 0 && r.true_relres == 0.0 &&
                 max_abs(n, x) == 0.0,
             "PCG b=0: %s, %d iterations, true_relres %g, max|x| %g", solve_status_name(r.status),
             r.iterations, r.true_relres, max_abs(n, x));
  sessile_ref_fill(n, 3.0, x);
  r = sessile_ref_bicgstab(&a, dinv, b, x, rtol, 1000);
  r1 = sessile_ref_gmres(&a, dinv, b, x2, rtol, 1000, 30);
  check_true(r.status == SESSILE_REF_CONVERGED && r.iterations == 0 && max_abs(n, x) == 0.0 &&
                 r1.status == SESSILE_REF_CONVERGED && r1.iterations == 0 && max_abs(n, x2) == 0.0,
             "BiCGSTAB and GMRES b=0: converged in 0 iterations with x = 0");

  /* Initial guess already the solution: 0 iterations. */
  sessile_fill_random(x, n, -1.0, 1.0, 12);
  sessile_ref_spmv_csr(&a, x, b);
  r = sessile_ref_pcg(&a, dinv, b, x, rtol, 1000);
  check_true(r.status == SESSILE_REF_CONVERGED && r.iterations == 0,
             "PCG with the exact solution as initial guess: %s in %d iterations",
             solve_status_name(r.status), r.iterations);

  /* Indefinite: laplacian7 − 10 I (eigenvalues in (−10, 2)). */
  for (uint32_t row = 0; row < a.nrows; row++)
    for (uint64_t p = a.rowptr[row]; p < a.rowptr[row + 1]; p++)
      if (a.col[p] == row) a.val[p] -= 10.0;
  sessile_fill_random(b, n, -1.0, 1.0, 13);
  must(sessile_ref_jacobi_csr(&a, dinv), "jacobi indefinite");
  for (int pre = 0; pre < 2; pre++) {
    sessile_ref_fill(n, 0.0, x);
    sessile_error_clear();
    r = sessile_ref_pcg(&a, pre ? dinv : NULL, b, x, rtol, 500);
    check_true((r.status == SESSILE_REF_BREAKDOWN || r.status == SESSILE_REF_MAX_ITER) &&
                   all_finite(n, x) && isfinite(r.true_relres),
               "CG%s on laplacian7 - 10I: %s after %d it, x finite, relres %.3g (\"%.50s...\")",
               pre ? " (Jacobi)" : "", solve_status_name(r.status), r.iterations, r.true_relres,
               sessile_error_message());
  }
  /* Restarted GMRES may stagnate on an indefinite matrix, but it never
   * increases the residual and never produces a non-finite x. */
  sessile_ref_fill(n, 0.0, x);
  r = sessile_ref_gmres(&a, dinv, b, x, rtol, 600, 30);
  check_true(r.status != SESSILE_REF_BREAKDOWN && all_finite(n, x) && r.true_relres <= 1.0,
             "GMRES(30) on laplacian7 - 10I: %s after %d it, x finite, relres %.3g <= 1",
             solve_status_name(r.status), r.iterations, r.true_relres);
  sessile_csr_free(&a);

  /* Nonsymmetric: convection-diffusion, Pe = 2. */
  must(sessile_csr_convdiff(16, 16, 16, 2.0, &a), "convdiff");
  must(sessile_ref_jacobi_csr(&a, dinv), "jacobi convdiff");
  sessile_fill_random(b, n, -1.0, 1.0, 14);
  for (int pre = 0; pre < 2; pre++) {
    char what[96];
    sessile_ref_fill(n, 0.0, x);
    r = sessile_ref_bicgstab(&a, pre ? dinv : NULL, b, x, rtol, 1000);
    snprintf(what, sizeof what, "BiCGSTAB%s convdiff 16^3 Pe=2", pre ? "(Jacobi)" : "");
    report_solve(what, r, n, x, want);
    sessile_ref_fill(n, 0.0, x);
    r = sessile_ref_gmres(&a, pre ? dinv : NULL, b, x, rtol, 3000, 30);
    snprintf(what, sizeof what, "GMRES(30)%s convdiff 16^3 Pe=2", pre ? "(Jacobi)" : "");
    report_solve(what, r, n, x, want);
  }
  /* A starved budget reports max_iter with a finite x and the right count. */
  sessile_ref_fill(n, 0.0, x);
  r = sessile_ref_gmres(&a, dinv, b, x, rtol, 45, 30);
  check_true(r.status == SESSILE_REF_MAX_ITER && r.iterations == 45 && all_finite(n, x) &&
                 r.true_relres < 1.0,
             "GMRES(30) with max_it 45: %s after %d Arnoldi steps, relres %.3g",
             solve_status_name(r.status), r.iterations, r.true_relres);
  sessile_csr_free(&a);

  /* Singular (zero) matrix and a NaN right-hand side: every solver reports
   * breakdown and leaves x as it was, finite. */
  must(sessile_csr_laplacian7(16, 16, 16, &a), "laplacian7");
  sessile_ref_fill(a.nnz, 0.0, a.val);
  int held = 1;
  for (int which = 0; which < 3; which++)
    for (int nan_b = 0; nan_b < 2; nan_b++) {
      sessile_fill_random(b, n, -1.0, 1.0, 16);
      if (nan_b) b[77] = NAN;
      sessile_ref_fill(n, 0.5, x);
      r = which == 0   ? sessile_ref_pcg(&a, NULL, b, x, rtol, 100)
          : which == 1 ? sessile_ref_bicgstab(&a, NULL, b, x, rtol, 100)
                       : sessile_ref_gmres(&a, NULL, b, x, rtol, 100, 10);
      held &= r.status == SESSILE_REF_BREAKDOWN && all_finite(n, x) && max_abs(n, x) == 0.5 &&
              min_abs(n, x) == 0.5;
    }
  check_true(held, "CG/BiCGSTAB/GMRES on A = 0 and with NaN in b: breakdown, x unchanged");
  sessile_csr_free(&a);

  /* SPD P1 matrix: PCG converges. */
  must(sessile_csr_p1tet(12, 12, 12, 1.0 / 12, 1.0 / 12, 1.0 / 12, &a), "p1tet");
  const uint64_t m = a.nrows;
  double *bp = dalloc(m), *xp = dalloc(m), *dp = dalloc(m);
  sessile_fill_random(bp, m, -1.0, 1.0, 15);
  sessile_ref_fill(m, 0.0, xp);
  must(sessile_ref_jacobi_csr(&a, dp), "jacobi p1tet");
  r = sessile_ref_pcg(&a, dp, bp, xp, rtol, 2000);
  report_solve("PCG(Jacobi) p1tet 12^3 (K+M, SPD)", r, m, xp, want);
  sessile_csr_free(&a);
  free(bp);
  free(xp);
  free(dp);

  free(b);
  free(x);
  free(x2);
  free(dinv);
}

int main(void) {
  printf("sessile reference tests (%d OpenMP threads)\n", omp_get_max_threads());
  test_status();
  test_stencil7();
  test_p1tet();
  test_random();
  test_vec();
  test_spmv();
  test_solvers();
  printf("%d checks, %d failed\n", checks, failures);
  return failures ? 1 : 0;
}
