/* Matrices stored in row chunks (mat.c): the la's max_matrix_chunk_bytes set
 * to a few KB splits small matrices into many chunks, as maxStorageBufferRange
 * (128 MiB on lavapipe) splits big ones.
 *
 * Checks, on the 7-point Laplacian, P1-tet K+M and convection-diffusion CSR
 * matrices and a 4x4 block-CSR matrix:
 *  - the matrix really is split (chunk count > 1, printed);
 *  - SpMV against the plain-C reference, row-wise relative error
 *    max_i |y_i - yref_i| / sum_j |a_ij x_j| <= 1e-14 in fp64, 1e-5 in fp32
 *    (the tolerances of test_spmv.c), through texel and storage buffers;
 *  - split and unsplit SpMV agree exactly (same kernel, same per-row order);
 *  - PCG (Poisson), BiCGSTAB and GMRES(30) (conv-diff, BCSR4) with Jacobi
 *    reach a host-recomputed true relres <= 1e-6 in the same number of
 *    iterations as the unsplit matrix, +-1 (CG's p.Ap is summed by a separate
 *    dot on a split matrix instead of the fused kernel: different rounding);
 *  - a row too long for one chunk, and ILU(0) factors over the limit, are
 *    refused with SESSILE_ERR_TOO_LARGE and a message naming the limit.
 * Split-vs-unsplit SpMV times are printed, never asserted. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/la/la_ref.h"
#include "testutil.h"

static sessile_la *la;
static int fp64;
static double tol_spmv;
static const double rtol = 1e-6;

/* The chunk limit for matrices created next (0: the device's). */
static int storage_only; /* the la's spmv_storage */
static void set_limit(unsigned bytes) {
  sessile_la_options o;
  sessile_la_options_default(&o);
  o.spmv_storage = storage_only;
  o.max_matrix_chunk_bytes = bytes;
  sessile_la_set_options(la, &o);
}

static void to_stored(double *v, uint64_t n) {
  if (!fp64)
    for (uint64_t i = 0; i < n; i++) v[i] = (double)(float)v[i];
}

/* Creates the unsplit and the split matrix of `a` (CSR) or `b` (BCSR4). */
static void create_pair(const sessile_csr *a, const sessile_bcsr4 *b, unsigned limit,
                        sessile_mat **whole, sessile_mat **split) {
  set_limit(0);
  t_must("mat_create", a ? sessile_mat_create_csr(la, a, whole) : sessile_mat_create_bcsr4(la, b, whole));
  set_limit(limit);
  t_must("mat_create (split)",
       a ? sessile_mat_create_csr(la, a, split) : sessile_mat_create_bcsr4(la, b, split));
  set_limit(0);
}

static double time_mults(const sessile_mat *m, const sessile_vec *x, sessile_vec *y, int reps) {
  double t0 = sessile_wall_seconds();
  for (int i = 0; i < reps; i++) t_must("mat_mult", sessile_mat_mult(la, m, x, y));
  return (sessile_wall_seconds() - t0) / reps;
}

