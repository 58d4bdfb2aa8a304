/* sessile — geometric multigrid on nested vertex grids for the cut-cell
 * 7-point operator (sessile_mat_create_stencil7_cut), used as the
 * preconditioner of CG: one V-cycle per iteration, damped-Jacobi smoothing,
 * trilinear prolongation P, restriction R = P^T, the coarse operators the
 * caller's rediscretisations.  Everything runs on the device; work vectors
 * and recorded command buffers are kept across solves.  docs/la.md.
 *
 * Ownership: the caller owns every level's mask buffer and diag vector and
 * keeps them alive while the sessile_mg exists; destroy the sessile_mg
 * before the la. */
#ifndef SESSILE_MG_H
#define SESSILE_MG_H

#include "sessile/la/la.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sessile_mg sessile_mg;
typedef struct sessile_mg_level {
  uint32_t n[3];          /* nodes per axis */
  double h;               /* spacing */
  sessile_buffer *mask;   /* uint32 per node, != 0: Dirichlet */
  const sessile_vec *diag;/* the cut-cell diagonal (see sessile_mat_create_stencil7_cut) */
  const sessile_vec *coef;/* NULL (the symmetric operator), or 6 off-diagonal weights per node:
                             the advective operator of sessile_mat_create_stencil7_cut_adv
                             (every level or none; the hierarchy is then a preconditioner for
                             BiCGSTAB or GMRES through pc "mg", and sessile_mg_solve refuses it) */
} sessile_mg_level;
/* levels[0] is the finest; level l+1 is nested in level l: n_{l+1} = (n_l - 1)/2 + 1 on every
 * axis, node (I,J,K) of l+1 is node (2I,2J,2K) of l, h_{l+1} = 2 h_l.  Coarse operators are
 * the caller's rediscretisations (their own mask and diag).  The caller owns the buffers and
 * may change their contents between solves (the recordings stay valid). */
typedef struct sessile_mg_options {
  int pre_smooth, post_smooth; /* damped-Jacobi sweeps (equal: the V-cycle is symmetric) */
  double omega;                /* Jacobi damping, in (0, 1] (default 6/7) */
  int coarse_sweeps;           /* Jacobi sweeps on the coarsest level (a fixed linear operator) */
} sessile_mg_options;
/* pre_smooth = post_smooth = 2, omega = 6/7, coarse_sweeps = 8 (docs/la.md has the
 * measurements behind them). */
void sessile_mg_options_default(sessile_mg_options *o);
/* Checks the levels (sizes nested, spacings doubling, buffers present and large enough) and
 * the options (pre_smooth = post_smooth >= 1, omega in (0, 1], coarse_sweeps >= 1); any
 * violation is SESSILE_ERR_USAGE naming the level and what is wrong.  o NULL: the defaults.
 * At most 16 levels. */
sessile_status sessile_mg_create(sessile_la *la, int nlevels, const sessile_mg_level *levels,
                                 const sessile_mg_options *o, sessile_mg **out);
void sessile_mg_destroy(sessile_mg *mg);
/* PCG on the finest operator, preconditioned by one V-cycle; x = warm start on entry.
 * Converges on the true relative residual rtol (res->true_relres recomputed at the end),
 * same result struct and monitor as sessile_ksp_solve.  Of the options only rtol, max_it
 * and the monitor apply: the method is always CG with the V-cycle, submitted one iteration
 * at a time (docs/la.md says why).  A solve with the same b and x objects
 * as the previous one re-records nothing.  fp32 contexts: mixed-precision refinement as in
 * sessile_ksp_solve. */
sessile_status sessile_mg_solve(sessile_mg *mg, const sessile_ksp_options *o, const sessile_vec *b,
                                sessile_vec *x, sessile_solve_result *res);
/* z = M r, one V-cycle (the preconditioner alone, for tests: symmetry, positivity). */
sessile_status sessile_mg_vcycle(sessile_mg *mg, const sessile_vec *r, sessile_vec *z);

#ifdef __cplusplus
}
#endif
#endif
