/* sessile — plain-C reference implementations of every la kernel and solver.
 *
 * They define what the GPU kernels must compute (tests compare against them)
 * and are the baseline `sessile bench la` measures against.  Threaded with
 * OpenMP where the work is large; every reduction is summed in a fixed order
 * (fixed chunks, pairwise), so results do not depend on the thread count. */
#ifndef SESSILE_LA_REF_H
#define SESSILE_LA_REF_H

#include <stdint.h>
#include "sessile/la/matrix.h"

#ifdef __cplusplus
extern "C" {
#endif

void sessile_ref_fill(uint64_t n, double value, double *y);
void sessile_ref_copy(uint64_t n, const double *x, double *y);
void sessile_ref_scale(uint64_t n, double alpha, double *y);                  /* y = a*y */
void sessile_ref_axpy(uint64_t n, double alpha, const double *x, double *y);  /* y += a*x */
void sessile_ref_aypx(uint64_t n, double alpha, const double *x, double *y);  /* y = x + a*y */
void sessile_ref_waxpy(uint64_t n, double alpha, const double *x, const double *y,
                       double *w);                                            /* w = a*x + y */
void sessile_ref_pmul(uint64_t n, const double *x, const double *y, double *w); /* w = x.*y */
double sessile_ref_dot(uint64_t n, const double *x, const double *y);
double sessile_ref_nrm2(uint64_t n, const double *x);

void sessile_ref_spmv_csr(const sessile_csr *a, const double *x, double *y);     /* y = A x */
void sessile_ref_spmv_bcsr4(const sessile_bcsr4 *a, const double *x, double *y); /* y = A x */
/* y = A x for the masked 7-point operator of sessile_mat_create_stencil7
 * (nx*ny*nz nodes; mask may be NULL: walls only). */
void sessile_ref_stencil7(uint32_t nx, uint32_t ny, uint32_t nz, double h, const uint32_t *mask,
                          const double *x, double *y);

/* y = A x for the cut-cell 7-point operator of sessile_mat_create_stencil7_cut (mask != 0:
 * Dirichlet node; diag: the caller's cut-cell diagonal). */
void sessile_ref_stencil7_cut(uint32_t nx, uint32_t ny, uint32_t nz, double h, const uint32_t *mask,
                              const double *diag, const double *x, double *y);
/* The same with the off-diagonal weights of sessile_mat_create_stencil7_cut_adv: coef holds
 * 6 per node (directions -x, +x, -y, +y, -z, +z), and the term of a free neighbour m in
 * direction d is f_nm coef[6 n + d] x_m (coef NULL: all 1, the operator above). */
void sessile_ref_stencil7_cut_adv(uint32_t nx, uint32_t ny, uint32_t nz, double h,
                                  const uint32_t *mask, const double *diag, const double *coef,
                                  const double *x, double *y);

/* Inverse diagonal for Jacobi; fails (SESSILE_ERR_NUMERIC, message names the
 * row) on a zero or non-finite diagonal entry. */
sessile_status sessile_ref_jacobi_csr(const sessile_csr *a, double *dinv);
/* BCSR4: point Jacobi, dinv has 4*nbrows entries (reciprocals of the scalar
 * diagonal, i.e. of the diagonals of the diagonal blocks). */
sessile_status sessile_ref_jacobi_bcsr4(const sessile_bcsr4 *a, double *dinv);

/* ILU(0): incomplete LU factorisation on A's own sparsity pattern (block
 * ILU(0) for BCSR4: 4x4 pivot blocks inverted densely), IKJ order in double.
 * `lu` receives A's nnz values (16*nnzb for blocks) in A's pattern: the
 * strict lower part holds L (unit diagonal implied), the diagonal and upper
 * part hold U, so (L U)_ij = A_ij wherever A has an entry.  Fails with
 * SESSILE_ERR_NUMERIC, naming the row, on a missing, zero, singular or
 * non-finite pivot.  Sequential (row i needs rows < i). */
sessile_status sessile_ref_ilu0_csr(const sessile_csr *a, double *lu);
sessile_status sessile_ref_ilu0_bcsr4(const sessile_bcsr4 *a, double *lu);
/* z = (L U)⁻¹ r with the factors above: forward then backward substitution in
 * natural row order (the 4x4 pivots solved by Gaussian elimination). */
void sessile_ref_ilu0_solve_csr(const sessile_csr *a, const double *lu, const double *r, double *z);
void sessile_ref_ilu0_solve_bcsr4(const sessile_bcsr4 *a, const double *lu, const double *r,
                                  double *z);

/* Block Jacobi of a 4x4 block CSR matrix: dinv receives the inverse of every
 * diagonal block (16 per block row, row-major).  Fails with
 * SESSILE_ERR_NUMERIC naming the lowest block row whose diagonal block is
 * missing, not finite or singular.  Threaded (OpenMP). */
sessile_status sessile_ref_bjacobi_bcsr4(const sessile_bcsr4 *a, double *dinv);
/* z = blockdiag(dinv) r (4 reals per block row). */
void sessile_ref_bjacobi_apply(uint32_t nbrows, const double *dinv, const double *r, double *z);

/* ‖b − A x‖ / ‖b‖ (‖r‖ when b = 0). */
double sessile_ref_true_relres(const sessile_csr *a, const double *b, const double *x);

typedef enum sessile_ref_solve_status {
  SESSILE_REF_CONVERGED = 0,
  SESSILE_REF_MAX_ITER = 1,
  SESSILE_REF_BREAKDOWN = 2
} sessile_ref_solve_status;

typedef struct sessile_ref_result {
  int iterations;
  double true_relres; /* recomputed ‖b − A x‖/‖b‖ */
  sessile_ref_solve_status status;
} sessile_ref_result;

/* Solvers on a CSR matrix; x holds the initial guess on entry.  Convergence:
 * unpreconditioned recursive residual ‖r‖ ≤ rtol‖b‖.  `dinv` may be NULL (no
 * preconditioner) or the Jacobi inverse diagonal (right preconditioning for
 * GMRES and BiCGSTAB, split-free left for CG). */
/* Breakdown (and a run that cannot start: non-square A, no memory) returns
 * SESSILE_REF_BREAKDOWN with the reason in sessile_error_message(); x then
 * holds the last finite iterate (untouched if the run could not start).
 * GMRES counts Arnoldi steps over all restarts in `iterations`; max_it bounds
 * that total. */
sessile_ref_result sessile_ref_pcg(const sessile_csr *a, const double *dinv, const double *b,
                                   double *x, double rtol, int max_it);
sessile_ref_result sessile_ref_bicgstab(const sessile_csr *a, const double *dinv,
                                        const double *b, double *x, double rtol, int max_it);
sessile_ref_result sessile_ref_gmres(const sessile_csr *a, const double *dinv, const double *b,
                                     double *x, double rtol, int max_it, int restart);

/* Geometric multigrid for the cut-cell operator: the algorithm of sessile_mg (sessile/la/mg.h)
 * in double on the host.  Level 0 is the finest; level l+1 is nested in level l as
 * sessile_mg_create requires (not checked here).  o: sessile_mg_options (mg.h). */
typedef struct sessile_ref_mg_level {
  uint32_t n[3];
  double h;
  const uint32_t *mask; /* != 0: Dirichlet */
  const double *diag;
  const double *coef;   /* NULL, or the advective weights (sessile_ref_stencil7_cut_adv) */
} sessile_ref_mg_level;
struct sessile_mg_options;
/* z = M r: one V-cycle.  Fails only with SESSILE_ERR_NO_MEMORY. */
sessile_status sessile_ref_mg_vcycle(int nlevels, const sessile_ref_mg_level *lv,
                                     const struct sessile_mg_options *o, const double *r, double *z);
/* CG preconditioned by one V-cycle per iteration, x = warm start on entry; convergence on the
 * recursive residual ||r|| <= rtol ||b||, tested before the V-cycle of each iteration (as on
 * the device); true_relres recomputed at the end. */
sessile_ref_result sessile_ref_mg_pcg(int nlevels, const sessile_ref_mg_level *lv,
                                      const struct sessile_mg_options *o, const double *b,
                                      double *x, double rtol, int max_it);

#ifdef __cplusplus
}
#endif
#endif
