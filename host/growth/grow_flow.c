/* The flow and the advected nutrient in the growth loop (paper §4.2-4.3).
 *
 * Flow: stationary Navier-Stokes (host/fem, docs/fluid.md) on either
 *  - the immersed domain: the box at level fluid_resolution (nested in the
 *    nutrient box), solid nodes from the same ray-parity classification;
 *    warm-started from the previous iteration's flow; or
 *  - the conforming domain: TetGen's mesh of the box minus the current
 *    sponge, warm-started from the previous flow interpolated onto it; where
 *    TetGen rejects the surface the iteration falls back to the immersed
 *    domain, with a warning in the manifest and on the terminal.
 * The velocity and pressure are then interpolated (P1) to the nutrient box's
 * nodes (ufine, pfine): zero inside the sponge.
 *
 * Nutrient with advection: by default the cut-cell solve of host/fem
 * (grow_nutrient.c); with advection_scheme = tet the SUPG advection-diffusion
 * below (docs/advdiff.md) on the nutrient box's tetrahedra with that
 * velocity, the paper's boundary conditions, solved on the GPU; its field is
 * clamped into [0, 1] (SUPG's small over- and undershoots near layers)
 * before the probe reads it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "grow_internal.h"

void grow_fluid_params(const grow_run *r, sessile_fluid_params *fp) {
  sessile_fluid_params_default(fp);
  fp->rho = r->p->fluid_density;
  fp->eta = r->p->fluid_viscosity;
  fp->inlet[0] = r->p->inlet_velocity;
  fp->inlet[1] = fp->inlet[2] = 0;
  fp->max_seconds = r->p->fluid_max_seconds;
  sessile_params_fluid_solver(r->p, fp);
}

/* The immersed flow's box, mesh and solver, once. */
sessile_status grow_flow_setup(grow_run *r) {
  if (r->flow_ready) return SESSILE_OK;
  const sessile_grow_params *p = r->p;
  const double origin[3] = {0, 0, 0};
  const uint32_t cells[3] = {(uint32_t)p->box_cells_x, (uint32_t)p->box_cells_y,
                             (uint32_t)p->box_cells_z};
  /* Each piece once: a diffusion-limited run goes on after a failed flow
   * and calls this again, which then completes what is missing (nothing is
   * made twice; grow_flow_teardown frees what there is). */
  if (!r->fmesh.nnodes) {
    SESSILE_CALL(sessile_box_make(origin, p->box_base_cell, cells, p->fluid_resolution, &r->fbox));
    SESSILE_CALL(sessile_tetmesh_from_box(&r->fbox, &r->fmesh));
  }
  if (!r->fluid) SESSILE_CALL(sessile_fluid_create(r->la, &r->fmesh, &r->fluid));
  uint32_t nf = sessile_box_nodes(&r->fbox), nb = sessile_box_nodes(&r->box);
  if (!r->fsolid)
    SESSILE_CALL(sessile_buffer_create(r->gpu, (size_t)nf * 4, SESSILE_BUFFER_DEVICE, &r->fsolid));
  if (!r->up) r->up = calloc((size_t)nf * 4, sizeof *r->up);
  if (!r->ufine) r->ufine = calloc((size_t)nb * 3, sizeof *r->ufine);
  if (!r->pfine) r->pfine = calloc(nb, sizeof *r->pfine);
  SESSILE_CHECK(r->up && r->ufine && r->pfine, SESSILE_ERR_NO_MEMORY, "out of host memory for the flow");
  r->flow_ready = 1;
  return SESSILE_OK;
}

void grow_flow_teardown(grow_run *r) {
  sessile_fluid_destroy(r->fluid);
  sessile_buffer_destroy(r->fsolid);
  sessile_tetmesh_free(&r->fmesh);
  sessile_tetmesh_free(&r->cmesh);
  sessile_advdiff_destroy(r->ad);
  sessile_tetmesh_free(&r->nmesh);
  free(r->up), free(r->cup), free(r->ufine), free(r->pfine);
  free(r->nmask), free(r->nsolid), free(r->nval), free(r->nc);
}

/* Downloads a uint32 mask buffer into bytes. */
static sessile_status mask_download(sessile_buffer *b, uint32_t n, uint8_t *out) {
  uint32_t *t = malloc((size_t)n * 4);
  SESSILE_CHECK(t, SESSILE_ERR_NO_MEMORY, "out of host memory for a mask");
  sessile_status s = sessile_buffer_download(b, 0, t, (size_t)n * 4);
  for (uint32_t i = 0; s == SESSILE_OK && i < n; i++) out[i] = t[i] != 0;
  free(t);
  return s;
}

