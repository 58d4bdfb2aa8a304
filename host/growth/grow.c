/* The growth loop (O'Hagan et al., Figure 2): per iteration classify the box
 * nodes inside the sponge, solve the nutrient field (warm-started), run the
 * growth kernels (normals, probe, translocate, grow), remesh on the host. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "grow_internal.h"
#include "sessile/growth_ref.h"
#include "sessile/rng.h"

const char *sessile_grow_stage_name(int stage) {
  static const char *names[] = {
#define X(n) #n,
      SESSILE_GROW_STAGES(X)
#undef X
  };
  return stage >= 0 && stage < SESSILE_STAGE_COUNT ? names[stage] : "?";
}

void sessile_grow_options_default(sessile_grow_options *o) {
  memset(o, 0, sizeof *o);
  o->preset = "radiate";
  o->iterations = 50;
  o->seed = 1;
  o->every = 10;
  o->slices = "x,y,z";
  o->fields = 1;
  o->check_every_iteration = 1;
  o->monitor = NULL;
}

/* Uniform in [-1, 1] from the top 53 bits. */
static double uniform_pm1(uint64_t *state) {
  return (double)(sessile_rng_next(state) >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

static sessile_status setup(grow_run *r) {
  const sessile_params *p = r->p;
  const double origin[3] = {0, 0, 0};
  const uint32_t cells[3] = {(uint32_t)p->box_cells_x, (uint32_t)p->box_cells_y,
                             (uint32_t)p->box_cells_z};
  SESSILE_CALL(sessile_box_make(origin, p->box_base_cell, cells, p->box_resolution, &r->box));
  double mx[3];
  sessile_box_max(&r->box, mx);
  /* The sponge sits on the substratum (its lowest point touches z = 0) at the
   * chosen x/y, shifted by the seeded jitter (§4.7); the shift is clamped so
   * the sponge stays one cell inside the side walls. */
  uint64_t st = r->o->seed ^ 0x5EED5EED5EED5EEDull;
  double jx = p->position_jitter * uniform_pm1(&st), jy = p->position_jitter * uniform_pm1(&st);
  r->center[0] = (p->sponge_x < 0 ? mx[0] / 2 : p->sponge_x) + jx;
  r->center[1] = (p->sponge_y < 0 ? mx[1] / 2 : p->sponge_y) + jy;
  r->center[2] = p->sponge_z;
  for (int a = 0; a < 2; a++) {
    double lo = p->sponge_radius + r->box.h, hi = mx[a] - p->sponge_radius - r->box.h;
    if (r->center[a] < lo) r->center[a] = lo;
    if (r->center[a] > hi) r->center[a] = hi;
  }
  if (r->o->initial) SESSILE_CALL(sessile_surface_copy(r->o->initial, &r->surf));
  else SESSILE_CALL(sessile_surface_icosphere(p->sponge_resolution, p->sponge_radius, r->center, &r->surf));
  /* A sponge grows attached to the rock: the part of the sphere below the
   * substratum is projected onto it (a flat base; its triangles keep their
   * downward orientation, so the surface stays closed and consistent). */
  for (uint32_t v = 0; v < r->surf.nv; v++)
    if (r->surf.pos[3 * v + 2] < r->box.origin[2]) r->surf.pos[3 * v + 2] = r->box.origin[2];
  SESSILE_CALL(sessile_la_create(r->gpu, &r->la));
  sessile_cut_bc bc;
  sessile_cut_bc_default(&bc);
  bc.far_field = p->far_field == SESSILE_FAR_WALLS ? SESSILE_FAR_FIELD_WALLS : SESSILE_FAR_FIELD_HEIGHT;
  bc.height = sessile_params_far_field_height(p);
  SESSILE_CALL(sessile_cut_nutrient_create(r->la, &r->box, &bc,
                                           p->nutrient_solver == SESSILE_SOLVER_MG ? 12 : 1,
                                           &r->nutrient));
  SESSILE_CALL(sessile_growth_gpu_create(r->la, &r->growth));
  uint32_t nodes = sessile_box_nodes(&r->box);
  sessile_cut_nutrient_level(r->nutrient, 0, NULL, &r->solid, NULL);
  SESSILE_CALL(sessile_vec_create(r->la, nodes, &r->c));
  /* Start from c = 1 (the far field); the first solve fixes the rest. */
  SESSILE_CALL(sessile_vec_fill(r->la, 1.0, r->c));
  r->sum.box_nodes = nodes;
  return SESSILE_OK;
}

static void teardown(grow_run *r) {
  grow_flow_teardown(r);
  sessile_vec_destroy(r->c);
  sessile_growth_gpu_destroy(r->growth);
  sessile_cut_nutrient_destroy(r->nutrient);
  sessile_la_destroy(r->la);
  sessile_surface_free(&r->surf);
  for (int i = 0; i < r->nvtu; i++) free(r->vtu_files[i]);
  free(r->vtu_files);
  free(r->vtu_steps);
}

/* Progress for the monitor: the stage, time so far and an estimate of
 * what is left from the iterations this process ran. */
static void progress(grow_run *r, int it, const char *stage, int done) {
  if (!r->o->monitor) return;
  double el = sessile_wall_seconds() - r->t_start;
  int ran = it - r->first_it + (done ? 1 : 0);
  double left = ran > 0 ? el / ran * (r->o->iterations - (done ? it : it - 1)) : 0;
  if (done)
    grow_monitor(r, SESSILE_MONITOR_ITERATION,
                 "iteration %d/%d: %u vertices, %u triangles, %.1f s elapsed, ~%.0f s left", it,
                 r->o->iterations, r->surf.nv, r->surf.nf, el, left);
  else
    grow_monitor(r, SESSILE_MONITOR_STATUS, "[%d/%d] %-9s %4.0f s elapsed, ~%.0f s left", it,
                 r->o->iterations, stage, el, left);
}

static sessile_status iterate(grow_run *r, int it, cJSON *rec, grow_flow_saved *saved,
                              const sessile_growth_params *gp, double **normals, double **newpos) {
  double t[SESSILE_STAGE_COUNT + 1];
  int nv = (int)r->surf.nv;

  progress(r, it, "upload", 0);
  t[0] = sessile_wall_seconds();
  SESSILE_CALL(sessile_growth_gpu_set_surface(r->growth, &r->surf));
  t[1] = sessile_wall_seconds();
  progress(r, it, "classify", 0);
  /* The solid mask and the cut fractions on every box level (the nutrient's
   * multigrid rediscretises the cut cells on each). */
  for (int l = 0; l < sessile_cut_nutrient_levels(r->nutrient); l++) {
    sessile_box lb;
    sessile_buffer *solid, *theta;
    sessile_cut_nutrient_level(r->nutrient, l, &lb, &solid, &theta);
    SESSILE_CALL(sessile_growth_gpu_cut(r->growth, &lb, solid, theta));
  }
  t[2] = sessile_wall_seconds();

  /* The flow feeds the nutrient unless diffusion limited; then it is solved
   * only for snapshots (or every iteration on request). */
  /* Snapshots every K iterations, and the last iteration always is one. */
  int snap = (r->o->every > 0 && it % r->o->every == 0) || it == r->o->iterations;
  int advect = !r->p->diffusion_limited;
  r->flow_valid = 0;
  int snap_flow = !advect && !r->p->fluid_every_iteration;
  int final_only = snap && !(r->o->every > 0 && it % r->o->every == 0);
  if (advect || r->p->fluid_every_iteration || (snap && r->o->run && r->p->fluid_at_snapshots)) {
    if (snap_flow && final_only) SESSILE_CALL(grow_flow_keep(r, saved));
    progress(r, it, "fluid", 0);
    sessile_status fs = grow_flow_solve(r, it, rec);
    if (fs != SESSILE_OK && advect) return fs;
    if (fs != SESSILE_OK) {
      /* Diffusion limited: the flow is output only, so its failure costs the
       * flow channels of this snapshot, not the run. */
      cJSON *fl = cJSON_GetObjectItem(rec, "fluid");
      if (!fl) fl = cJSON_AddObjectToObject(rec, "fluid");
      cJSON_AddStringToObject(fl, "error", sessile_error_message());
      grow_warn(r, "iteration %d: the flow solve failed (%s); this snapshot has no flow channels", it,
                sessile_error_message());
      r->flow_valid = 0;
    }
  }
  t[3] = sessile_wall_seconds();

  progress(r, it, "nutrient", 0);
  sessile_ksp_options ko;
  sessile_ksp_options_default(&ko);
  ko.type = SESSILE_KSP_CG;
  ko.pc = SESSILE_PC_JACOBI;
  ko.rtol = r->p->linear_rtol;
  ko.max_it = r->p->linear_max_iterations;
  sessile_solve_result res;
  sessile_cut_solver solver =
      r->p->nutrient_solver == SESSILE_SOLVER_MG ? SESSILE_CUT_SOLVER_MG : SESSILE_CUT_SOLVER_JACOBI;
  if (advect) SESSILE_CALL(grow_nutrient_advected(r, &res));
  else SESSILE_CALL(sessile_cut_nutrient_solve(r->nutrient, solver, r->c, &ko, &res));
  /* The flux probe reads the field extended across the surface. */
  if (advect && r->p->probe == SESSILE_PROBE_FLUX) SESSILE_CALL(sessile_cut_nutrient_extend(r->nutrient, r->c));
  const sessile_vec *probe_field =
      r->p->probe == SESSILE_PROBE_FLUX ? sessile_cut_nutrient_extended(r->nutrient) : r->c;
  t[4] = sessile_wall_seconds();
  cJSON *ns = cJSON_AddObjectToObject(rec, "nutrient_solve");
  cJSON_AddStringToObject(ns, "equation", advect ? "advection-diffusion (SUPG), u from the flow"
                                                 : "Laplace (diffusion limited), cut-cell boundary");
  cJSON_AddStringToObject(ns, "solver", advect ? "bicgstab+jacobi"
                                        : solver == SESSILE_CUT_SOLVER_MG ? "pcg+multigrid" : "pcg+jacobi");
  cJSON_AddNumberToObject(ns, "iterations", res.iterations);
  cJSON_AddNumberToObject(ns, "true_relres", res.true_relres);
  cJSON_AddStringToObject(ns, "status", sessile_solve_status_name(res.status));
  cJSON_AddStringToObject(ns, "reason", res.reason);
  cJSON_AddNumberToObject(ns, "seconds", res.seconds);
  r->sum.solver_iterations += res.iterations;
  if (res.true_relres > r->sum.worst_relres) r->sum.worst_relres = res.true_relres;
  SESSILE_CHECK(res.status != SESSILE_SOLVE_BREAKDOWN, SESSILE_ERR_NUMERIC,
                "iteration %d: the nutrient solve broke down (%s); the run stops here, its "
                "files so far are whole", it, res.reason);
  if (res.status != SESSILE_SOLVE_CONVERGED)
    grow_warn(r, "iteration %d: nutrient solve stopped at %d iterations with true relative residual "
                 "%.2e (%s); raise linear_max_iterations", it, res.iterations, res.true_relres, res.reason);

  progress(r, it, "growth", 0);
  double *np = realloc(*newpos, (size_t)nv * 3 * sizeof *np);
  SESSILE_CHECK(np, SESSILE_ERR_NO_MEMORY, "out of host memory for %d vertices", nv);
  *newpos = np;
  double *pv = malloc((size_t)nv * 3 * sizeof *pv);
  SESSILE_CHECK(pv, SESSILE_ERR_NO_MEMORY, "out of host memory for %d vertices", nv);
  sessile_status gs = sessile_growth_gpu_step(r->growth, &r->box, probe_field, gp, r->o->seed, (uint32_t)it,
                                              np, pv, pv + nv, pv + 2 * nv);
  if (gs == SESSILE_OK) {
    /* Per-vertex summaries: what the surface saw and how much it grew. */
    const char *names[3] = {"probed_nutrient", "translocated_nutrient", "growth_length_cm"};
    cJSON *gr = cJSON_AddObjectToObject(rec, "growth");
    for (int a = 0; a < 3; a++) {
      double lo = INFINITY, hi = -INFINITY, sum = 0;
      for (int v = 0; v < nv; v++) {
        double x = pv[a * nv + v];
        lo = x < lo ? x : lo, hi = x > hi ? x : hi, sum += x;
      }
      cJSON *st = cJSON_AddObjectToObject(gr, names[a]);
      cJSON_AddNumberToObject(st, "min", nv ? lo : 0);
      cJSON_AddNumberToObject(st, "mean", nv ? sum / nv : 0);
      cJSON_AddNumberToObject(st, "max", nv ? hi : 0);
    }
    int growing = 0;
    for (int v = 0; v < nv; v++) growing += pv[2 * nv + v] > 0;
    cJSON_AddNumberToObject(gr, "growing_vertices", growing);
  }
  free(pv);
  SESSILE_CALL(gs);
  SESSILE_CALL(grow_guard_motion(r, it, np, rec)); /* contact inhibition: grow_guard.c */
  memcpy(r->surf.pos, np, (size_t)nv * 3 * sizeof *np);
  t[5] = sessile_wall_seconds();

  progress(r, it, "remesh", 0);
  double *nn = realloc(*normals, (size_t)r->surf.nv * 3 * sizeof *nn);
  SESSILE_CHECK(nn, SESSILE_ERR_NO_MEMORY, "out of host memory for %u normals", r->surf.nv);
  *normals = nn;
  sessile_surface_normals(&r->surf, nn);
  sessile_remesh_options ro;
  sessile_remesh_options_default(&ro);
  ro.insert_len = r->p->vertex_insertion_threshold;
  ro.fuse_len = r->p->vertex_fusion_threshold;
  ro.min_area = r->p->triangle_area_deletion_threshold;
  /* Vertices clamped onto a box face stay on it through remeshing. */
  memcpy(ro.clamp_lo, r->box.origin, sizeof ro.clamp_lo);
  sessile_box_max(&r->box, ro.clamp_hi);
  sessile_remesh_stats rs;
  SESSILE_CALL(sessile_remesh(&r->surf, nn, &ro, &rs));
  if (r->o->check_every_iteration) {
    sessile_status cs = sessile_surface_check(&r->surf, 2, 0.0);
    if (cs != SESSILE_OK)
      return sessile_error_set(SESSILE_ERR_INTERNAL, "iteration %d: the remeshed surface is broken (%s)",
                               it, sessile_error_message());
  }
  if (r->o->check_every_iteration) cJSON_AddStringToObject(rec, "surface_check", "passed");
  /* A sponge fused down to a few vertices (e.g. a radius below the fusion
   * threshold) is no model of anything: say so once. */
  if (r->surf.nv < 20 && !r->warned_degenerate) {
    r->warned_degenerate = 1;
    grow_warn(r, "iteration %d: the sponge has degenerated to %u vertices (remeshing fuses edges "
                 "shorter than vertex_fusion_threshold = %g cm); the result is not meaningful: "
                 "raise sponge_radius or lower the remeshing thresholds",
              it, r->surf.nv, r->p->vertex_fusion_threshold);
    cJSON_AddStringToObject(rec, "warning", "degenerate surface");
  }
  cJSON *rm = cJSON_AddObjectToObject(rec, "remesh");
  cJSON_AddNumberToObject(rm, "splits", rs.splits);
  cJSON_AddNumberToObject(rm, "fusions", rs.fusions);
  cJSON_AddNumberToObject(rm, "area_collapses", rs.area_collapses);
  cJSON_AddNumberToObject(rm, "rejected_collapses", rs.rejected);
  SESSILE_CALL(grow_guard_check(r, it, &rs, rec)); /* no self-intersection: grow_guard.c */
  t[6] = sessile_wall_seconds();

  progress(r, it, "output", 0);
  nn = realloc(*normals, (size_t)r->surf.nv * 3 * sizeof *nn);
  SESSILE_CHECK(nn, SESSILE_ERR_NO_MEMORY, "out of host memory for %u normals", r->surf.nv);
  *normals = nn;
  sessile_surface_normals(&r->surf, nn);
  if (r->o->run && snap) SESSILE_CALL(grow_write_snapshot(r, it, nn));
  grow_flow_putback(r, saved);
  t[7] = sessile_wall_seconds();

  cJSON *ts = cJSON_AddObjectToObject(rec, "seconds");
  for (int s = 0; s < SESSILE_STAGE_COUNT; s++) {
    r->sum.stage_seconds[s] += t[s + 1] - t[s];
    cJSON_AddNumberToObject(ts, sessile_grow_stage_name(s), t[s + 1] - t[s]);
  }
  cJSON_AddNumberToObject(ts, "total", t[SESSILE_STAGE_COUNT] - t[0]);
  grow_manifest_surface_stats(cJSON_AddObjectToObject(rec, "surface"), &r->surf);
  r->sum.iterations = it;
  if (r->o->run) {
    SESSILE_CALL(sessile_run_record(r->o->run, rec));
    /* A checkpoint at every snapshot, and when asked to stop (the state
     * after this whole iteration). */
    if (snap || sessile_run_stop_requested(r->o->run)) SESSILE_CALL(grow_checkpoint_save(r, it));
  }
  progress(r, it, "done", 1);
  return SESSILE_OK;
}

/* Restores a checkpoint when the run has one; sets r->first_it. */
static sessile_status resume(grow_run *r) {
  r->first_it = 1;
  const sessile_ckpt *ck = r->o->run ? sessile_run_checkpoint_loaded(r->o->run) : NULL;
  if (!ck) return SESSILE_OK;
  int k = sessile_ckpt_iteration(ck);
  SESSILE_CHECK(k <= r->o->iterations, SESSILE_ERR_USAGE,
                "the run's checkpoint is at iteration %d: --iterations must be at least %d", k, k);
  SESSILE_CALL(grow_checkpoint_restore(r, ck));
  r->first_it = k + 1;
  /* The old last iteration was a snapshot only because it was the last: a
   * run that goes past it never had one there. */
  if (k < r->o->iterations && (r->o->every == 0 || k % r->o->every != 0))
    SESSILE_CALL(grow_forget_snapshot(r, k));
  return SESSILE_OK;
}

/* Refuses a box the device cannot hold, with the estimate. */
sessile_status sessile_grow_check_device(const sessile_gpu *g, const sessile_params *p) {
  const sessile_gpu_info *gi = sessile_gpu_info_of(g);
  double need = sessile_params_device_bytes(p);
  if (gi->precision == 32) need *= 0.5;
  SESSILE_CHECK(gi->device_local_bytes == 0 || need < (double)gi->device_local_bytes, SESSILE_ERR_USAGE,
                "the run needs about %.2f GiB of device memory but %s has %.2f GiB; lower "
                "box_resolution, fluid_resolution or the box size",
                need / 1073741824.0, gi->name, (double)gi->device_local_bytes / 1073741824.0);
  return SESSILE_OK;
}

/* One iteration with its record (appended to the run, then freed). */
static sessile_status iterate_recorded(grow_run *r, int it, const sessile_growth_params *gp,
                                       double **normals, double **newpos) {
  cJSON *rec = grow_manifest_iteration(r, it);
  SESSILE_CHECK(rec, SESSILE_ERR_NO_MEMORY, "out of host memory for iteration %d's record", it);
  grow_flow_saved saved;
  memset(&saved, 0, sizeof saved);
  sessile_status s = iterate(r, it, rec, &saved, gp, normals, newpos);
  grow_flow_saved_free(&saved);
  cJSON_Delete(rec);
  return s;
}

sessile_status sessile_grow_run(sessile_gpu *g, const sessile_params *p,
                                const sessile_grow_options *o, sessile_surface *final,
                                sessile_grow_summary *summary) {
  SESSILE_CALL(sessile_params_validate(p));
  SESSILE_CHECK(o->iterations >= 0, SESSILE_ERR_USAGE, "iterations must be >= 0");
  grow_run r;
  memset(&r, 0, sizeof r);
  r.p = p;
  r.o = o;
  r.gpu = g;
  r.t_start = sessile_wall_seconds();
  double *normals = NULL, *newpos = NULL;
  sessile_status s = sessile_grow_check_device(g, p);
  if (s == SESSILE_OK) s = setup(&r);
  if (s == SESSILE_OK) s = grow_parse_planes(&r);
  if (s == SESSILE_OK && o->run) s = grow_manifest_begin(&r);
  if (s == SESSILE_OK) s = resume(&r);
  sessile_growth_params gp;
  sessile_growth_params_from(p, &gp);
  for (int it = r.first_it; s == SESSILE_OK && it <= o->iterations; it++) {
    s = iterate_recorded(&r, it, &gp, &normals, &newpos);
    if (s == SESSILE_OK && o->run && sessile_run_stop_requested(o->run) && it < o->iterations)
      s = sessile_error_set(SESSILE_ERR_INTERRUPTED,
                            "stopped by signal %d after iteration %d of %d; continue with 'sessile "
                            "grow --resume DIR'", sessile_run_stop_requested(o->run), it, o->iterations);
  }
  if (s == SESSILE_OK && o->run) {
    double *nn = realloc(normals, (size_t)(r.surf.nv ? r.surf.nv : 1) * 3 * sizeof *normals);
    if (!nn) s = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory");
    else {
      normals = nn;
      sessile_surface_normals(&r.surf, normals);
      s = grow_write_final(&r, normals);
    }
  }
  r.sum.total_seconds = sessile_wall_seconds() - r.t_start;
  r.sum.final_vertices = r.surf.nv;
  r.sum.final_triangles = r.surf.nf;
  if (o->run && r.first_it > 0) {
    /* The totals so far, even when the run failed (keep the first error). */
    char msg[1024];
    snprintf(msg, sizeof msg, "%s", s == SESSILE_OK ? "" : sessile_error_message());
    sessile_status ms = grow_manifest_totals(&r);
    if (s == SESSILE_OK) s = ms;
    else sessile_error_set(s, "%s", msg);
  }
  if (s == SESSILE_OK && final) s = sessile_surface_copy(&r.surf, final);
  if (summary) *summary = r.sum;
  free(normals);
  free(newpos);
  teardown(&r);
  return s;
}
