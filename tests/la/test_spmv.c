/* GPU SpMV (sessile_mat_mult) and Jacobi (sessile_mat_jacobi) against the
 * plain-C references sessile_ref_spmv_csr / _bcsr4 and sessile_ref_jacobi_*,
 * on random matrices with 1, 7 and 33 entries per row (rows of 1..33 entries
 * exercise every padding length to a multiple of 4), the 7-point Laplacian
 * 32^3, the P1-tetrahedra K+M on 32^3 cubes and a 4x4 block-CSR matrix on
 * the P1 pattern; plus the error paths of matrix creation and Jacobi.
 *
 * SpMV error measure: max_i |y_i - yref_i| / sum_j |a_ij x_j|, the
 * row-wise relative error that any summation order is bounded by
 * (k eps sum_j |a_ij x_j| for k terms).  Tolerances: fp64 1e-14 (k <= 64 for
 * the block rows, 64 * 1.1e-16 = 7e-15); fp32 path 1e-5 (values and x are
 * stored in float: ~2 * 6e-8 per product, plus k float roundings).
 * Jacobi: 1/a_ii once rounded; fp64 tolerance 2.3e-16 relative (1 ulp),
 * fp32 1e-5. */
#include <inttypes.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/la/la_ref.h"
#include "testutil.h"

static sessile_la *la;
static int fp64;
static double tol_spmv, tol_jac;

/* Rounds host values to what an fp32 context stores, so that the reference
 * computes with exactly the device's operands. */
static void to_stored(double *v, uint64_t n) {
  if (!fp64)
    for (uint64_t i = 0; i < n; i++) v[i] = (double)(float)v[i];
}

static double stored(double v) { return fp64 ? v : (double)(float)v; }

/* max_i |y_i - r_i| / s_i, s_i = sum_j |a_ij x_j| (or 1 for empty rows). */
static double rowwise_err(uint32_t n, const double *y, const double *r, const double *s) {
  double e = 0;
  for (uint32_t i = 0; i < n; i++) {
    double d = fabs(y[i] - r[i]) / (s[i] > 0 ? s[i] : 1.0);
    if (!(d <= e)) e = d; /* propagates NaN */
  }
  return e;
}

/* y = A x on the GPU vs sessile_ref_spmv_csr. */
static void check_csr(const char *name, sessile_csr *a, uint64_t seed) {
  char what[160];
  const uint32_t n = a->nrows;
  to_stored(a->val, a->nnz);
  double *x = t_dalloc(n), *y = t_dalloc(n), *r = t_dalloc(n), *s = t_dalloc(n);
  sessile_fill_random(x, n, -1.0, 1.0, seed);
  to_stored(x, n);
  sessile_mat *m = NULL;
  sessile_vec *vx = NULL, *vy = NULL;
  t_must("mat_create_csr", sessile_mat_create_csr(la, a, &m));
  t_must("vec_create", sessile_vec_create(la, n, &vx));
  t_must("vec_create", sessile_vec_create(la, n, &vy));
  t_must("upload", sessile_vec_upload(vx, x));
  snprintf(what, sizeof what, "%s: mat_rows = %u, mat_nnz = %" PRIu64 " (before padding)", name, n,
           a->nnz);
  t_true(what, sessile_mat_rows(m) == n && sessile_mat_nnz(m) == a->nnz);
  t_must("mat_mult", sessile_mat_mult(la, m, vx, vy));
  t_must("download", sessile_vec_download(vy, y));
  sessile_ref_spmv_csr(a, x, r);
  for (uint32_t i = 0; i < n; i++) {
    s[i] = 0;
    for (uint64_t p = a->rowptr[i]; p < a->rowptr[i + 1]; p++) s[i] += fabs(a->val[p] * x[a->col[p]]);
  }
  snprintf(what, sizeof what, "%s: SpMV vs ref_spmv_csr (row-wise rel.)", name);
  t_check(what, rowwise_err(n, y, r, s), tol_spmv);

  /* A second product into the same y overwrites it completely. */
  for (uint32_t i = 0; i < n; i++) x[i] = stored(-0.5 * x[i]);
  t_must("upload", sessile_vec_upload(vx, x));
  t_must("mat_mult", sessile_mat_mult(la, m, vx, vy));
  t_must("download", sessile_vec_download(vy, y));
  sessile_ref_spmv_csr(a, x, r);
  for (uint32_t i = 0; i < n; i++) s[i] *= 0.5;
  snprintf(what, sizeof what, "%s: second SpMV (x *= -0.5) into the same y", name);
  t_check(what, rowwise_err(n, y, r, s), tol_spmv);

  sessile_mat_destroy(m);
  sessile_vec_destroy(vx);
  sessile_vec_destroy(vy);
  free(x);
  free(y);
  free(r);
  free(s);
}

