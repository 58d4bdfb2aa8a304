/* ILU(0) preconditioner: the host factorisation, the level-scheduled device
 * application and its use in BiCGSTAB and GMRES(30).
 *
 * Run twice by ctest: default precision (fp64 on lavapipe) and --fp32.
 * Checks and tolerances:
 *  - ILU(0) property: (L U)_ij = A_ij on A's pattern, max |LU − A| / max |A|
 *    <= 1e-12 (each product entry sums a few dozen terms of size ~|A|, so the
 *    rounding is ~1e-15; 1e-12 leaves room for growth in the factors);
 *  - device z = (LU)⁻¹ r against the plain-C reference (natural-order
 *    substitution, 4x4 pivots solved by Gaussian elimination instead of the
 *    device's inverted pivots): max |z − z_ref| / max |z_ref| <= 1e-11 in fp64
 *    (rounding eps times the growth of the triangular solves, ~1e2 here),
 *    1e-4 in fp32 (the factors and vectors are stored in float, eps 6e-8,
 *    times the same growth);
 *  - solves: the true relative residual recomputed on the host in double
 *    <= rtol = 1e-6, and ILU0 needs at most 60% of Jacobi's iterations
 *    (both counts printed);
 *  - zero / singular pivots: SESSILE_ERR_NUMERIC whose message names the row. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sessile/la/la_ref.h"
#include "testutil.h"

static sessile_la *la;
static int fp32;
static const double rtol = 1e-6;

/* A generic view of CSR (bs 1) and BCSR4 (bs 4). */
typedef struct {
  int bs;
  uint32_t n;
  const uint64_t *rowptr;
  const uint32_t *col;
  const double *val;
} pat;
static pat pat_csr(const sessile_csr *a) { return (pat){1, a->nrows, a->rowptr, a->col, a->val}; }
static pat pat_bcsr4(const sessile_bcsr4 *a) { return (pat){4, a->nbrows, a->rowptr, a->col, a->val}; }

/* max over A's pattern of |(L U)_ij − A_ij| / max |A|, computed directly:
 * (LU)_ij = Σ_{k <= min(i,j)} L_ik U_kj with L_ii = I; the terms come from
 * row i of the factors (L_ik, k < i, plus k = i) and row k's U entries. */
static double ilu_property(pat p, const double *lu) {
  const int bs = p.bs, b2 = bs * bs;
  double *prod = t_dalloc((size_t)p.n * b2); /* one row of L U, dense in the block column */
  uint8_t *in = calloc(p.n, 1);
  double amax = 0, err = 0;
  for (uint64_t k = 0; k < p.rowptr[p.n] * b2; k++) amax = fmax(amax, fabs(p.val[k]));
  for (uint32_t i = 0; i < p.n; i++) {
    for (uint64_t k = p.rowptr[i]; k < p.rowptr[i + 1]; k++) {
      in[p.col[k]] = 1;
      memset(prod + (size_t)p.col[k] * b2, 0, (size_t)b2 * sizeof *prod);
    }
    for (uint64_t kk = p.rowptr[i]; kk < p.rowptr[i + 1]; kk++) {
      uint32_t k = p.col[kk];
      if (k > i) break;
      /* L_ik (identity for k = i) times row k of U (k's entries with column >= k) */
      for (uint64_t jj = p.rowptr[k]; jj < p.rowptr[k + 1]; jj++) {
        uint32_t j = p.col[jj];
        if (j < k || !in[j]) continue;
        const double *u = lu + jj * b2;
        double *t = prod + (size_t)j * b2;
        for (int r = 0; r < bs; r++)
          for (int c = 0; c < bs; c++) {
            double s = 0;
            for (int q = 0; q < bs; q++)
              s += (k == i ? (r == q ? 1.0 : 0.0) : lu[kk * b2 + r * bs + q]) * u[q * bs + c];
            t[r * bs + c] += s;
          }
      }
    }
    for (uint64_t k = p.rowptr[i]; k < p.rowptr[i + 1]; k++) {
      for (int q = 0; q < b2; q++)
        err = fmax(err, fabs(prod[(size_t)p.col[k] * b2 + q] - p.val[k * b2 + q]));
      in[p.col[k]] = 0;
    }
  }
  free(prod);
  free(in);
  return err / amax;
}

