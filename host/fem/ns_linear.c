/* The linear solve of one Newton (or Picard) step on the GPU: the block
 * Jacobian uploaded (optionally block-Jacobi scaled) and la's Krylov solver. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fem/ns_internal.h"
#include "sessile/la_ref.h"

/* Inverts the 4x4 matrix a (row-major) into inv by Gauss-Jordan with
 * partial pivoting; returns 0 if singular. */
static int inv4(const double *a, double *inv) {
  double m[4][8];
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 8; j++) m[i][j] = j < 4 ? a[4 * i + j] : (j - 4 == i);
  for (int c = 0; c < 4; c++) {
    int piv = c;
    for (int i = c + 1; i < 4; i++)
      if (fabs(m[i][c]) > fabs(m[piv][c])) piv = i;
    if (!(fabs(m[piv][c]) > 0)) return 0;
    for (int j = 0; j < 8; j++) {
      double t = m[c][j];
      m[c][j] = m[piv][j];
      m[piv][j] = t;
    }
    double d = 1.0 / m[c][c];
    for (int j = 0; j < 8; j++) m[c][j] *= d;
    for (int i = 0; i < 4; i++)
      if (i != c) {
        double f = m[i][c];
        for (int j = 0; j < 8; j++) m[i][j] -= f * m[c][j];
      }
  }
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) inv[4 * i + j] = m[i][j + 4];
  return 1;
}

/* Block-Jacobi by explicit left scaling: every block row and its right-hand
 * side multiplied by the inverse of its diagonal block, so the Krylov solver
 * sees D^-1 A x = D^-1 b (its relative residual is then that of the scaled
 * system).  la's point Jacobi cannot couple a node's u and p. */
static sessile_status block_scale(sessile_fluid *fl, double *rhs) {
  /* A failure in a worker is reduced to the lowest failing node and reported
   * once, on the calling thread, after the parallel loop: the error message
   * is thread-local, so a worker's sessile_error_set would be lost. */
  uint32_t bad = UINT32_MAX;
#pragma omp parallel for schedule(static) reduction(min : bad)
  for (uint32_t i = 0; i < fl->nnodes; i++) {
    double D[16], Di[16], tmp[16];
    int found = 0;
    for (uint64_t e = fl->a.rowptr[i]; e < fl->a.rowptr[i + 1]; e++)
      if (fl->a.col[e] == i) {
        memcpy(D, fl->a.val + 16 * e, sizeof D);
        found = 1;
      }
    if (!found || !inv4(D, Di)) {
      if (i < bad) bad = i;
      continue;
    }
    for (uint64_t e = fl->a.rowptr[i]; e < fl->a.rowptr[i + 1]; e++) {
      double *B = fl->a.val + 16 * e;
      for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
          tmp[4 * r + c] = Di[4 * r] * B[c] + Di[4 * r + 1] * B[4 + c] + Di[4 * r + 2] * B[8 + c] + Di[4 * r + 3] * B[12 + c];
      memcpy(B, tmp, sizeof tmp);
    }
    double *b = rhs + 4 * (size_t)i, bt[4];
    for (int r = 0; r < 4; r++) bt[r] = Di[4 * r] * b[0] + Di[4 * r + 1] * b[1] + Di[4 * r + 2] * b[2] + Di[4 * r + 3] * b[3];
    memcpy(b, bt, sizeof bt);
  }
  if (bad != UINT32_MAX)
    return sessile_error_set(SESSILE_ERR_NUMERIC,
                             "Navier-Stokes Jacobian: singular diagonal block at node %u", bad);
  return SESSILE_OK;
}

sessile_status ns_linear_solve(sessile_fluid *fl, const sessile_fluid_params *p, const double *r,
                               double *du, sessile_vec *b, sessile_vec *x, sessile_fluid_step *st) {
  size_t n4 = (size_t)fl->nnodes * 4;
  for (size_t k = 0; k < n4; k++) du[k] = -r[k];
  if (p->block_jacobi) SESSILE_CALL(block_scale(fl, du));
  sessile_mat *m = NULL;
  SESSILE_CALL(sessile_mat_create_bcsr4(fl->la, &fl->a, &m));
  sessile_ksp_options o;
  sessile_ksp_options_default(&o);
  o.type = p->ksp;
  o.pc = p->pc;
  /* la factorises ILU(0) only on a matrix stored in one piece */
  st->lin_chunks = sessile_mat_chunks(m);
  if (o.pc == SESSILE_PC_ILU0 && st->lin_chunks > 1) o.pc = SESSILE_PC_JACOBI;
  st->lin_pc = o.pc;
  o.rtol = p->linear_rtol;
  o.max_it = p->linear_max;
  o.restart = p->restart;
  sessile_solve_result lr;
  sessile_status s = sessile_vec_upload(b, du);
  if (s == SESSILE_OK) s = sessile_vec_fill(fl->la, 0.0, x);
  if (s == SESSILE_OK) s = sessile_ksp_solve(fl->la, &o, m, b, x, &lr);
  if (s == SESSILE_OK) s = sessile_vec_download(x, du);
  sessile_mat_destroy(m);
  if (s != SESSILE_OK) return s;
  if (p->check_linear && p->monitor) {
    double *y = malloc(n4 * sizeof *y), e = 0, nb = 0;
    SESSILE_CHECK(y, SESSILE_ERR_NO_MEMORY, "out of host memory for the linear-solve check");
    sessile_ref_spmv_bcsr4(&fl->a, du, y);
    for (size_t k = 0; k < n4; k++) { e += (y[k] + r[k]) * (y[k] + r[k]); nb += r[k] * r[k]; }
    if (p->block_jacobi) e = NAN; /* the matrix is scaled */
    free(y);
    ns_monitor(p, "host check |J du + r|/|r| = %g", sqrt(e / nb));
  }
  st->lin_iterations = lr.iterations;
  st->lin_relres = lr.true_relres;
  st->lin_status = lr.status;
  return SESSILE_OK;
}
