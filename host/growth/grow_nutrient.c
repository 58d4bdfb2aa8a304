/* The nutrient of one growth iteration: the uploaded surface classified
 * on every box level (the solid mask and the cut fractions), then the field
 * solved (Laplace with cut cells, warm-started; or advected by the flow,
 * with the same cut cells, or on the tetrahedra with advection_scheme = tet),
 * recorded under "nutrient_solve". */
#include "grow_internal.h"

sessile_status grow_classify(grow_run *r) {
  /* The solid mask and the cut fractions on every box level (the nutrient's
   * multigrid rediscretises the cut cells on each). */
  for (int l = 0; l < sessile_cut_nutrient_levels(r->nutrient); l++) {
    sessile_box lb;
    sessile_buffer *solid, *theta;
    sessile_cut_nutrient_level(r->nutrient, l, &lb, &solid, &theta);
    SESSILE_CALL(sessile_growth_gpu_cut(r->growth, &lb, solid, theta));
  }
  return SESSILE_OK;
}

enum { LAPLACE, ADVECT_CUT, ADVECT_TET };

static void record_solve(cJSON *rec, int eq, sessile_cut_solver solver, const sessile_solve_result *res) {
  static const char *const eqs[] = {"Laplace (diffusion limited), cut-cell boundary",
                                    "advection-diffusion (exponentially fitted), cut-cell boundary, u from the flow",
                                    "advection-diffusion (SUPG on tetrahedra), u from the flow"};
  int mg = solver == SESSILE_CUT_SOLVER_MG;
  cJSON *ns = cJSON_AddObjectToObject(rec, "nutrient_solve");
  cJSON_AddStringToObject(ns, "equation", eqs[eq]);
  cJSON_AddStringToObject(ns, "solver", eq == ADVECT_TET ? "bicgstab+jacobi"
                                        : eq == ADVECT_CUT ? (mg ? "bicgstab+multigrid" : "bicgstab+jacobi")
                                        : mg ? "pcg+multigrid" : "pcg+jacobi");
  cJSON_AddNumberToObject(ns, "iterations", res->iterations);
  cJSON_AddNumberToObject(ns, "true_relres", res->true_relres);
  cJSON_AddStringToObject(ns, "status", sessile_solve_status_name(res->status));
  cJSON_AddStringToObject(ns, "reason", res->reason);
  cJSON_AddNumberToObject(ns, "seconds", res->seconds);
}

sessile_status grow_nutrient_solve(grow_run *r, int it, cJSON *rec, const sessile_vec **probe_field) {
  int eq = r->p->diffusion_limited ? LAPLACE
           : r->p->advection_scheme == SESSILE_ADVECTION_TET ? ADVECT_TET : ADVECT_CUT;
  sessile_ksp_options ko;
  sessile_ksp_options_default(&ko);
  ko.type = SESSILE_KSP_CG;
  ko.pc = SESSILE_PC_JACOBI;
  ko.rtol = r->p->nutrient_ksp_rtol;
  ko.max_it = r->p->nutrient_ksp_max_it;
  sessile_solve_result res;
  sessile_cut_solver solver =
      r->p->nutrient_pc_type == SESSILE_SOLVER_MG ? SESSILE_CUT_SOLVER_MG : SESSILE_CUT_SOLVER_JACOBI;
  if (eq == ADVECT_TET) SESSILE_CALL(grow_nutrient_advected(r, &res));
  else if (eq == ADVECT_CUT)
    SESSILE_CALL(sessile_cut_nutrient_solve_advected(r->nutrient, solver, r->ufine,
                                                     r->p->diffusion_coefficient, r->c, &ko, &res));
  else SESSILE_CALL(sessile_cut_nutrient_solve(r->nutrient, solver, r->c, &ko, &res));
  /* The flux probe reads the field extended across the surface (the cut
   * solves extend it themselves). */
  if (eq == ADVECT_TET && r->p->probe == SESSILE_PROBE_FLUX)
    SESSILE_CALL(sessile_cut_nutrient_extend(r->nutrient, r->c));
  *probe_field = r->p->probe == SESSILE_PROBE_FLUX ? sessile_cut_nutrient_extended(r->nutrient) : r->c;
  record_solve(rec, eq, solver, &res);
  r->sum.solver_iterations += res.iterations;
  if (res.true_relres > r->sum.worst_relres) r->sum.worst_relres = res.true_relres;
  SESSILE_CHECK(res.status != SESSILE_SOLVE_BREAKDOWN, SESSILE_ERR_NUMERIC,
                "iteration %d: the nutrient solve broke down (%s); the run stops here, its "
                "files so far are whole", it, res.reason);
  if (res.status != SESSILE_SOLVE_CONVERGED)
    grow_warn(r, "iteration %d: nutrient solve stopped at %d iterations with true relative residual "
                 "%.2e (%s); raise nutrient_ksp_max_it", it, res.iterations, res.true_relres, res.reason);
  return SESSILE_OK;
}