/* Factor property and device application against the reference. */
static void check_apply(const char *name, const sessile_csr *a, const sessile_bcsr4 *b) {
  pat p = a ? pat_csr(a) : pat_bcsr4(b);
  uint32_t n = p.n * (uint32_t)p.bs;
  double *lu = t_dalloc((size_t)p.rowptr[p.n] * p.bs * p.bs);
  double *r = t_dalloc(n), *z = t_dalloc(n), *zr = t_dalloc(n);
  char what[160];
  t_must("ref ilu0", a ? sessile_ref_ilu0_csr(a, lu) : sessile_ref_ilu0_bcsr4(b, lu));
  snprintf(what, sizeof what, "%s: ILU(0) property max|LU - A|/max|A| on A's pattern", name);
  t_check(what, ilu_property(p, lu), 1e-12);

  sessile_fill_random(r, n, -1, 1, 77);
  if (fp32)
    for (uint32_t i = 0; i < n; i++) r[i] = (double)(float)r[i];
  if (a) sessile_ref_ilu0_solve_csr(a, lu, r, zr);
  else sessile_ref_ilu0_solve_bcsr4(b, lu, r, zr);
  sessile_mat *m = NULL;
  sessile_vec *vr = NULL, *vz = NULL;
  t_must("mat", a ? sessile_mat_create_csr(la, a, &m) : sessile_mat_create_bcsr4(la, b, &m));
  t_must("vec", sessile_vec_create(la, n, &vr));
  t_must("vec", sessile_vec_create(la, n, &vz));
  t_must("upload", sessile_vec_upload(vr, r));
  sessile_ilu0_info info;
  t_must("ilu0", sessile_mat_ilu0(la, m, &info));
  t_must("ilu0 apply", sessile_mat_ilu0_apply(la, m, vr, vz));
  t_must("download", sessile_vec_download(vz, z));
  printf("   %s: %u rows, %u + %u levels, factorised in %.3f s\n", name, n, info.levels_lower,
         info.levels_upper, info.seconds);
  snprintf(what, sizeof what, "%s: device (LU)^-1 r vs C reference, max rel", name);
  t_check(what, t_relerr(z, zr, n), fp32 ? 1e-4 : 1e-11);
  /* A second application reuses the cached factors and gives the same z. */
  double *z2 = t_dalloc(n);
  t_must("ilu0 apply 2", sessile_mat_ilu0_apply(la, m, vr, vz));
  t_must("download", sessile_vec_download(vz, z2));
  snprintf(what, sizeof what, "%s: second application identical", name);
  t_check(what, t_relerr(z2, z, n), 0);
  free(z2);
  sessile_vec_destroy(vr);
  sessile_vec_destroy(vz);
  sessile_mat_destroy(m);
  free(lu);
  free(r);
  free(z);
  free(zr);
}

static void test_apply(void) {
  printf("-- factor property and device application\n");
  sessile_csr a = {0}, cd = {0}, pt = {0};
  sessile_bcsr4 b = {0};
  t_must("random", sessile_csr_random(2000, 9, 1.5, 42, &a));
  check_apply("random CSR n=2000", &a, NULL);
  t_must("convdiff", sessile_csr_convdiff(12, 10, 9, 2.0, &cd));
  check_apply("conv-diff Pe=2 12x10x9", &cd, NULL);
  sessile_csr_free(&cd);
  t_must("convdiff", sessile_csr_convdiff(12, 10, 9, 10.0, &cd));
  check_apply("conv-diff Pe=10 12x10x9", &cd, NULL);
  t_must("p1tet", sessile_csr_p1tet(6, 5, 4, 1.0, 1.0, 1.0, &pt));
  t_must("bcsr4", sessile_bcsr4_random_on(&pt, 5, &b));
  check_apply("random BCSR4 on P1-tet 6x5x4", NULL, &b);
  sessile_bcsr4_free(&b);
  t_must("bcsr4", sessile_bcsr4_random_on(&a, 6, &b));
  check_apply("random BCSR4 on random pattern n=2000", NULL, &b);
  sessile_csr_free(&a);
  sessile_csr_free(&cd);
  sessile_csr_free(&pt);
  sessile_bcsr4_free(&b);
}

/* Solves with the given preconditioner; returns the iteration count and
 * checks the host residual. */