/* GPU Jacobi vs sessile_ref_jacobi_csr. */
static void check_jacobi_csr(const char *name, const sessile_csr *a) {
  char what[160];
  const uint32_t n = a->nrows;
  double *d = t_dalloc(n), *r = t_dalloc(n);
  sessile_mat *m = NULL;
  sessile_vec *v = NULL;
  t_must("mat_create_csr", sessile_mat_create_csr(la, a, &m));
  t_must("vec_create", sessile_vec_create(la, n, &v));
  t_ok("mat_jacobi", sessile_mat_jacobi(la, m, v));
  t_must("download", sessile_vec_download(v, d));
  t_must("ref_jacobi_csr", sessile_ref_jacobi_csr(a, r));
  snprintf(what, sizeof what, "%s: Jacobi vs ref_jacobi_csr (max rel.)", name);
  double e = 0;
  for (uint32_t i = 0; i < n; i++) {
    double q = fabs(d[i] - r[i]) / fabs(r[i]);
    if (!(q <= e)) e = q;
  }
  t_check(what, e, tol_jac);
  sessile_vec_destroy(v);
  sessile_mat_destroy(m);
  free(d);
  free(r);
}

static void test_random(void) {
  const uint32_t ns[] = {1000, 50000}, per[] = {1, 7, 33};
  for (size_t i = 0; i < 2; i++)
    for (size_t j = 0; j < 3; j++) {
      char name[96];
      sessile_csr a;
      t_must("csr_random", sessile_csr_random(ns[i], per[j], 1.5, 31 * i + j + 1, &a));
      /* Row lengths seen, to show that the padding cases are covered. */
      uint64_t lmin = UINT64_MAX, lmax = 0, mod[4] = {0};
      for (uint32_t r = 0; r < a.nrows; r++) {
        uint64_t l = a.rowptr[r + 1] - a.rowptr[r];
        lmin = l < lmin ? l : lmin;
        lmax = l > lmax ? l : lmax;
        mod[l % 4]++;
      }
      snprintf(name, sizeof name, "random n=%u per_row=%u", ns[i], per[j]);
      printf("-- %s: nnz %" PRIu64 ", row lengths %" PRIu64 "..%" PRIu64
             ", rows with len%%4 = 0/1/2/3: %" PRIu64 "/%" PRIu64 "/%" PRIu64 "/%" PRIu64 "\n",
             name, a.nnz, lmin, lmax, mod[0], mod[1], mod[2], mod[3]);
      check_csr(name, &a, 1000 + i * 10 + j);
      if (i == 0) check_jacobi_csr(name, &a);
      sessile_csr_free(&a);
    }
}

/* SELL-8 storage pads each row to the widest row of its slice of 8: rows of
 * lengths 0..13 mixed inside slices, empty rows, and a last slice of 3 rows. */
