/* MG-preconditioned CG, the host side: re-record only for new b or x, run
 * the start, submit one iteration at a time until the device stops (why one:
 * mg_record.c), recompute the true residual and restart from x while it lags
 * rtol (as ksp.c does); on fp32 contexts all of that inside ksp.c's
 * mixed-precision refinement. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "mg_internal.h"

static sessile_status solve_device(sessile_mg *mg, const sessile_ksp_options *o,
                                   const sessile_vec *b, sessile_vec *x, sessile_solve_result *res) {
  sessile_la *la = mg->la;
  if (b->serial != mg->rec_b || x->serial != mg->rec_x) SESSILE_CALL(mg_record(mg, b, x));
  sessile_ksp_options oo = *o;
  for (int attempt = 0; attempt < 4; attempt++) {
    oo.max_it = o->max_it - res->iterations;
    if (oo.max_it <= 0) {
      res->status = SESSILE_SOLVE_MAX_ITER;
      break;
    }
    la_solver_reset(la, &oo);
    SESSILE_CALL(sessile_cmd_submit_wait(mg->start));
    double bb = la_scalar_read(la, S_BB);
    if (!isfinite(bb)) {
      res->status = SESSILE_SOLVE_BREAKDOWN;
      res->true_relres = NAN;
      snprintf(res->reason, sizeof res->reason, "the right-hand side contains NaN or Inf");
      return SESSILE_OK;
    }
    if (bb == 0) { /* the solution of A x = 0 is x = 0 */
      SESSILE_CALL(sessile_vec_fill(la, 0.0, x));
      res->status = SESSILE_SOLVE_CONVERGED;
      res->true_relres = 0;
      snprintf(res->reason, sizeof res->reason, "zero right-hand side: x = 0");
      return SESSILE_OK;
    }
    SESSILE_CALL(la_solver_loop(la, mg->iter, 1, oo.max_it, o, "mg-pcg", CG_RR, 1));
    la_solver_outcome(la, res, sqrt(fmax(la_scalar_read(la, CG_RR), 0) / bb));
    SESSILE_CALL(sessile_cmd_submit_wait(mg->resid));
    res->true_relres = la_scalar_read(la, S_TRUE) / sqrt(bb);
    if (!isfinite(res->true_relres)) {
      res->status = SESSILE_SOLVE_BREAKDOWN;
      snprintf(res->reason, sizeof res->reason, "a non-finite value (NaN/Inf) appeared");
    }
    if (res->status != SESSILE_SOLVE_CONVERGED || res->true_relres <= o->rtol) break;
    la_monitorf(o, "mg-pcg: true residual %.3e > rtol after convergence: restarting",
                res->true_relres);
    res->status = SESSILE_SOLVE_MAX_ITER; /* unless the restart converges */
    snprintf(res->reason, sizeof res->reason, "true residual stayed above rtol after restarts");
  }
  return SESSILE_OK;
}

static sessile_status mg_inner(void *ctx, const sessile_ksp_options *o, const sessile_vec *q,
                               sessile_vec *d, sessile_solve_result *res) {
  return solve_device(ctx, o, q, d, res);
}

sessile_status sessile_mg_solve(sessile_mg *mg, const sessile_ksp_options *opt, const sessile_vec *b,
                                sessile_vec *x, sessile_solve_result *res) {
  sessile_ksp_options o;
  if (opt) o = *opt;
  else sessile_ksp_options_default(&o);
  memset(res, 0, sizeof *res);
  sessile_la *la = mg->la;
  uint32_t n = mg->lv[0].nodes;
  SESSILE_CHECK(b && x, SESSILE_ERR_USAGE, "multigrid solve: b and x are required");
  SESSILE_CHECK(!mg->lv[0].coef, SESSILE_ERR_USAGE,
                "multigrid solve: the advective operator is nonsymmetric and CG does not apply; "
                "use the hierarchy as pc \"mg\" of BiCGSTAB or GMRES (sessile_ksp_solve_pc)");
  SESSILE_CHECK(b->n == n && x->n == n && b->la == la && x->la == la, SESSILE_ERR_USAGE,
                "multigrid solve: the finest level has %u nodes, b %u and x %u entries%s", n, b->n,
                x->n, b->la == la && x->la == la ? "" : " (or they belong to another la)");
  SESSILE_CHECK(o.rtol > 0 && o.rtol < 1, SESSILE_ERR_USAGE, "rtol must be in (0, 1), got %g", o.rtol);
  SESSILE_CHECK(o.max_it > 0, SESSILE_ERR_USAGE, "max_it must be positive, got %d", o.max_it);
  double t0 = sessile_wall_seconds();
  sessile_status s = SESSILE_OK;
  if (la->real_bytes == 8) s = solve_device(mg, &o, b, x, res);
  else {
    double bnorm;
    s = sessile_vec_nrm2(la, b, &bnorm);
    if (s == SESSILE_OK && !(bnorm > 0 && isfinite(bnorm))) { /* as solve_device does */
      int zero = bnorm == 0;
      if (zero) s = sessile_vec_fill(la, 0.0, x);
      res->status = zero ? SESSILE_SOLVE_CONVERGED : SESSILE_SOLVE_BREAKDOWN;
      res->true_relres = zero ? 0 : NAN;
      snprintf(res->reason, sizeof res->reason, "%s",
               zero ? "zero right-hand side: x = 0" : "the right-hand side contains NaN or Inf");
      res->seconds = sessile_wall_seconds() - t0;
      return s;
    }
    if (s == SESSILE_OK && !mg->rb) s = sessile_vec_create(la, n, &mg->rb);
    if (s == SESSILE_OK && !mg->dx) s = sessile_vec_create(la, n, &mg->dx);
    if (s == SESSILE_OK)
      s = la_solve_refined(la, &o, mg->lv[0].a, b, x, mg->rb, mg->dx, mg_inner, mg, res);
  }
  res->seconds = sessile_wall_seconds() - t0;
  if (s == SESSILE_OK)
    la_monitorf(&o, "mg-pcg: %s after %d iterations, true relative residual %.3e (%.3f s)",
                sessile_solve_status_name(res->status), res->iterations, res->true_relres,
                res->seconds);
  return s;
}

sessile_status sessile_mg_vcycle(sessile_mg *mg, const sessile_vec *r, sessile_vec *z) {
  uint32_t n = mg->lv[0].nodes;
  SESSILE_CHECK(r && z && r->n == n && z->n == n && r->la == mg->la && z->la == mg->la,
                SESSILE_ERR_USAGE, "multigrid V-cycle: r and z need the finest level's %u nodes", n);
  SESSILE_CHECK(r != z, SESSILE_ERR_USAGE, "multigrid V-cycle: r and z must be different vectors");
  SESSILE_CALL(sessile_cmd_begin(mg->misc));
  SESSILE_CALL(mg_rec_vcycle(mg, mg->misc, vref_of(r), vref_of(z), 0, 0, NULL, -1));
  SESSILE_CALL(sessile_cmd_end(mg->misc));
  return sessile_cmd_submit_wait(mg->misc);
}