static void record_fluid(cJSON *fl, const sessile_fluid_result *res, uint32_t nodes) {
  cJSON_AddNumberToObject(fl, "nodes", nodes);
  cJSON_AddBoolToObject(fl, "converged", res->converged);
  cJSON_AddNumberToObject(fl, "newton_steps", res->nsteps);
  cJSON_AddNumberToObject(fl, "residual_rest", res->residual_rest);
  cJSON_AddNumberToObject(fl, "residual_initial", res->residual0);
  cJSON_AddNumberToObject(fl, "residual_final", res->residual);
  cJSON_AddNumberToObject(fl, "linear_iterations", res->lin_iterations);
  cJSON_AddNumberToObject(fl, "assembly_seconds", res->assembly_s);
  cJSON_AddNumberToObject(fl, "solve_seconds", res->solve_s);
  cJSON_AddNumberToObject(fl, "seconds", res->seconds);
  if (res->coarse_tried) { /* fluid_nested: the solve on the box of twice the spacing */
    cJSON *n = cJSON_AddObjectToObject(fl, "nested_start");
    if (n) {
      cJSON_AddBoolToObject(n, "taken", res->started_coarse);
      cJSON_AddNumberToObject(n, "newton_steps", res->coarse_steps);
      cJSON_AddNumberToObject(n, "linear_iterations", res->coarse_lin_iterations);
      cJSON_AddNumberToObject(n, "seconds", res->coarse_seconds);
    }
  }
  cJSON *steps = cJSON_AddArrayToObject(fl, "steps");
  for (int k = 0; steps && k < res->nsteps && k < SESSILE_FLUID_MAX_STEPS; k++) {
    const sessile_fluid_step *st = &res->step[k];
    cJSON *o = cJSON_CreateObject();
    if (!o) break; /* out of memory: the record is shorter, the run goes on */
    cJSON_AddNumberToObject(o, "residual", st->residual);
    cJSON_AddStringToObject(o, "kind", st->picard ? "picard" : "newton");
    cJSON_AddNumberToObject(o, "linear_iterations", st->lin_iterations);
    cJSON_AddNumberToObject(o, "linear_rtol", st->lin_rtol);
    cJSON_AddNumberToObject(o, "linear_true_relres", st->lin_relres);
    cJSON_AddStringToObject(o, "linear_status", sessile_solve_status_name(st->lin_status));
    cJSON_AddStringToObject(o, "krylov", sessile_ksp_type_name(st->lin_ksp));
    cJSON_AddStringToObject(o, "preconditioner", sessile_pc_type_name(st->lin_pc));
    cJSON_AddNumberToObject(o, "matrix_chunks", st->lin_chunks);
    cJSON_AddNumberToObject(o, "assembly_seconds", st->assembly_s);
    cJSON_AddNumberToObject(o, "solve_seconds", st->solve_s);
    if (!cJSON_AddItemToArray(steps, o)) cJSON_Delete(o);
  }
}

/* Immersed flow: classify on the fluid box, solve warm, interpolate to the
 * nutrient box (nested grids: P1 interpolation on the fluid box). */
static sessile_status flow_immersed(grow_run *r, sessile_fluid_result *res) {
  uint32_t nf = sessile_box_nodes(&r->fbox), nb = sessile_box_nodes(&r->box);
  uint8_t *solid = malloc(nf);
  SESSILE_CHECK(solid, SESSILE_ERR_NO_MEMORY, "out of host memory for the fluid mask");
  sessile_status s = sessile_growth_gpu_classify(r->growth, &r->fbox, r->fsolid);
  if (s == SESSILE_OK) s = mask_download(r->fsolid, nf, solid);
  /* A solid node gets u = 0 from the warm start on, which also helps Newton. */
  for (uint32_t i = 0; s == SESSILE_OK && i < nf; i++)
    if (solid[i]) r->up[4 * i] = r->up[4 * i + 1] = r->up[4 * i + 2] = 0;
  sessile_fluid_params fp;
  grow_fluid_params(r, &fp);
  if (s == SESSILE_OK) s = sessile_fluid_solve(r->fluid, solid, &fp, r->up, res);
  free(solid);
  SESSILE_CALL(s);
  for (uint32_t i = 0; i < nb; i++) {
    double x[3], w[4];
    uint32_t n[4];
    sessile_box_node_pos(&r->box, i, x);
    sessile_box_locate(&r->fbox, x, n, w);
    for (int a = 0; a < 4; a++) {
      double v = 0;
      for (int q = 0; q < 4; q++) v += w[q] * r->up[4 * n[q] + a];
      if (a < 3) r->ufine[3 * i + a] = v;
      else r->pfine[i] = v;
    }
  }
  r->flow_domain = "immersed";
  return SESSILE_OK;
}