static int solve(const char *name, const sessile_mat *m, const double *b, uint32_t n,
                 sessile_ksp_type type, sessile_pc_type pc, const sessile_csr *a,
                 const sessile_bcsr4 *bb) {
  sessile_vec *vb = NULL, *vx = NULL;
  double *x = t_dalloc(n), *r = t_dalloc(n);
  t_must("vec", sessile_vec_create(la, n, &vb));
  t_must("vec", sessile_vec_create(la, n, &vx));
  t_must("upload", sessile_vec_upload(vb, b));
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  o.type = type;
  o.pc = pc;
  o.rtol = rtol;
  o.max_it = 3000;
  sessile_solve_result res;
  t_must("solve", sessile_ksp_solve(la, &o, m, vb, vx, &res));
  t_must("download", sessile_vec_download(vx, x));
  if (a) sessile_ref_spmv_csr(a, x, r);
  else sessile_ref_spmv_bcsr4(bb, x, r);
  for (uint32_t i = 0; i < n; i++) r[i] = b[i] - r[i];
  double rel = sessile_ref_nrm2(n, r) / sessile_ref_nrm2(n, b);
  char what[200];
  if (res.status == SESSILE_SOLVE_BREAKDOWN) printf("  why: %s\n", res.reason);
  snprintf(what, sizeof what, "%s %s+%s: %s after %d iterations (%.2f s), host true relres", name,
           sessile_ksp_type_name(type), pc == SESSILE_PC_ILU0 ? "ilu0" : "jacobi",
           sessile_solve_status_name(res.status), res.iterations, res.seconds);
  t_check(what, rel, rtol);
  t_true("solver reports convergence", res.status == SESSILE_SOLVE_CONVERGED);
  sessile_vec_destroy(vb);
  sessile_vec_destroy(vx);
  free(x);
  free(r);
  return res.iterations;
}

static void compare(const char *name, const sessile_csr *a, const sessile_bcsr4 *bb) {
  uint32_t n = a ? a->nrows : 4 * bb->nbrows;
  double *b = t_dalloc(n);
  sessile_fill_random(b, n, -1, 1, 9);
  if (fp32)
    for (uint32_t i = 0; i < n; i++) b[i] = (double)(float)b[i];
  sessile_mat *m = NULL;
  t_must("mat", a ? sessile_mat_create_csr(la, a, &m) : sessile_mat_create_bcsr4(la, bb, &m));
  static const sessile_ksp_type types[2] = {SESSILE_KSP_GMRES, SESSILE_KSP_BICGSTAB};
  for (int t = 0; t < 2; t++) {
    int ij = solve(name, m, b, n, types[t], SESSILE_PC_JACOBI, a, bb);
    int ii = solve(name, m, b, n, types[t], SESSILE_PC_ILU0, a, bb);
    char what[200];
    snprintf(what, sizeof what, "%s %s: iterations ILU0 %d / Jacobi %d", name,
             sessile_ksp_type_name(types[t]), ii, ij);
    t_check(what, (double)ii / ij, 0.6);
  }
  sessile_mat_destroy(m);
  free(b);
}

static void test_convdiff(void) {
  printf("-- GMRES(30) and BiCGSTAB on convection-diffusion, Jacobi vs ILU0\n");
  static const double pe[2] = {2.0, 10.0};
  for (int k = 0; k < 2; k++) {
    sessile_csr a = {0};
    char name[64];
    uint32_t g = 16;
    t_must("convdiff", sessile_csr_convdiff(g, g, g, pe[k], &a));
    snprintf(name, sizeof name, "conv-diff Pe=%g %u^3", pe[k], g);
    compare(name, &a, NULL);
    sessile_csr_free(&a);
  }
}

/* Four convection-diffusion components coupled inside each node and across
 * neighbours: B_ij = C_ij (I + 0.2 R) for i != j, B_ii = C_ii I + K, with C the
 * scalar conv-diff matrix (Pe 2), R a fixed random 4x4 and K a nonsymmetric
 * coupling with zero diagonal (entries up to 1.5 against diagonal 6). */
static void test_coupled_bcsr4(void) {
  printf("-- coupled BCSR4 system (4 conv-diff components)\n");
  sessile_csr c = {0};
  const uint32_t g = 10;
  t_must("convdiff", sessile_csr_convdiff(g, g, g, 2.0, &c));
  sessile_bcsr4 b = {0};
  t_must("alloc", sessile_bcsr4_alloc(c.nrows, c.nrows, c.nnz, &b));
  double R[16], K[16];
  sessile_fill_random(R, 16, -1, 1, 3);
  sessile_fill_random(K, 16, -1.5, 1.5, 4);
  for (int i = 0; i < 4; i++) K[5 * i] = 0;
  memcpy(b.rowptr, c.rowptr, ((size_t)c.nrows + 1) * sizeof *b.rowptr);
  memcpy(b.col, c.col, (size_t)c.nnz * sizeof *b.col);
  for (uint32_t i = 0; i < c.nrows; i++)
    for (uint64_t k = c.rowptr[i]; k < c.rowptr[i + 1]; k++)
      for (int q = 0; q < 16; q++) {
        double id = (q / 4 == q % 4) ? 1.0 : 0.0;
        b.val[16 * k + q] = c.col[k] == i ? c.val[k] * id + K[q] : c.val[k] * (id + 0.2 * R[q]);
      }
  check_apply("coupled BCSR4 10^3", NULL, &b);
  compare("coupled BCSR4 10^3", NULL, &b);
  sessile_bcsr4_free(&b);
  sessile_csr_free(&c);
}

