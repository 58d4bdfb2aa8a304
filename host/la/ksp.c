/* Krylov solve driver: options, the zero right-hand side, the preconditioner
 * object (the options' enum builds one when the caller gives none),
 * restarts when the true residual lags the recursive one, and
 * mixed-precision iterative refinement on fp32 devices. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "pc_internal.h"
#include "sessile/la/la_ref.h"

void sessile_ksp_options_default(sessile_ksp_options *o) {
  memset(o, 0, sizeof *o);
  o->type = SESSILE_KSP_CG;
  o->pc = SESSILE_PC_JACOBI;
  o->rtol = 1e-6;
  o->max_it = 1000;
  o->restart = 30;
  o->check_every = 16;
}

const char *sessile_ksp_type_name(sessile_ksp_type t) {
  switch (t) {
  case SESSILE_KSP_CG: return "cg";
  case SESSILE_KSP_BICGSTAB: return "bicgstab";
  case SESSILE_KSP_GMRES: return "gmres";
  }
  return "?";
}

const char *sessile_solve_status_name(sessile_solve_status s) {
  switch (s) {
  case SESSILE_SOLVE_CONVERGED: return "converged";
  case SESSILE_SOLVE_MAX_ITER: return "max-iterations";
  case SESSILE_SOLVE_BREAKDOWN: return "breakdown";
  }
  return "?";
}

static const char *reason_text(int code) {
  switch (code) {
  case 1: return "p·Ap <= 0: the matrix is not symmetric positive definite (use bicgstab or gmres)";
  case 2: return "a non-finite value (NaN/Inf) appeared: the matrix or right-hand side is invalid or singular";
  case 3: return "r0·r = 0 (BiCGSTAB breakdown): try gmres";
  case 4: return "r0·A p = 0 (BiCGSTAB breakdown): try gmres";
  case 5: return "A s = 0 (BiCGSTAB breakdown): the matrix is singular";
  case 6: return "the iteration stagnated: the matrix is probably singular";
  default: return "breakdown";
  }
}

void la_solver_outcome(sessile_la *la, sessile_solve_result *res, double est) {
  double stop = la_scalar_read(la, S_STOP);
  res->iterations += (int)la_scalar_read(la, S_ITER);
  res->est_relres = est;
  if (stop == STOP_CONVERGED) {
    res->status = SESSILE_SOLVE_CONVERGED;
    snprintf(res->reason, sizeof res->reason, "relative residual <= rtol");
  } else if (stop == STOP_MAXIT) {
    res->status = SESSILE_SOLVE_MAX_ITER;
    snprintf(res->reason, sizeof res->reason, "reached the iteration limit before rtol");
  } else {
    res->status = SESSILE_SOLVE_BREAKDOWN;
    snprintf(res->reason, sizeof res->reason, "%s", reason_text((int)la_scalar_read(la, S_REASON)));
  }
}

/* ‖b − A x‖ on the device (into S_TRUE); r and q are scratch. */
static sessile_status true_residual(sessile_la *la, const sessile_mat *a, const sessile_vec *b,
                                    const sessile_vec *x, sessile_vec *q, double *norm) {
  sessile_cmd *c = la->cmd;
  uint32_t count, n = a->nrows;
  vref none = {0};
  SESSILE_CALL(sessile_cmd_begin(c));
  SESSILE_CALL(rec_spmv(la, c, a, vref_of(x), vref_of(q), -1));
  SESSILE_CALL(rec_vec(la, c, K_WAXPY, n, vref_of(q), vref_of(b), vref_of(q), -1, COEF_NEG, -1));
  SESSILE_CALL(rec_dot(la, c, n, vref_of(q), vref_of(q), 0, -1, &count));
  SESSILE_CALL(rec_reduce(la, c, count, 0, 1, S_TRUE, 1, -1));
  (void)none;
  SESSILE_CALL(sessile_cmd_end(c));
  SESSILE_CALL(sessile_cmd_submit_wait(c));
  *norm = la_scalar_read(la, S_TRUE);
  return SESSILE_OK;
}