static void test_ragged_slices(void) {
  const uint32_t n = 19;
  uint64_t nnz = 0;
  for (uint32_t r = 0; r < n; r++) nnz += (r * 5) % 14;
  sessile_csr a;
  t_must("csr_alloc", sessile_csr_alloc(n, n, nnz, &a));
  uint64_t k = 0;
  a.rowptr[0] = 0;
  for (uint32_t r = 0; r < n; r++) {
    uint32_t len = (r * 5) % 14; /* 0, 5, 10, 1, 6, 11, 2, ... ; row 0 and 14 empty */
    for (uint32_t j = 0; j < len; j++, k++) {
      a.col[k] = (r + 2 * j) % n; /* 2 is invertible mod 19: distinct for j < 19 */
      a.val[k] = 1.0 + 0.25 * (double)j - 0.125 * (double)r;
    }
    a.rowptr[r + 1] = k;
  }
  int distinct = 1;
  for (uint32_t r = 0; r < n; r++)
    for (uint64_t p = a.rowptr[r]; p < a.rowptr[r + 1]; p++)
      for (uint64_t q = a.rowptr[r]; q < p; q++) distinct &= a.col[p] != a.col[q];
  t_true("ragged 19 rows: columns distinct within each row", distinct);
  printf("-- ragged slices: 19 rows of lengths 0..13, rows 0 and 14 empty, last slice 3 rows\n");
  check_csr("ragged 19 rows", &a, 77);
  sessile_csr_free(&a);
}

static void test_structured(void) {
  sessile_csr a;
  printf("-- laplacian7 32^3\n");
  t_must("laplacian7", sessile_csr_laplacian7(32, 32, 32, &a));
  check_csr("laplacian7 32^3", &a, 7);
  check_jacobi_csr("laplacian7 32^3", &a);
  sessile_csr_free(&a);

  printf("-- p1tet K+M on 32^3 cubes (33^3 = 35937 rows)\n");
  t_must("p1tet", sessile_csr_p1tet(32, 32, 32, 1.0 / 32, 1.0 / 32, 1.0 / 32, &a));
  t_true("p1tet 32^3 has 33^3 rows", a.nrows == 33u * 33u * 33u);
  check_csr("p1tet 32^3", &a, 8);
  check_jacobi_csr("p1tet 32^3", &a);
  sessile_csr_free(&a);

  printf("-- convdiff 32^3 Pe=2 (nonsymmetric)\n");
  t_must("convdiff", sessile_csr_convdiff(32, 32, 32, 2.0, &a));
  check_csr("convdiff 32^3", &a, 9);
  sessile_csr_free(&a);
}

/* The texel path's block SpMV result, compared bit for bit with the
 * storage path's (the same arithmetic in the same order). */
static double *bcsr4_y_texel;

