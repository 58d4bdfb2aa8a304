/* The stationary Navier-Stokes solve: Newton (after optional Picard steps)
 * with a backtracking line search on ||R||, its stopping rules and the
 * progress lines; decisions and measurements are in docs/fluid.md. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fem/ns_internal.h"

/* Each step's linear tolerance (params.forcing; the constants are
 * Eisenstat-Walker choice 2 with PETSc's defaults, fluid.h). */
#define EW_ETA0 0.3
#define EW_ETA_MAX 0.9
#define EW_ALPHA 1.6180339887498949 /* (1 + sqrt 5) / 2 */
#define EW_THRESHOLD 0.1
static double forcing(const sessile_fluid_params *p, int it, double rn, double rn_last, double eta_last) {
  if (p->forcing != SESSILE_FLUID_FORCING_EW) return p->linear_rtol;
  double eta = EW_ETA0;
  if (it > 0 && rn_last > 0) {
    eta = pow(rn / rn_last, EW_ALPHA);
    double keep = pow(eta_last, EW_ALPHA); /* no sudden tightening (EW's safeguard) */
    if (keep > EW_THRESHOLD && keep > eta) eta = keep;
  }
  if (eta > EW_ETA_MAX) eta = EW_ETA_MAX;
  return eta > p->linear_rtol ? eta : p->linear_rtol;
}

/* The residual and Jacobian at up, the boundary rows applied: ||R||. */
static double assemble_jacobian(sessile_fluid *fl, const sessile_fluid_params *p, const uint8_t *bc,
                                const double *up, int picard, double *r) {
  ns_assemble(fl, p, up, picard ? 0.0 : 1.0, 1, r);
  return ns_apply_bc_rows(fl, bc, 1, r);
}

void ns_monitor(const sessile_fluid_params *p, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  sessile_monitor_vprintf(p->monitor, p->monitor_user, fmt, ap);
  va_end(ap);
}