sessile_status grow_flow_solve(grow_run *r, int it, cJSON *rec) {
  SESSILE_CALL(grow_flow_setup(r));
  cJSON *fl = cJSON_AddObjectToObject(rec, "fluid");
  SESSILE_CHECK(fl, SESSILE_ERR_NO_MEMORY, "out of host memory for the manifest's flow record");
  cJSON_AddStringToObject(fl, "why", !r->p->diffusion_limited ? "feeds the advected nutrient"
                                     : r->p->fluid_every_iteration ? "requested every iteration"
                                                                   : "snapshot output only (diffusion limited)");
  sessile_fluid_result res;
  memset(&res, 0, sizeof res);
  int fell_back = 0;
  if (r->p->domain == SESSILE_DOMAIN_CONFORMING) {
    SESSILE_CALL(grow_flow_conforming(r, &res, fl, &fell_back));
    if (fell_back) {
      const char *why = cJSON_GetStringValue(cJSON_GetObjectItem(fl, "fallback"));
      grow_warn(r, "iteration %d: TetGen rejected the sponge surface (%s); this iteration's flow "
                   "uses the immersed domain", it, why ? why : "no reason recorded");
    }
  }
  if (r->p->domain == SESSILE_DOMAIN_IMMERSED || fell_back) SESSILE_CALL(flow_immersed(r, &res));
  cJSON_AddStringToObject(fl, "domain", r->flow_domain);
  record_fluid(fl, &res, !strcmp(r->flow_domain, "immersed") ? sessile_box_nodes(&r->fbox) : r->cmesh.nnodes);
  if (!res.converged)
    grow_warn(r, "iteration %d: Navier-Stokes stopped after %d Newton steps at residual %.2e, %.2e of "
                 "the rest state's (not converged to %g); see records.jsonl",
              it, res.nsteps, res.residual,
              res.residual_rest > 0 ? res.residual / res.residual_rest : 0.0, r->p->fluid_newton_rtol);
  r->flow_valid = 1;
  return SESSILE_OK;
}

sessile_status grow_advected_setup(grow_run *r) {
  uint32_t nb = sessile_box_nodes(&r->box);
  if (!r->ad) {
    /* The arrays first, the solver last: r->ad set means all of it is there. */
    if (!r->nmask) r->nmask = malloc(nb);
    if (!r->nsolid) r->nsolid = malloc(nb);
    if (!r->nval) r->nval = malloc((size_t)nb * sizeof *r->nval);
    if (!r->nc) r->nc = malloc((size_t)nb * sizeof *r->nc);
    SESSILE_CHECK(r->nmask && r->nsolid && r->nval && r->nc, SESSILE_ERR_NO_MEMORY, "out of host memory for the nutrient");
    for (uint32_t i = 0; i < nb; i++) r->nc[i] = 1.0;
    if (!r->nmesh.nnodes) SESSILE_CALL(sessile_tetmesh_from_box(&r->box, &r->nmesh));
    SESSILE_CALL(sessile_advdiff_create(r->la, &r->nmesh, &r->ad));
  }
  return SESSILE_OK;
}

sessile_status grow_nutrient_advected(grow_run *r, sessile_solve_result *res) {
  uint32_t nb = sessile_box_nodes(&r->box);
  SESSILE_CALL(grow_advected_setup(r));
  SESSILE_CALL(mask_download(r->solid, nb, r->nsolid));
  sessile_advdiff_nutrient_bc(&r->nmesh, r->nsolid, r->nmask, r->nval);
  SESSILE_CALL(sessile_advdiff_solve(r->ad, r->ufine, r->p->diffusion_coefficient, r->nmask, r->nval,
                                     NULL, r->nc, res));
  /* The probe reads concentrations: SUPG's small overshoots near layers are
   * clipped (the warm start keeps the unclipped field). */
  double *cl = malloc((size_t)nb * sizeof *cl);
  SESSILE_CHECK(cl, SESSILE_ERR_NO_MEMORY, "out of host memory for the nutrient");
  for (uint32_t i = 0; i < nb; i++) cl[i] = r->nc[i] < 0 ? 0 : r->nc[i] > 1 ? 1 : r->nc[i];
  sessile_status s = sessile_vec_upload(r->c, cl);
  free(cl);
  return s;
}

sessile_status grow_flow_iteration(grow_run *r, int it, cJSON *rec, int snap) {
  /* The flow feeds the nutrient unless diffusion limited; then it is solved
   * only for snapshots (or every iteration on request). */
  int advect = !r->p->diffusion_limited;
  r->flow_valid = 0;
  int snap_flow = !advect && !r->p->fluid_every_iteration;
  if (!(advect || r->p->fluid_every_iteration || (snap && r->o->run && r->p->fluid_at_snapshots)))
    return SESSILE_OK;
  if (snap_flow && snap == 2) SESSILE_CALL(grow_flow_keep(r, &r->saved)); /* put back after the snapshot */
  grow_progress(r, "fluid", 0.3);
  sessile_status fs = grow_flow_solve(r, it, rec);
  if (fs == SESSILE_OK || advect) return fs;
  /* Diffusion limited: the flow is output only, so its failure costs the
   * flow channels of this snapshot, not the run. */
  cJSON *fl = cJSON_GetObjectItem(rec, "fluid");
  if (!fl) fl = cJSON_AddObjectToObject(rec, "fluid");
  cJSON_AddStringToObject(fl, "error", sessile_error_message());
  grow_warn(r, "iteration %d: the flow solve failed (%s); this snapshot has no flow channels", it,
            sessile_error_message());
  r->flow_valid = 0;
  return SESSILE_OK;
}