static void test_bcsr4(void) {
  printf("-- 4x4 block CSR on the p1tet 16^3 pattern\n");
  char what[160];
  sessile_csr pat;
  sessile_bcsr4 b;
  t_must("p1tet", sessile_csr_p1tet(16, 16, 16, 1.0 / 16, 1.0 / 16, 1.0 / 16, &pat));
  t_must("bcsr4_random_on", sessile_bcsr4_random_on(&pat, 4242, &b));
  to_stored(b.val, 16 * b.nnzb);
  const uint32_t n = 4 * b.nbrows;
  double *x = t_dalloc(n), *y = t_dalloc(n), *r = t_dalloc(n), *s = t_dalloc(n);
  sessile_fill_random(x, n, -1.0, 1.0, 11);
  to_stored(x, n);
  sessile_mat *m = NULL;
  sessile_vec *vx = NULL, *vy = NULL;
  t_must("mat_create_bcsr4", sessile_mat_create_bcsr4(la, &b, &m));
  t_must("vec_create", sessile_vec_create(la, n, &vx));
  t_must("vec_create", sessile_vec_create(la, n, &vy));
  t_must("upload", sessile_vec_upload(vx, x));
  snprintf(what, sizeof what, "bcsr4 p1tet 16^3: mat_rows = %u (4 x %u), mat_nnz = 16 x %" PRIu64,
           n, b.nbrows, b.nnzb);
  t_true(what, sessile_mat_rows(m) == n && sessile_mat_nnz(m) == 16 * b.nnzb);
  t_must("mat_mult", sessile_mat_mult(la, m, vx, vy));
  t_must("download", sessile_vec_download(vy, y));
  sessile_ref_spmv_bcsr4(&b, x, r);
  for (uint32_t br = 0; br < b.nbrows; br++)
    for (int i = 0; i < 4; i++) {
      double t = 0;
      for (uint64_t k = b.rowptr[br]; k < b.rowptr[br + 1]; k++)
        for (int j = 0; j < 4; j++) t += fabs(b.val[16 * k + 4 * i + j] * x[4 * b.col[k] + j]);
      s[4 * br + i] = t;
    }
  t_check("bcsr4 p1tet 16^3: SpMV vs ref_spmv_bcsr4 (row-wise rel.)", rowwise_err(n, y, r, s),
          tol_spmv);
  if (!bcsr4_y_texel) {
    bcsr4_y_texel = t_dalloc(n);
    memcpy(bcsr4_y_texel, y, n * sizeof *y);
  } else {
    t_true("bcsr4 p1tet 16^3: the storage path's SpMV equals the texel path's bit for bit",
           memcmp(bcsr4_y_texel, y, n * sizeof *y) == 0);
    free(bcsr4_y_texel);
    bcsr4_y_texel = NULL;
  }

  /* Point Jacobi of the block matrix vs ref_jacobi_bcsr4. */
  sessile_vec *vd = NULL;
  t_must("vec_create", sessile_vec_create(la, n, &vd));
  t_ok("mat_jacobi bcsr4", sessile_mat_jacobi(la, m, vd));
  t_must("download", sessile_vec_download(vd, y));
  t_must("ref_jacobi_bcsr4", sessile_ref_jacobi_bcsr4(&b, r));
  double e = 0;
  for (uint32_t i = 0; i < n; i++) {
    double q = fabs(y[i] - r[i]) / fabs(r[i]);
    if (!(q <= e)) e = q;
  }
  t_check("bcsr4 p1tet 16^3: Jacobi vs ref_jacobi_bcsr4 (max rel.)", e, tol_jac);

  /* Wrong vector lengths are usage errors. */
  sessile_vec *small = NULL;
  t_must("vec_create", sessile_vec_create(la, n - 4, &small));
  sessile_status st = sessile_mat_mult(la, m, small, vy);
  t_true("mat_mult with x of the wrong length -> SESSILE_ERR_USAGE", st == SESSILE_ERR_USAGE);
  st = sessile_mat_mult(la, m, vx, small);
  t_true("mat_mult with y of the wrong length -> SESSILE_ERR_USAGE", st == SESSILE_ERR_USAGE);
  st = sessile_mat_jacobi(la, m, small);
  t_true("mat_jacobi with dinv of the wrong length -> SESSILE_ERR_USAGE", st == SESSILE_ERR_USAGE);

  /* Block-matrix creation errors. */
  sessile_mat *bad = (sessile_mat *)&bad;
  uint32_t keep = b.nbcols;
  b.nbcols = keep + 1;
  st = sessile_mat_create_bcsr4(la, &b, &bad);
  t_true("mat_create_bcsr4 non-square (nbcols = nbrows + 1) -> SESSILE_ERR_USAGE, *out = NULL",
         st == SESSILE_ERR_USAGE && bad == NULL);
  b.nbcols = keep;
  uint32_t kc = b.col[5];
  b.col[5] = b.nbcols;
  bad = (sessile_mat *)&bad;
  st = sessile_mat_create_bcsr4(la, &b, &bad);
  t_true("mat_create_bcsr4 block column == nbcols -> SESSILE_ERR_USAGE", st == SESSILE_ERR_USAGE && bad == NULL);
  b.col[5] = kc;

  sessile_vec_destroy(small);
  sessile_vec_destroy(vd);
  sessile_vec_destroy(vx);
  sessile_vec_destroy(vy);
  sessile_mat_destroy(m);
  sessile_bcsr4_free(&b);
  sessile_csr_free(&pat);
  free(x);
  free(y);
  free(r);
  free(s);
}