static int names_row(const char *msg, const char *row) { return strstr(msg, row) != NULL; }

static void test_pivots(void) {
  printf("-- zero and singular pivots\n");
  /* [[1 1 0] [1 1 1] [0 1 2]]: u_11 = 1 − 1·1 = 0 at row 1. */
  sessile_csr a = {0};
  t_must("alloc", sessile_csr_alloc(3, 3, 7, &a));
  const uint64_t rp[4] = {0, 2, 5, 7};
  const uint32_t col[7] = {0, 1, 0, 1, 2, 1, 2};
  const double val[7] = {1, 1, 1, 1, 1, 1, 2};
  memcpy(a.rowptr, rp, sizeof rp);
  memcpy(a.col, col, sizeof col);
  memcpy(a.val, val, sizeof val);
  double lu[7];
  sessile_status s = sessile_ref_ilu0_csr(&a, lu);
  printf("   message: %s\n", sessile_error_message());
  t_true("zero pivot during elimination: SESSILE_ERR_NUMERIC", s == SESSILE_ERR_NUMERIC);
  t_true("the message names row 1", names_row(sessile_error_message(), "row 1"));
  sessile_error_clear();
  /* Through the solver: the same error, nothing leaked. */
  sessile_mat *m = NULL;
  sessile_vec *vb = NULL, *vx = NULL;
  t_must("mat", sessile_mat_create_csr(la, &a, &m));
  t_must("vec", sessile_vec_create(la, 3, &vb));
  t_must("vec", sessile_vec_create(la, 3, &vx));
  t_must("fill", sessile_vec_fill(la, 1.0, vb));
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  o.type = SESSILE_KSP_GMRES;
  o.pc = SESSILE_PC_ILU0;
  sessile_solve_result res;
  s = sessile_ksp_solve(la, &o, m, vb, vx, &res);
  t_true("ksp_solve with ILU0 on it: SESSILE_ERR_NUMERIC", s == SESSILE_ERR_NUMERIC);
  sessile_error_clear();
  o.type = SESSILE_KSP_CG;
  s = sessile_ksp_solve(la, &o, m, vb, vx, &res);
  printf("   message: %s\n", sessile_error_message());
  t_true("CG with ILU0: SESSILE_ERR_USAGE", s == SESSILE_ERR_USAGE);
  sessile_error_clear();
  sessile_vec_destroy(vb);
  sessile_vec_destroy(vx);
  sessile_mat_destroy(m);
  /* A zero diagonal entry from the start, at row 0. */
  a.val[0] = 0;
  s = sessile_ref_ilu0_csr(&a, lu);
  printf("   message: %s\n", sessile_error_message());
  t_true("zero diagonal: SESSILE_ERR_NUMERIC naming row 0",
         s == SESSILE_ERR_NUMERIC && names_row(sessile_error_message(), "row 0"));
  sessile_error_clear();
  sessile_csr_free(&a);
  /* Block: a singular 4x4 pivot (two equal rows) in block row 1 of 2. */
  sessile_bcsr4 b = {0};
  t_must("alloc", sessile_bcsr4_alloc(2, 2, 2, &b));
  b.rowptr[0] = 0, b.rowptr[1] = 1, b.rowptr[2] = 2;
  b.col[0] = 0, b.col[1] = 1;
  for (int q = 0; q < 16; q++) {
    b.val[q] = (q / 4 == q % 4) ? 4.0 : 0.5;
    b.val[16 + q] = (q / 4 == 3 ? (q % 4 == 2 ? 1.0 : 0.0) : (q / 4 == q % 4 ? 1.0 : 0.0));
  }
  double lub[32];
  s = sessile_ref_ilu0_bcsr4(&b, lub);
  printf("   message: %s\n", sessile_error_message());
  t_true("singular 4x4 pivot: SESSILE_ERR_NUMERIC naming block row 1",
         s == SESSILE_ERR_NUMERIC && names_row(sessile_error_message(), "block row 1"));
  sessile_error_clear();
  sessile_bcsr4_free(&b);
}