/* SpMV of the split matrix vs the reference and vs the unsplit matrix. */
static void check_spmv(const char *name, const sessile_csr *a, const sessile_bcsr4 *b,
                       unsigned limit) {
  sessile_csr ac = {0};
  sessile_bcsr4 bc = {0};
  /* Values rounded to the stored precision so the reference uses the device's operands. */
  if (a) {
    t_must("csr_alloc", sessile_csr_alloc(a->nrows, a->ncols, a->nnz, &ac));
    memcpy(ac.rowptr, a->rowptr, ((size_t)a->nrows + 1) * sizeof *a->rowptr);
    memcpy(ac.col, a->col, (size_t)a->nnz * sizeof *a->col);
    memcpy(ac.val, a->val, (size_t)a->nnz * sizeof *a->val);
    to_stored(ac.val, ac.nnz);
  } else {
    t_must("bcsr4_alloc", sessile_bcsr4_alloc(b->nbrows, b->nbcols, b->nnzb, &bc));
    memcpy(bc.rowptr, b->rowptr, ((size_t)b->nbrows + 1) * sizeof *b->rowptr);
    memcpy(bc.col, b->col, (size_t)b->nnzb * sizeof *b->col);
    memcpy(bc.val, b->val, (size_t)b->nnzb * 16 * sizeof *b->val);
    to_stored(bc.val, bc.nnzb * 16);
  }
  sessile_mat *mw, *ms;
  create_pair(a ? &ac : NULL, a ? NULL : &bc, limit, &mw, &ms);
  uint32_t n = sessile_mat_rows(ms);
  printf("   %s: n = %u, %u chunk(s) unsplit, %u chunks at %u bytes\n", name, n,
         sessile_mat_chunks(mw), sessile_mat_chunks(ms), limit);
  char what[200];
  snprintf(what, sizeof what, "%s: unsplit is 1 chunk, split is > 1 chunk", name);
  t_true(what, sessile_mat_chunks(mw) == 1 && sessile_mat_chunks(ms) > 1);

  double *x = t_dalloc(n), *y = t_dalloc(n), *yw = t_dalloc(n), *r = t_dalloc(n), *s = t_dalloc(n);
  sessile_fill_random(x, n, -1.0, 1.0, 7);
  to_stored(x, n);
  if (a) sessile_ref_spmv_csr(&ac, x, r);
  else sessile_ref_spmv_bcsr4(&bc, x, r);
  /* s_i = sum_j |a_ij x_j|: the reference on |A| and |x|. */
  double *ax = t_dalloc(n);
  for (uint32_t i = 0; i < n; i++) ax[i] = fabs(x[i]);
  if (a) {
    for (uint64_t k = 0; k < ac.nnz; k++) ac.val[k] = fabs(ac.val[k]);
    sessile_ref_spmv_csr(&ac, ax, s);
  } else {
    for (uint64_t k = 0; k < bc.nnzb * 16; k++) bc.val[k] = fabs(bc.val[k]);
    sessile_ref_spmv_bcsr4(&bc, ax, s);
  }
  sessile_vec *vx, *vy;
  t_must("vec_create", sessile_vec_create(la, n, &vx));
  t_must("vec_create", sessile_vec_create(la, n, &vy));
  t_must("upload x", sessile_vec_upload(vx, x));
  t_must("mat_mult split", sessile_mat_mult(la, ms, vx, vy));
  t_must("download", sessile_vec_download(vy, y));
  t_must("mat_mult unsplit", sessile_mat_mult(la, mw, vx, vy));
  t_must("download", sessile_vec_download(vy, yw));
  double e = 0, d = 0;
  for (uint32_t i = 0; i < n; i++) {
    double q = fabs(y[i] - r[i]) / (s[i] > 0 ? s[i] : 1.0);
    if (!(q <= e)) e = q;
    if (!(fabs(y[i] - yw[i]) <= d)) d = fabs(y[i] - yw[i]);
  }
  snprintf(what, sizeof what, "%s: split SpMV vs reference, row-wise relative error", name);
  t_check(what, e, tol_spmv);
  snprintf(what, sizeof what, "%s: split vs unsplit SpMV, max |difference| (exactly equal)", name);
  t_check(what, d, 0.0);
  double tw = time_mults(mw, vx, vy, 20), ts = time_mults(ms, vx, vy, 20);
  printf("   %s: sessile_mat_mult %.3f ms unsplit, %.3f ms in %u chunks (timing, not checked)\n",
         name, 1e3 * tw, 1e3 * ts, sessile_mat_chunks(ms));
  sessile_vec_destroy(vx);
  sessile_vec_destroy(vy);
  sessile_mat_destroy(mw);
  sessile_mat_destroy(ms);
  if (a) sessile_csr_free(&ac);
  else sessile_bcsr4_free(&bc);
  free(x), free(y), free(yw), free(r), free(s), free(ax);
}

static void spmv_cases(void) {
  sessile_csr a;
  t_must("laplacian7", sessile_csr_laplacian7(16, 16, 16, &a));
  check_spmv("laplacian7 16^3", &a, NULL, 4096);
  sessile_csr_free(&a);
  t_must("p1tet", sessile_csr_p1tet(12, 12, 12, 1.0 / 12, 1.0 / 12, 1.0 / 12, &a));
  check_spmv("p1tet 12^3", &a, NULL, 4096);
  sessile_csr_free(&a);
  t_must("convdiff", sessile_csr_convdiff(16, 16, 16, 2.0, &a));
  check_spmv("convdiff 16^3", &a, NULL, 4096);
  sessile_csr_free(&a);
  sessile_bcsr4 b;
  t_must("laplacian7", sessile_csr_laplacian7(10, 10, 10, &a));
  t_must("bcsr4_random_on", sessile_bcsr4_random_on(&a, 99, &b));
  check_spmv("bcsr4 on laplacian7 10^3", NULL, &b, 16384);
  sessile_bcsr4_free(&b);
  sessile_csr_free(&a);
}