/* Index of the diagonal entry of row r, or UINT64_MAX. */
static uint64_t diag_at(const sessile_csr *a, uint32_t r) {
  for (uint64_t p = a->rowptr[r]; p < a->rowptr[r + 1]; p++)
    if (a->col[p] == r) return p;
  return UINT64_MAX;
}

static void test_errors(void) {
  printf("-- matrix errors\n");
  char what[256];
  sessile_csr a;
  t_must("laplacian7", sessile_csr_laplacian7(8, 8, 8, &a));

  /* Zero diagonal: creation is fine, Jacobi fails naming the row. */
  uint64_t p = diag_at(&a, 77);
  a.val[p] = 0.0;
  sessile_mat *m = NULL;
  sessile_vec *d = NULL;
  t_ok("mat_create_csr with a zero diagonal", sessile_mat_create_csr(la, &a, &m));
  t_must("vec_create", sessile_vec_create(la, a.nrows, &d));
  sessile_error_clear();
  sessile_status s = m ? sessile_mat_jacobi(la, m, d) : SESSILE_ERR_INTERNAL;
  snprintf(what, sizeof what, "zero diagonal in row 77: mat_jacobi -> %s (\"%s\")",
           sessile_status_name(s), sessile_error_message());
  t_true(what, s == SESSILE_ERR_NUMERIC);
  t_true("  ... the message names row 77", strstr(sessile_error_message(), "77") != NULL);
  sessile_mat_destroy(m);
  m = NULL;
  a.val[p] = NAN;
  t_ok("mat_create_csr with a NaN diagonal", sessile_mat_create_csr(la, &a, &m));
  s = m ? sessile_mat_jacobi(la, m, d) : SESSILE_ERR_INTERNAL;
  snprintf(what, sizeof what, "NaN diagonal in row 77: mat_jacobi -> %s", sessile_status_name(s));
  t_true(what, s == SESSILE_ERR_NUMERIC);
  sessile_mat_destroy(m);
  m = NULL;
  a.val[p] = 6.0;

  /* A row without a stored diagonal is a zero diagonal too. */
  sessile_csr nd;
  t_must("csr_alloc", sessile_csr_alloc(3, 3, 3, &nd));
  nd.rowptr[0] = 0, nd.rowptr[1] = 1, nd.rowptr[2] = 2, nd.rowptr[3] = 3;
  nd.col[0] = 0, nd.col[1] = 0, nd.col[2] = 2; /* row 1 has only column 0 */
  nd.val[0] = 1, nd.val[1] = 1, nd.val[2] = 1;
  sessile_vec *d3 = NULL;
  t_must("vec_create", sessile_vec_create(la, 3, &d3));
  t_ok("mat_create_csr 3x3 without a_11", sessile_mat_create_csr(la, &nd, &m));
  s = m ? sessile_mat_jacobi(la, m, d3) : SESSILE_ERR_INTERNAL;
  snprintf(what, sizeof what, "row 1 without a stored diagonal: mat_jacobi -> %s (\"%s\")",
           sessile_status_name(s), sessile_error_message());
  t_true(what, s == SESSILE_ERR_NUMERIC);
  sessile_mat_destroy(m);
  m = NULL;
  sessile_vec_destroy(d3);
  sessile_csr_free(&nd);

  /* Non-square. */
  sessile_csr ns;
  t_must("csr_alloc", sessile_csr_alloc(4, 5, 4, &ns));
  for (uint32_t r = 0; r < 4; r++) ns.rowptr[r + 1] = r + 1, ns.col[r] = r, ns.val[r] = 1;
  m = (sessile_mat *)&m;
  sessile_error_clear();
  s = sessile_mat_create_csr(la, &ns, &m);
  snprintf(what, sizeof what, "mat_create_csr 4x5 -> %s, *out = NULL (\"%s\")",
           sessile_status_name(s), sessile_error_message());
  t_true(what, s == SESSILE_ERR_USAGE && m == NULL);
  sessile_csr_free(&ns);

  /* Column out of range. */
  uint32_t kc = a.col[a.rowptr[100] + 1];
  a.col[a.rowptr[100] + 1] = a.ncols;
  m = (sessile_mat *)&m;
  sessile_error_clear();
  s = sessile_mat_create_csr(la, &a, &m);
  snprintf(what, sizeof what, "mat_create_csr with column %u (= ncols) in row 100 -> %s (\"%s\")",
           a.ncols, sessile_status_name(s), sessile_error_message());
  t_true(what, s == SESSILE_ERR_USAGE && m == NULL);
  a.col[a.rowptr[100] + 1] = kc;

  /* Inconsistent row pointers. */
  a.rowptr[a.nrows] = a.nnz - 1;
  m = (sessile_mat *)&m;
  s = sessile_mat_create_csr(la, &a, &m);
  snprintf(what, sizeof what, "mat_create_csr with rowptr[n] != nnz -> %s", sessile_status_name(s));
  t_true(what, s == SESSILE_ERR_USAGE && m == NULL);
  a.rowptr[a.nrows] = a.nnz;

  /* SpMV with wrong lengths. */
  m = NULL;
  t_must("mat_create_csr", sessile_mat_create_csr(la, &a, &m));
  sessile_vec *v5 = NULL;
  t_must("vec_create", sessile_vec_create(la, 5, &v5));
  s = sessile_mat_mult(la, m, v5, d);
  t_true("csr mat_mult with x of length 5 for 512 rows -> SESSILE_ERR_USAGE", s == SESSILE_ERR_USAGE);
  sessile_mat_destroy(m);
  sessile_vec_destroy(v5);
  sessile_vec_destroy(d);
  sessile_csr_free(&a);
}