sessile_status sessile_fluid_solve(sessile_fluid *fl, const uint8_t *solid, const sessile_fluid_params *p,
                                   double *up, sessile_fluid_result *res) {
  SESSILE_CHECK(fl && p && up && res, SESSILE_ERR_USAGE,
                "fluid solve needs a solver, parameters, a state and a result");
  memset(res, 0, sizeof *res);
  SESSILE_CHECK(p->eta > 0 && p->rho >= 0 && isfinite(p->rho) && isfinite(p->eta), SESSILE_ERR_USAGE,
                "fluid needs eta > 0 and rho >= 0 (got eta %g, rho %g)", p->eta, p->rho);
  SESSILE_CHECK(p->newton_max >= 1 && p->newton_max < SESSILE_FLUID_MAX_STEPS, SESSILE_ERR_USAGE,
                "newton_max must be between 1 and %d (got %d)", SESSILE_FLUID_MAX_STEPS - 1,
                p->newton_max);
  double t0 = sessile_wall_seconds();
  size_t n4 = (size_t)fl->nnodes * 4;
  uint8_t *bc = malloc(fl->nnodes);
  double *r = malloc(n4 * sizeof *r), *du = malloc(n4 * sizeof *du);
  sessile_vec *b = NULL, *x = NULL;
  sessile_status s = SESSILE_OK;
  if (!bc || !r || !du) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
  if (s == SESSILE_OK) s = sessile_vec_create(fl->la, (uint32_t)n4, &b);
  if (s == SESSILE_OK) s = sessile_vec_create(fl->la, (uint32_t)n4, &x);
  if (s == SESSILE_OK) {
    for (uint32_t i = 0; i < fl->nnodes; i++) bc[i] = ns_node_bc(fl, solid, p, i);
    /* the reference residual: the rest state with the boundary values */
    memset(du, 0, n4 * sizeof *du);
    ns_impose_bc(fl, solid, p, bc, du);
    ns_assemble(fl, p, du, 1.0, 0, r);
    res->residual_rest = ns_apply_bc_rows(fl, bc, 0, r);
    ns_impose_bc(fl, solid, p, bc, up);
    /* from rest, up is the rest state: its residual is the one just assembled */
    double r_up = memcmp(up, du, n4 * sizeof *up) ? -1.0 : res->residual_rest;
    if (p->nested) s = ns_nested_start(fl, solid, p, bc, up, r_up, r, res);
  }
  int stalled = 0; /* Newton steps running whose line search found no decrease */
  double rn_last = 0, eta_last = 0;
  /* ||R|| at up when the line search's accepted trial left it in r: the
   * tests below need no Jacobian, which is assembled (with the same r, bit
   * for bit) only when a step follows; the converged state's was wasted */
  double rn_known = -1;
  for (int it = 0; s == SESSILE_OK; it++) {
    int picard = it < p->picard_steps;
    double ta = sessile_wall_seconds();
    int have_jac = rn_known < 0;
    double rn = have_jac ? assemble_jacobian(fl, p, bc, up, picard, r) : rn_known;
    rn_known = -1;
    double tass = sessile_wall_seconds() - ta;
    if (!isfinite(rn)) {
      s = sessile_error_set(SESSILE_ERR_NUMERIC,
                            "Navier-Stokes residual is not finite at step %d; try picard_steps > 0 "
                            "or a smaller inlet velocity", it);
      break;
    }
    if (it == 0) res->residual0 = rn;
    res->residual = rn;
    res->assembly_s += tass;
    if (rn <= p->newton_rtol * res->residual_rest || rn <= p->newton_atol || rn == 0) {
      res->converged = 1;
      break;
    }
    if (it >= p->newton_max) break;
    /* A hopeless but in-range setting (e.g. eta = 1e-9 Pa s, Re ~ 1e9) must
     * fail with a message, not run for hours: a wall-clock bound, and a
     * stop once the line search finds no decrease several steps running. */
    double el = sessile_wall_seconds() - t0;
    if (p->max_seconds > 0 && el > p->max_seconds) {
      s = sessile_error_set(SESSILE_ERR_NUMERIC,
                            "the flow solve passed its time bound (%.0f s > %g s) after %d Newton steps at "
                            "residual %.2e (%.2e of the rest state's); the setting may be hopeless "
                            "(Reynolds number, viscosity) or raise fluid_max_seconds",
                            el, p->max_seconds, it, rn, res->residual_rest > 0 ? rn / res->residual_rest : 0.0);
      break;
    }
    if (it >= 20 && rn > 10 * p->newton_rtol * res->residual_rest) {
      s = sessile_error_set(SESSILE_ERR_NUMERIC,
                            "the flow solve is not converging: after %d Newton steps the residual is "
                            "still %.2e of the rest state's (the target is %g); the setting may be "
                            "hopeless (Reynolds number, viscosity)", it, rn / res->residual_rest,
                            p->newton_rtol);
      break;
    }
    if (stalled >= 5) {
      s = sessile_error_set(SESSILE_ERR_NUMERIC,
                            "the flow solve stagnated: %d Newton steps running found no decrease of the "
                            "residual (%.2e, %.2e of the rest state's); the setting may be hopeless "
                            "(Reynolds number, viscosity)", stalled, rn,
                            res->residual_rest > 0 ? rn / res->residual_rest : 0.0);
      break;
    }
    if (!have_jac) {
      ta = sessile_wall_seconds();
      assemble_jacobian(fl, p, bc, up, picard, r);
      double tj = sessile_wall_seconds() - ta;
      tass += tj;
      res->assembly_s += tj;
    }
    sessile_fluid_step *st = &res->step[it];
    st->residual = rn;
    st->picard = picard;
    st->assembly_s = tass;
    st->lin_rtol = eta_last = forcing(p, it, rn, rn_last, eta_last);
    rn_last = rn;
    double ts = sessile_wall_seconds();
    s = ns_linear_solve(fl, p, solid, up, picard ? 0.0 : 1.0, r, du, b, x, st);
    st->solve_s = sessile_wall_seconds() - ts;
    if (s != SESSILE_OK) break;
    res->solve_s += st->solve_s;
    res->lin_iterations += st->lin_iterations;
    res->nsteps = it + 1;
    /* backtracking on ||R||: halve the step while the residual does not
     * decrease (at most 6 times); a full step near the solution (quadratic) */
    double lam = 1.0;
    for (int ls = 0; ls < 7; ls++) {
      for (size_t k = 0; k < n4; k++) up[k] += lam * du[k];
      if (ls == 6) {
        stalled++; /* no decrease: the smallest step is taken anyway */
        break;
      }
      ns_assemble(fl, p, up, 1.0, 0, r);
      double rt = ns_apply_bc_rows(fl, bc, 0, r);
      if (isfinite(rt) && rt < (1.0 - 1e-4 * lam) * rn) {
        stalled = 0;
        rn_known = rt;
        break;
      }
      for (size_t k = 0; k < n4; k++) up[k] -= lam * du[k];
      lam *= 0.5;
    }
    st->step_length = lam;
    ns_monitor(p, "fluid %s %d: |R| %.3e (rel %.2e)  step %.3g  lin %d it relres %.2e (aim %.1e) %s  asm %.2f s solve %.2f s",
                  picard ? "picard" : "newton", it, rn, rn / res->residual_rest, lam, st->lin_iterations,
                  st->lin_relres, st->lin_rtol, sessile_solve_status_name(st->lin_status), tass, st->solve_s);
  }
  if (s == SESSILE_OK)
    ns_monitor(p, "fluid: %s after %d steps, |R| %.3e (rel %.2e)",
                  res->converged ? "converged" : "NOT converged", res->nsteps, res->residual,
                  res->residual_rest > 0 ? res->residual / res->residual_rest : 0.0);
  sessile_vec_destroy(b);
  sessile_vec_destroy(x);
  free(bc);
  free(r);
  free(du);
  res->seconds = sessile_wall_seconds() - t0;
  return s;
}