/* ---- solvers: split vs unsplit iteration counts ---- */
static double relres(const sessile_csr *a, const sessile_bcsr4 *b, const double *rhs,
                     const double *x) {
  if (a) return sessile_ref_true_relres(a, rhs, x);
  uint32_t n = 4 * b->nbrows;
  double *r = t_dalloc(n);
  sessile_ref_spmv_bcsr4(b, x, r);
  for (uint32_t i = 0; i < n; i++) r[i] = rhs[i] - r[i];
  double q = sessile_ref_nrm2(n, r) / sessile_ref_nrm2(n, rhs);
  free(r);
  return q;
}

static int solve(sessile_ksp_type t, const sessile_mat *m, const double *rhs, double *x,
                 sessile_solve_result *res) {
  uint32_t n = sessile_mat_rows(m);
  sessile_vec *vb, *vx;
  t_must("vec_create", sessile_vec_create(la, n, &vb));
  t_must("vec_create", sessile_vec_create(la, n, &vx));
  t_must("upload b", sessile_vec_upload(vb, rhs));
  for (uint32_t i = 0; i < n; i++) x[i] = 0;
  t_must("upload x", sessile_vec_upload(vx, x));
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  o.type = t;
  o.pc = SESSILE_PC_JACOBI;
  o.rtol = rtol;
  o.max_it = 2000;
  memset(res, 0, sizeof *res);
  sessile_status s = sessile_ksp_solve(la, &o, m, vb, vx, res);
  t_must("download x", sessile_vec_download(vx, x));
  sessile_vec_destroy(vb);
  sessile_vec_destroy(vx);
  return s == SESSILE_OK && res->status == SESSILE_SOLVE_CONVERGED;
}

static void check_solver(const char *name, sessile_ksp_type t, const sessile_csr *a,
                         const sessile_bcsr4 *b, unsigned limit) {
  sessile_mat *mw, *ms;
  create_pair(a, b, limit, &mw, &ms);
  uint32_t n = sessile_mat_rows(ms);
  double *rhs = t_dalloc(n), *x = t_dalloc(n);
  sessile_fill_random(rhs, n, -1.0, 1.0, 32);
  to_stored(rhs, n);
  sessile_solve_result rw, rs;
  int okw = solve(t, mw, rhs, x, &rw);
  double hw = relres(a, b, rhs, x);
  int oks = solve(t, ms, rhs, x, &rs);
  double hs = relres(a, b, rhs, x);
  printf("   %s: unsplit %d iterations (relres %.3e, %.3f s), %u chunks %d iterations (relres "
         "%.3e, %.3f s)\n",
         name, rw.iterations, hw, rw.seconds, sessile_mat_chunks(ms), rs.iterations, hs, rs.seconds);
  char what[200];
  snprintf(what, sizeof what, "%s: both solves converged", name);
  t_true(what, okw && oks);
  snprintf(what, sizeof what, "%s: split, host-recomputed true relres <= rtol", name);
  t_check(what, hs, rtol);
  snprintf(what, sizeof what, "%s: |iterations split - unsplit|", name);
  t_check(what, fabs((double)rs.iterations - rw.iterations), 1.0);
  sessile_mat_destroy(mw);
  sessile_mat_destroy(ms);
  free(rhs), free(x);
}

static void solver_cases(void) {
  sessile_csr a;
  t_must("laplacian7", sessile_csr_laplacian7(20, 20, 20, &a));
  check_solver("PCG(Jacobi) laplacian7 20^3", SESSILE_KSP_CG, &a, NULL, 8192);
  sessile_csr_free(&a);
  t_must("convdiff", sessile_csr_convdiff(16, 16, 16, 2.0, &a));
  check_solver("BiCGSTAB(Jacobi) convdiff 16^3", SESSILE_KSP_BICGSTAB, &a, NULL, 8192);
  check_solver("GMRES(30)(Jacobi) convdiff 16^3", SESSILE_KSP_GMRES, &a, NULL, 8192);
  sessile_csr_free(&a);
  sessile_bcsr4 b;
  t_must("laplacian7", sessile_csr_laplacian7(10, 10, 10, &a));
  t_must("bcsr4_random_on", sessile_bcsr4_random_on(&a, 99, &b));
  check_solver("BiCGSTAB(Jacobi) bcsr4 10^3", SESSILE_KSP_BICGSTAB, NULL, &b, 16384);
  check_solver("GMRES(30)(Jacobi) bcsr4 10^3", SESSILE_KSP_GMRES, NULL, &b, 16384);
  sessile_bcsr4_free(&b);
  sessile_csr_free(&a);
}