/* A non-finite x_j may only reach the rows that reference column j: the
 * reference gives finite values everywhere else. */
static void test_nonfinite_x(void) {
  printf("-- non-finite entry in x\n");
  sessile_csr a;
  t_must("laplacian7", sessile_csr_laplacian7(8, 8, 8, &a));
  const uint32_t n = a.nrows;
  double *x = t_dalloc(n), *y = t_dalloc(n), *r = t_dalloc(n);
  sessile_fill_random(x, n, -1.0, 1.0, 5);
  to_stored(x, n);
  x[0] = INFINITY;
  sessile_mat *m = NULL;
  sessile_vec *vx = NULL, *vy = NULL;
  t_must("mat_create_csr", sessile_mat_create_csr(la, &a, &m));
  t_must("vec_create", sessile_vec_create(la, n, &vx));
  t_must("vec_create", sessile_vec_create(la, n, &vy));
  t_must("upload", sessile_vec_upload(vx, x));
  t_must("mat_mult", sessile_mat_mult(la, m, vx, vy));
  t_must("download", sessile_vec_download(vy, y));
  sessile_ref_spmv_csr(&a, x, r);
  uint32_t bad = 0, first = UINT32_MAX, refnf = 0;
  for (uint32_t i = 0; i < n; i++) {
    refnf += !isfinite(r[i]);
    int same = (isnan(y[i]) && isnan(r[i])) || y[i] == r[i] ||
               fabs(y[i] - r[i]) <= tol_spmv * 20.0; /* |a x| sums are <= 12 here */
    if (!same) {
      bad++;
      if (first == UINT32_MAX) first = i;
    }
  }
  printf("   x[0] = inf: reference has %u non-finite rows (those that reference column 0); "
         "GPU differs in %u rows (first: row %d, y = %g, ref = %g)\n",
         refnf, bad, first == UINT32_MAX ? -1 : (int)first,
         first == UINT32_MAX ? 0.0 : y[first], first == UINT32_MAX ? 0.0 : r[first]);
  t_true("x[0] = inf: GPU SpMV matches ref_spmv_csr in every row (non-finite only where the "
         "row references column 0)",
         bad == 0);
  sessile_mat_destroy(m);
  sessile_vec_destroy(vx);
  sessile_vec_destroy(vy);
  sessile_csr_free(&a);
  free(x);
  free(y);
  free(r);
}