/* sessile_mat_refill_bcsr4: new values in the same buffers give the SpMV
 * and the ILU(0) application of a matrix made from them (the factors of
 * the old values are dropped); another pattern is refused. */
static void test_refill(void) {
  printf("-- refilling a block matrix's values in place\n");
  sessile_csr pt = {0};
  sessile_bcsr4 b1 = {0}, b2 = {0}, b3 = {0};
  t_must("p1tet", sessile_csr_p1tet(6, 5, 4, 1.0, 1.0, 1.0, &pt));
  t_must("bcsr4", sessile_bcsr4_random_on(&pt, 5, &b1));
  t_must("bcsr4", sessile_bcsr4_random_on(&pt, 9, &b2));
  uint32_t n = b1.nbrows * 4;
  double *r = t_dalloc(n), *y1 = t_dalloc(n), *y2 = t_dalloc(n), *z1 = t_dalloc(n), *z2 = t_dalloc(n);
  sessile_fill_random(r, n, -1, 1, 5);
  sessile_mat *m = NULL, *f = NULL;
  sessile_vec *vr = NULL, *vy = NULL;
  t_must("mats", sessile_mat_create_bcsr4(la, &b1, &m));
  t_must("mats", sessile_mat_create_bcsr4(la, &b2, &f));
  t_must("vecs", sessile_vec_create(la, n, &vr));
  t_must("vecs", sessile_vec_create(la, n, &vy));
  t_must("upload", sessile_vec_upload(vr, r));
  sessile_ilu0_info info;
  t_must("ilu0 of the old values", sessile_mat_ilu0(la, m, &info));
  t_must("refill", sessile_mat_refill_bcsr4(m, &b2));
  t_must("spmv", sessile_mat_mult(la, m, vr, vy));
  t_must("download", sessile_vec_download(vy, y1));
  t_must("spmv", sessile_mat_mult(la, f, vr, vy));
  t_must("download", sessile_vec_download(vy, y2));
  t_true("refilled SpMV = a new matrix's, bit for bit", memcmp(y1, y2, n * sizeof *y1) == 0);
  t_must("ilu0", sessile_mat_ilu0(la, m, &info));
  t_must("ilu0 apply", sessile_mat_ilu0_apply(la, m, vr, vy));
  t_must("download", sessile_vec_download(vy, z1));
  t_must("ilu0", sessile_mat_ilu0(la, f, &info));
  t_must("ilu0 apply", sessile_mat_ilu0_apply(la, f, vr, vy));
  t_must("download", sessile_vec_download(vy, z2));
  t_true("refilled ILU(0) application = a new matrix's (the old factors dropped)",
         memcmp(z1, z2, n * sizeof *z1) == 0);
  /* another pattern: one block fewer */
  t_must("alloc", sessile_bcsr4_alloc(b1.nbrows, b1.nbcols, b1.nnzb - 1, &b3));
  memcpy(b3.rowptr, b1.rowptr, ((size_t)b1.nbrows + 1) * sizeof *b3.rowptr);
  b3.rowptr[b1.nbrows] = b1.nnzb - 1;
  memcpy(b3.col, b1.col, (size_t)(b1.nnzb - 1) * sizeof *b3.col);
  t_true("another pattern is refused (SESSILE_ERR_USAGE)", sessile_mat_refill_bcsr4(m, &b3) == SESSILE_ERR_USAGE);
  sessile_vec_destroy(vr), sessile_vec_destroy(vy);
  sessile_mat_destroy(m), sessile_mat_destroy(f);
  sessile_bcsr4_free(&b1), sessile_bcsr4_free(&b2), sessile_bcsr4_free(&b3);
  sessile_csr_free(&pt);
  free(r), free(y1), free(y2), free(z1), free(z2);
}

int main(int argc, char **argv) {
  int want32 = 0;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--fp32") == 0) want32 = 1;
    else {
      printf("usage: %s [--fp32]\n", argv[0]);
      return 2;
    }
  }
  sessile_gpu *g = t_gpu(want32 ? 32 : 0);
  fp32 = sessile_gpu_info_of(g)->precision == 32;
  if (want32) t_true("--fp32: the context precision is 32", fp32);
  t_must("la_create", sessile_la_create(g, &la));
  double t0 = sessile_wall_seconds();
  test_apply();
  test_pivots();
  test_convdiff();
  test_coupled_bcsr4();
  test_refill();
  printf("ILU tests took %.1f s\n", sessile_wall_seconds() - t0);
  sessile_la_destroy(la);
  return t_finish(g);
}