static sessile_status run_type(sessile_la *la, const sessile_ksp_options *o, const sessile_mat *a,
                               const sessile_vec *b, sessile_vec *x, const sessile_pc *pc,
                               sessile_solve_result *res) {
  switch (o->type) {
  case SESSILE_KSP_CG: return la_cg(la, o, a, b, x, pc, res);
  case SESSILE_KSP_BICGSTAB: return la_bicgstab(la, o, a, b, x, pc, res);
  case SESSILE_KSP_GMRES: return la_gmres(la, o, a, b, x, pc, res);
  }
  return sessile_error_set(SESSILE_ERR_USAGE, "unknown solver type %d", (int)o->type);
}

/* The device solve with restarts until the *true* residual meets rtol (the
 * recursive residual drifts from it in finite precision). */
static sessile_status solve_device(sessile_la *la, const sessile_ksp_options *o,
                                   const sessile_mat *a, const sessile_vec *b, sessile_vec *x,
                                   const sessile_pc *pc, sessile_vec *q, double bnorm,
                                   sessile_solve_result *res) {
  sessile_ksp_options oo = *o;
  for (int attempt = 0; attempt < 4; attempt++) {
    oo.max_it = o->max_it - res->iterations;
    if (oo.max_it <= 0) { res->status = SESSILE_SOLVE_MAX_ITER; break; }
    SESSILE_CALL(run_type(la, &oo, a, b, x, pc, res));
    double rn;
    SESSILE_CALL(true_residual(la, a, b, x, q, &rn));
    res->true_relres = rn / bnorm;
    if (!isfinite(res->true_relres)) {
      res->status = SESSILE_SOLVE_BREAKDOWN;
      snprintf(res->reason, sizeof res->reason, "%s", reason_text(2));
    }
    if (res->status != SESSILE_SOLVE_CONVERGED || res->true_relres <= o->rtol) break;
    la_monitorf(o, "%s: true residual %.3e > rtol after convergence: restarting",
                sessile_ksp_type_name(o->type), res->true_relres);
    res->status = SESSILE_SOLVE_MAX_ITER; /* unless the restart converges */
    snprintf(res->reason, sizeof res->reason, "true residual stayed above rtol after restarts");
  }
  return SESSILE_OK;
}

/* Host residual r = b − A x in double (CSR, block CSR, or the 7-point
 * operators with their mask and diagonal downloaded once per solve). */
static void host_residual(const sessile_mat *a, const uint32_t *mask, const double *diag,
                          const double *coef, const double *b, const double *x, double *r) {
  if (a->kind == MAT_STENCIL7)
    sessile_ref_stencil7(a->grid[0], a->grid[1], a->grid[2], a->h, mask, x, r);
  else if (a->kind == MAT_STENCIL7_CUT)
    sessile_ref_stencil7_cut_adv(a->grid[0], a->grid[1], a->grid[2], a->h, mask, diag, coef, x, r);
  else if (a->kind == MAT_CSR) sessile_ref_spmv_csr(&a->host, x, r);
  else sessile_ref_spmv_bcsr4(&a->hostb, x, r);
  for (uint32_t i = 0; i < a->nrows; i++) r[i] = b[i] - r[i];
}

/* fp32 devices: iterative refinement, x_{k+1} = x_k + A⁻¹(b − A x_k) with the
 * residual in double on the host and the correction solved on the device by
 * `inner` (q and d: its right-hand side and solution).
 * The reported true residual is that of the x the caller gets back (stored
 * in fp32), so it is honest about what fp32 storage allows. */