/* PCG (whose p·Ap is fused into the SpMV kernel) on laplacian7 24^3 with the
 * context's SpMV path: converged, true residual <= rtol, and the same
 * iteration count as the host reference PCG within 1 (both compute the same
 * recurrence; only summation orders differ). */
static void test_cg_fused(const char *path) {
  sessile_csr a;
  t_must("laplacian7", sessile_csr_laplacian7(24, 24, 24, &a));
  const uint32_t n = a.nrows;
  double *b = t_dalloc(n), *x = t_dalloc(n), *d = t_dalloc(n);
  sessile_fill_random(b, n, -1.0, 1.0, 9);
  to_stored(b, n);
  sessile_mat *m = NULL;
  sessile_vec *vb = NULL, *vx = NULL;
  t_must("mat_create_csr", sessile_mat_create_csr(la, &a, &m));
  t_must("vec_create", sessile_vec_create(la, n, &vb));
  t_must("vec_create", sessile_vec_create(la, n, &vx));
  t_must("upload", sessile_vec_upload(vb, b));
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  o.pc = SESSILE_PC_JACOBI;
  sessile_solve_result r;
  t_must("ksp_solve", sessile_ksp_solve(la, &o, m, vb, vx, &r));
  t_must("ref_jacobi", sessile_ref_jacobi_csr(&a, d));
  memset(x, 0, (size_t)n * sizeof *x); /* zero initial guess, as the device solve's */
  sessile_ref_result rr = sessile_ref_pcg(&a, d, b, x, o.rtol, o.max_it);
  char what[160];
  printf("-- PCG laplacian7 24^3 (%s): %d iterations, true relres %.3e; host reference %d\n", path,
         r.iterations, r.true_relres, rr.iterations);
  snprintf(what, sizeof what, "PCG laplacian7 24^3 (%s): converged", path);
  t_true(what, r.status == SESSILE_SOLVE_CONVERGED);
  snprintf(what, sizeof what, "PCG laplacian7 24^3 (%s): true relres vs rtol", path);
  t_check(what, r.true_relres, o.rtol);
  if (fp64) { /* fp32 runs refinement cycles: a different iteration count */
    snprintf(what, sizeof what, "PCG laplacian7 24^3 (%s): |iterations - host reference's|", path);
    t_check(what, fabs((double)r.iterations - (double)rr.iterations), 1.0);
  }
  sessile_mat_destroy(m);
  sessile_vec_destroy(vb);
  sessile_vec_destroy(vx);
  sessile_csr_free(&a);
  free(b);
  free(x);
  free(d);
}

int main(int argc, char **argv) {
  /* --fp32: the fp32 kernels (context precision 32) */
  sessile_gpu *g = t_gpu(argc > 1 && strcmp(argv[1], "--fp32") == 0 ? 32 : 0);
  fp64 = sessile_gpu_info_of(g)->precision == 64;
  tol_spmv = fp64 ? 1e-14 : 1e-5;
  tol_jac = fp64 ? 2.3e-16 : 1e-5;
  t_must("la_create", sessile_la_create(g, &la));
  test_random();
  test_ragged_slices();
  test_structured();
  test_bcsr4();
  test_errors();
  test_nonfinite_x();
  test_cg_fused("texel buffers");
  sessile_la_destroy(la);
  /* The storage-buffer SpMV kernels (used where texel views do not fit the
   * device limit) on the same cases. */
  printf("== storage-buffer SpMV path (la option spmv_storage = 1)\n");
  sessile_la_options lo;
  sessile_la_options_default(&lo);
  lo.spmv_storage = 1;
  t_must("la_create", sessile_la_create_with(g, &lo, &la));
  test_random();
  test_ragged_slices();
  test_structured();
  test_bcsr4();
  test_nonfinite_x();
  test_cg_fused("storage buffers");
  sessile_la_destroy(la);
  return t_finish(g);
}
