/* One growth iteration (O'Hagan et al., Figure 2), stage by stage: upload
 * and classify the surface (grow_nutrient.c), the flow when this iteration
 * needs it (grow_flow.c), the nutrient (grow_nutrient.c), uptake,
 * translocation and growth (grow_step.c), the remesh (grow_remesh.c); then
 * the stage timings and surface statistics of its record.  The snapshot and
 * the checkpoint are the run loop's (grow_gen.c). */
#include <stdio.h>
#include "grow_internal.h"

/* Where the iteration stands for the run loop's progress: the stage and
 * the part of the iteration before it (the stages' order; time left is
 * the loop's estimate from measured iterations). */
void grow_progress(grow_run *r, const char *stage, double part) { sessile_gen_progress(r->su, stage, part, NULL); }

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
  grow_progress(r, "upload", 0);
  t[0] = sessile_wall_seconds();
  SESSILE_CALL(sessile_growth_gpu_set_surface(r->growth, &r->surf));
  t[1] = sessile_wall_seconds();
  grow_progress(r, "classify", 0.15);
  SESSILE_CALL(grow_classify(r));
  t[2] = sessile_wall_seconds();
  SESSILE_CALL(grow_flow_iteration(r, it, rec, snap));
  t[3] = sessile_wall_seconds();
  grow_progress(r, "nutrient", 0.5);
  SESSILE_CALL(grow_nutrient_solve(r, it, rec, &probe_field));
  t[4] = sessile_wall_seconds();
  grow_progress(r, "growth", 0.7);
  SESSILE_CALL(grow_growth_step(r, it, rec, probe_field));
  t[5] = sessile_wall_seconds();
  grow_progress(r, "remesh", 0.8);
  SESSILE_CALL(grow_remesh(r, it, rec));
  t[6] = sessile_wall_seconds();
  /* the output stage: the normals a snapshot writes (the snapshot's own
   * time is added when it is written) */
  SESSILE_CALL(grow_normals(r));
  t[7] = sessile_wall_seconds();
  record_stages(r, rec, t);
  r->sum.iterations = it;
  char done[96];
  snprintf(done, sizeof done, "%u vertices, %u triangles", r->surf.nv, r->surf.nf);
  sessile_gen_progress(r->su, NULL, 1, done);
  return SESSILE_OK;
}
