/* One growth iteration (O'Hagan et al., Figure 2), stage by stage: upload
 * and classify the surface (grow_nutrient.c), the flow when this iteration
 * needs it (grow_flow.c), the nutrient (grow_nutrient.c), uptake,
 * translocation and growth (grow_step.c), the remesh (grow_remesh.c); then
 * the stage timings and surface statistics of its record.  The snapshot and
 * the checkpoint are the run loop's (grow_gen.c). */
#include <stdio.h>
#include "grow_internal.h"

/* Progress for the monitor: the stage, time so far and an estimate of
 * what is left from the iterations this process ran. */
void grow_progress(grow_run *r, int it, const char *stage, int done) {
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

/* The stage timings (t: the stages' boundaries) into the record and the totals. */
static void record_stages(grow_run *r, cJSON *rec, const double *t) {
  cJSON *ts = cJSON_AddObjectToObject(rec, "seconds");
  for (int s = 0; s < SESSILE_STAGE_COUNT; s++) {
    r->sum.stage_seconds[s] += t[s + 1] - t[s];
    cJSON_AddNumberToObject(ts, sessile_grow_stage_name(s), t[s + 1] - t[s]);
  }
  cJSON_AddNumberToObject(ts, "total", t[SESSILE_STAGE_COUNT] - t[0]);
  grow_manifest_surface_stats(cJSON_AddObjectToObject(rec, "surface"), &r->surf);
}

sessile_status grow_iterate(grow_run *r, int it, cJSON *rec, int snap) {
  double t[SESSILE_STAGE_COUNT + 1];
  const sessile_vec *probe_field = NULL;
  grow_progress(r, it, "upload", 0);
  t[0] = sessile_wall_seconds();
  SESSILE_CALL(sessile_growth_gpu_set_surface(r->growth, &r->surf));
  t[1] = sessile_wall_seconds();
  grow_progress(r, it, "classify", 0);
  SESSILE_CALL(grow_classify(r));
  t[2] = sessile_wall_seconds();
  SESSILE_CALL(grow_flow_iteration(r, it, rec, snap));
  t[3] = sessile_wall_seconds();
  grow_progress(r, it, "nutrient", 0);
  SESSILE_CALL(grow_nutrient_solve(r, it, rec, &probe_field));
  t[4] = sessile_wall_seconds();
  grow_progress(r, it, "growth", 0);
  SESSILE_CALL(grow_growth_step(r, it, rec, probe_field));
  t[5] = sessile_wall_seconds();
  grow_progress(r, it, "remesh", 0);
  SESSILE_CALL(grow_remesh(r, it, rec));
  t[6] = sessile_wall_seconds();
  /* the output stage: the normals a snapshot writes (the snapshot's own
   * time is added when it is written) */
  SESSILE_CALL(grow_normals(r));
  t[7] = sessile_wall_seconds();
  record_stages(r, rec, t);
  r->sum.iterations = it;
  grow_progress(r, it, "done", 1);
  return SESSILE_OK;
}