/* ---- what cannot be split ---- */
static void check_refused(const char *what, sessile_status s, const char *needle) {
  const char *msg = s == SESSILE_OK ? "" : sessile_error_message();
  printf("   %s: %s: %s\n", what, sessile_status_name(s), msg);
  char w[240];
  snprintf(w, sizeof w, "%s: SESSILE_ERR_TOO_LARGE naming the limit and \"%s\"", what, needle);
  t_true(w, s == SESSILE_ERR_TOO_LARGE && strstr(msg, "max_matrix_chunk_bytes") &&
                strstr(msg, "maxStorageBufferRange") && strstr(msg, needle));
}

static void error_cases(void) {
  /* CSR: 64 rows, row 5 dense (64 entries: an 8-row slice of 16 chunks of 4,
   * 4 KB of fp64 values), the others diagonal. */
  const uint32_t n = 64;
  sessile_csr a;
  t_must("csr_alloc", sessile_csr_alloc(n, n, 2 * n - 1, &a));
  uint64_t k = 0;
  for (uint32_t r = 0; r < n; r++) {
    a.rowptr[r] = k;
    for (uint32_t c = 0; c < n; c++)
      if (r == 5 || c == r) a.col[k] = c, a.val[k++] = c == r ? 4.0 : 0.01;
  }
  a.rowptr[n] = k;
  sessile_mat *m = NULL;
  set_limit(1024);
  check_refused("CSR with a 64-entry row at 1024 bytes", sessile_mat_create_csr(la, &a, &m),
                "row 5");
  t_true("refused CSR matrix: *out stays NULL", m == NULL);
  set_limit(0);
  sessile_csr_free(&a);

  /* BCSR4: block row 3 with 16 blocks (2 KB in fp64, 1 KB in fp32) at 512 bytes. */
  sessile_bcsr4 b;
  t_must("bcsr4_alloc", sessile_bcsr4_alloc(16, 16, 31, &b));
  k = 0;
  for (uint32_t r = 0; r < 16; r++) {
    b.rowptr[r] = k;
    for (uint32_t c = 0; c < 16; c++)
      if (r == 3 || c == r) {
        b.col[k] = c;
        for (int q = 0; q < 16; q++) b.val[16 * k + q] = c == r && q % 5 == 0 ? 4.0 : 0.01;
        k++;
      }
  }
  b.rowptr[16] = k;
  set_limit(512);
  check_refused("BCSR4 with a 16-block row at 512 bytes", sessile_mat_create_bcsr4(la, &b, &m),
                "block row 3");
  t_true("refused BCSR4 matrix: *out stays NULL", m == NULL);
  set_limit(0);
  sessile_bcsr4_free(&b);

  /* ILU(0) of a split matrix whose factors exceed the chunk limit. */
  t_must("convdiff", sessile_csr_convdiff(8, 8, 8, 2.0, &a));
  set_limit(1024);
  t_must("mat_create_csr (split)", sessile_mat_create_csr(la, &a, &m));
  set_limit(0);
  sessile_ilu0_info info;
  check_refused("ILU(0) of a split convdiff 8^3 at 1024 bytes", sessile_mat_ilu0(la, m, &info),
                "ILU(0)");
  sessile_mat_destroy(m);
  sessile_csr_free(&a);
}

int main(int argc, char **argv) {
  /* --fp32: the fp32 kernels (context precision 32) */
  sessile_gpu *g = t_gpu(argc > 1 && strcmp(argv[1], "--fp32") == 0 ? 32 : 0);
  fp64 = sessile_gpu_info_of(g)->precision == 64;
  tol_spmv = fp64 ? 1e-14 : 1e-5;
  t_must("la_create", sessile_la_create(g, &la));
  printf("== SpMV, texel-buffer path\n");
  spmv_cases();
  printf("== solvers\n");
  solver_cases();
  printf("== refused\n");
  error_cases();
  sessile_la_destroy(la);
  printf("== SpMV, storage-buffer path (la option spmv_storage = 1)\n");
  sessile_la_options lo;
  sessile_la_options_default(&lo);
  lo.spmv_storage = storage_only = 1;
  t_must("la_create", sessile_la_create_with(g, &lo, &la));
  spmv_cases();
  sessile_la_destroy(la);
  return t_finish(g);
}