sessile_status la_solve_refined(sessile_la *la, const sessile_ksp_options *o, const sessile_mat *a,
                                const sessile_vec *b, sessile_vec *x, sessile_vec *q, sessile_vec *d,
                                la_inner_fn inner, void *ctx, sessile_solve_result *res) {
  uint32_t n = a->nrows;
  double *bh = malloc((size_t)n * 3 * sizeof(double));
  SESSILE_CHECK(bh, SESSILE_ERR_NO_MEMORY, "out of host memory");
  double *xh = bh + n, *rh = xh + n;
  uint32_t *mask = NULL;
  double *diag = NULL, *coef = NULL;
  sessile_status s = sessile_vec_download((sessile_vec *)b, bh);
  if (s == SESSILE_OK && (a->kind == MAT_STENCIL7 || a->kind == MAT_STENCIL7_CUT))
    s = la_stencil7_host_mask(a, &mask);
  if (s == SESSILE_OK && a->kind == MAT_STENCIL7_CUT) s = la_stencil7_cut_host_diag(a, &diag);
  if (s == SESSILE_OK && a->kind == MAT_STENCIL7_CUT) s = la_stencil7_cut_host_coef(a, &coef);
  if (s == SESSILE_OK) s = sessile_vec_download(x, xh);
  double bnorm = sessile_ref_nrm2(n, bh);
  sessile_ksp_options in = *o;
  in.rtol = fmax(o->rtol, 1e-4); /* what fp32 Krylov reliably reaches */
  in.x_zero = 1;                  /* each correction d starts from 0 */
  for (int k = 0; s == SESSILE_OK && k < 30; k++) {
    host_residual(a, mask, diag, coef, bh, xh, rh);
    double rel = sessile_ref_nrm2(n, rh) / bnorm;
    if (!isfinite(rel)) {
      res->status = SESSILE_SOLVE_BREAKDOWN;
      snprintf(res->reason, sizeof res->reason, "%s", reason_text(2));
      break;
    }
    /* Aim a little below rtol so that rounding x to fp32 keeps it below. */
    if (rel <= 0.5 * o->rtol) {
      res->status = SESSILE_SOLVE_CONVERGED;
      snprintf(res->reason, sizeof res->reason, "relative residual <= rtol");
      break;
    }
    if (res->iterations >= o->max_it) {
      res->status = SESSILE_SOLVE_MAX_ITER;
      snprintf(res->reason, sizeof res->reason, "reached the iteration limit before rtol");
      break;
    }
    /* Solve A d = r to in.rtol relative to ‖r‖. */
    if ((s = sessile_vec_upload(q, rh)) != SESSILE_OK) break;
    if ((s = sessile_vec_fill(la, 0.0, d)) != SESSILE_OK) break;
    in.max_it = o->max_it - res->iterations;
    if ((s = inner(ctx, &in, q, d, res)) != SESSILE_OK) break;
    res->refinements++;
    if (res->status == SESSILE_SOLVE_BREAKDOWN) break;
    if ((s = sessile_vec_download(d, rh)) != SESSILE_OK) break;
    for (uint32_t i = 0; i < n; i++) xh[i] += rh[i];
  }
  if (s == SESSILE_OK) s = sessile_vec_upload(x, xh);
  if (s == SESSILE_OK) s = sessile_vec_download(x, xh); /* x as stored, rounded to fp32 */
  if (s == SESSILE_OK) {
    host_residual(a, mask, diag, coef, bh, xh, rh);
    res->true_relres = sessile_ref_nrm2(n, rh) / bnorm;
    if (res->status == SESSILE_SOLVE_CONVERGED && !(res->true_relres <= o->rtol)) {
      res->status = SESSILE_SOLVE_MAX_ITER;
      snprintf(res->reason, sizeof res->reason,
               "fp32 storage of x limits the residual to %.2e (use an fp64 device)",
               res->true_relres);
    }
  }
  free(mask);
  free(diag);
  free(coef);
  free(bh);
  return s;
}

typedef struct { sessile_la *la; const sessile_mat *a; const sessile_pc *pc; } ksp_inner_ctx;
static sessile_status ksp_inner(void *ctx, const sessile_ksp_options *o, const sessile_vec *r,
                                sessile_vec *d, sessile_solve_result *res) {
  ksp_inner_ctx *c = ctx;
  return run_type(c->la, o, c->a, r, d, c->pc, res);
}

sessile_status sessile_ksp_solve(sessile_la *la, const sessile_ksp_options *opt,
                                 const sessile_mat *a, const sessile_vec *b, sessile_vec *x,
                                 sessile_solve_result *res) {
  return sessile_ksp_solve_pc(la, opt, a, NULL, b, x, res);
}

/* The options, and that the pc fits them (its type when the options' enum
 * is to build it: checked before any setup work). */
