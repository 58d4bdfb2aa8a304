/* Contact inhibition in the growth loop (docs/intersection.md): the motion
 * guard between the growth step and the remesh, and the self-intersection
 * check after the remesh, with what they record.  grow.c calls each once. */
#include "grow_internal.h"
#include "sessile/mesh/intersect.h"

/* Halfway first, then back: in the default runs it held back fewer
 * vertices and kept more growth than stepping straight back
 * (docs/intersection.md, "Measured"). */
#define GUARD_HALFWAY 1

sessile_status grow_guard_motion(grow_run *r, int it, double *newpos, cJSON *rec) {
  double t0 = sessile_wall_seconds();
  sessile_guard_stats st;
  sessile_status s = sessile_surface_guard_motion(&r->surf, newpos, GUARD_HALFWAY, &st);
  if (s != SESSILE_OK)
    return sessile_error_set(s, "iteration %d: %s", it, sessile_error_message());
  cJSON *gr = cJSON_GetObjectItem(rec, "growth");
  if (!gr) gr = cJSON_AddObjectToObject(rec, "growth");
  cJSON_AddNumberToObject(gr, "held_back_vertices", st.held_back);
  cJSON_AddNumberToObject(gr, "halfway_vertices", st.halfway);
  cJSON_AddNumberToObject(gr, "growth_kept_cm", st.kept_cm);
  cJSON_AddNumberToObject(gr, "growth_proposed_cm", st.proposed_cm);
  cJSON_AddNumberToObject(gr, "guard_rounds", st.rounds);
  cJSON_AddNumberToObject(gr, "guard_seconds", sessile_wall_seconds() - t0);
  if (st.fallback) {
    grow_warn(r, "iteration %d: the contact guard needed more than %u rounds and held back every "
                 "growing vertex", it, st.rounds);
    cJSON_AddStringToObject(gr, "guard_warning", "round limit: every growing vertex held back");
  }
  return SESSILE_OK;
}

sessile_status grow_guard_check(grow_run *r, int it, const sessile_remesh_stats *rs, cJSON *rec) {
  cJSON *rm = cJSON_GetObjectItem(rec, "remesh");
  if (rm) {
    cJSON_AddNumberToObject(rm, "contact_refusals", rs->contact_refusals);
    cJSON_AddNumberToObject(rm, "chord_splits", rs->chord_splits);
  }
  if (!r->o->check_every_iteration) return SESSILE_OK;
  double t0 = sessile_wall_seconds();
  uint64_t n = 0;
  uint32_t pair[2] = {0, 0};
  SESSILE_CALL(sessile_surface_self_intersections(&r->surf, 1, pair, &n));
  cJSON_AddNumberToObject(rec, "self_intersections", (double)n);
  cJSON_AddNumberToObject(rec, "self_intersection_seconds", sessile_wall_seconds() - t0);
  SESSILE_CHECK(n == 0, SESSILE_ERR_INTERNAL,
                "iteration %d: the remeshed surface intersects itself (%llu triangle pairs, the "
                "first %u and %u) although every growth step and remesh is guarded against it: "
                "a bug; please report it with this run's folder (the checkpoint holds the surface "
                "before this iteration)",
                it, (unsigned long long)n, pair[0], pair[1]);
  return SESSILE_OK;
}