static sessile_status check_options(const sessile_ksp_options *o, const sessile_mat *a,
                                    const sessile_pc *pc, const sessile_vec *b,
                                    const sessile_vec *x) {
  SESSILE_CHECK(b->n == a->nrows && x->n == a->nrows, SESSILE_ERR_USAGE,
                "solve: matrix has %u rows, b %u and x %u entries", a->nrows, b->n, x->n);
  SESSILE_CHECK(o->rtol > 0 && o->rtol < 1, SESSILE_ERR_USAGE, "rtol must be in (0, 1), got %g", o->rtol);
  SESSILE_CHECK(o->max_it > 0, SESSILE_ERR_USAGE, "max_it must be positive, got %d", o->max_it);
  SESSILE_CHECK(o->restart >= 1 && o->restart <= 64, SESSILE_ERR_USAGE,
                "GMRES restart must be in 1..64, got %d", o->restart);
  const la_pc_ops *ops = pc ? pc->ops : la_pc_ops_of(o->pc);
  SESSILE_CHECK(ops, SESSILE_ERR_USAGE, "unknown preconditioner %d", (int)o->pc);
  SESSILE_CHECK(ops->symmetric || o->type != SESSILE_KSP_CG, SESSILE_ERR_USAGE,
                "%s is a nonsymmetric preconditioner and CG needs a symmetric one: use "
                "bicgstab or gmres with %s, or CG with a symmetric one (jacobi, block_jacobi, mg)",
                ops->name, ops->name);
  if (pc) {
    SESSILE_CHECK(pc->la == a->la, SESSILE_ERR_USAGE, "solve: the pc belongs to another la");
    SESSILE_CHECK(pc->n == a->nrows, SESSILE_ERR_USAGE,
                  "solve: pc %s is %s (the matrix has %u rows)", ops->name,
                  pc->n ? "set up for another size" : "not set up", a->nrows);
  }
  return SESSILE_OK;
}

/* The zero or non-finite right-hand side: answered without iterating
 * (*done = 1), or *done = 0. */
static sessile_status trivial_rhs(sessile_la *la, double bnorm, sessile_vec *x,
                                  sessile_solve_result *res, int *done) {
  *done = 1;
  if (!isfinite(bnorm)) {
    res->status = SESSILE_SOLVE_BREAKDOWN;
    res->true_relres = NAN;
    snprintf(res->reason, sizeof res->reason, "the right-hand side contains NaN or Inf");
    return SESSILE_OK;
  }
  if (bnorm == 0) { /* the solution of A x = 0 is x = 0: no iteration needed */
    res->status = SESSILE_SOLVE_CONVERGED;
    snprintf(res->reason, sizeof res->reason, "zero right-hand side: x = 0");
    return sessile_vec_fill(la, 0.0, x);
  }
  *done = 0;
  return SESSILE_OK;
}

sessile_status sessile_ksp_solve_pc(sessile_la *la, const sessile_ksp_options *opt,
                                    const sessile_mat *a, sessile_pc *pc, const sessile_vec *b,
                                    sessile_vec *x, sessile_solve_result *res) {
  sessile_ksp_options o;
  if (opt) o = *opt;
  else sessile_ksp_options_default(&o);
  memset(res, 0, sizeof *res);
  SESSILE_CALL(check_options(&o, a, pc, b, x));
  if (o.check_every < 1) o.check_every = 1;
  double t0 = sessile_wall_seconds();
  double bnorm;
  int done;
  SESSILE_CALL(sessile_vec_nrm2(la, b, &bnorm));
  sessile_status s = trivial_rhs(la, bnorm, x, res, &done);
  if (s != SESSILE_OK || done) {
    res->seconds = sessile_wall_seconds() - t0;
    return s;
  }
  sessile_pc *own = NULL; /* the options' pc, built here */
  sessile_vec *q = NULL, *d = NULL;
  if (!pc) {
    s = sessile_pc_create_type(la, o.pc, &own);
    if (s == SESSILE_OK) s = sessile_pc_setup(own, a);
    pc = own;
  }
  if (s == SESSILE_OK) s = sessile_vec_create(la, a->nrows, &q);
  if (s == SESSILE_OK && la->real_bytes != 8) s = sessile_vec_create(la, a->nrows, &d);
  ksp_inner_ctx ctx = {la, a, pc};
  if (s == SESSILE_OK)
    s = la->real_bytes == 8 ? solve_device(la, &o, a, b, x, pc, q, bnorm, res)
                            : la_solve_refined(la, &o, a, b, x, q, d, ksp_inner, &ctx, res);
  sessile_vec_destroy(d);
  sessile_vec_destroy(q);
  sessile_pc_destroy(own);
  res->seconds = sessile_wall_seconds() - t0;
  if (s == SESSILE_OK)
    la_monitorf(&o, "%s: %s after %d iterations, true relative residual %.3e (%.3f s)",
                sessile_ksp_type_name(o.type), sessile_solve_status_name(res->status),
                res->iterations, res->true_relres, res->seconds);
  return s;
}
