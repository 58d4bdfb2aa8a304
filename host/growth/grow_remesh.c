/* The remesh of one growth iteration: split long edges, fuse short ones,
 * collapse tiny triangles (thresholds from Table 1), then the checks that
 * the surface is still whole and free of self-intersection.  Records under
 * "remesh". */
#include <string.h>
#include "grow_internal.h"

/* A sponge fused down to a few vertices (e.g. a radius below the fusion
 * threshold) is no model of anything: say so once. */
static void warn_degenerate(grow_run *r, int it, cJSON *rec) {
  if (r->surf.nv >= 20 || r->warned_degenerate) return;
  r->warned_degenerate = 1;
  grow_warn(r, "iteration %d: the sponge has degenerated to %u vertices (remeshing fuses edges "
               "shorter than vertex_fusion_threshold = %g cm); the result is not meaningful: "
               "raise sponge_radius or lower the remeshing thresholds",
            it, r->surf.nv, r->p->vertex_fusion_threshold);
  cJSON_AddStringToObject(rec, "warning", "degenerate surface");
}

sessile_status grow_remesh(grow_run *r, int it, cJSON *rec) {
  SESSILE_CALL(grow_normals(r));
  sessile_remesh_options ro;
  sessile_remesh_options_default(&ro);
  ro.insert_len = r->p->vertex_insertion_threshold;
  ro.fuse_len = r->p->vertex_fusion_threshold;
  ro.min_area = r->p->triangle_area_deletion_threshold;
  /* Vertices clamped onto a box face stay on it through remeshing. */
  memcpy(ro.clamp_lo, r->box.origin, sizeof ro.clamp_lo);
  sessile_box_max(&r->box, ro.clamp_hi);
  sessile_remesh_stats rs;
  SESSILE_CALL(sessile_remesh(&r->surf, r->normals, &ro, &rs));
  if (r->o->check_every_iteration) {
    sessile_status cs = sessile_surface_check(&r->surf, 2, 0.0);
    if (cs != SESSILE_OK)
      return sessile_error_set(SESSILE_ERR_INTERNAL, "iteration %d: the remeshed surface is broken (%s)",
                               it, sessile_error_message());
    cJSON_AddStringToObject(rec, "surface_check", "passed");
  }
  warn_degenerate(r, it, rec);
  cJSON *rm = cJSON_AddObjectToObject(rec, "remesh");
  cJSON_AddNumberToObject(rm, "splits", rs.splits);
  cJSON_AddNumberToObject(rm, "fusions", rs.fusions);
  cJSON_AddNumberToObject(rm, "area_collapses", rs.area_collapses);
  cJSON_AddNumberToObject(rm, "rejected_collapses", rs.rejected);
  return grow_guard_check(r, it, &rs, rec); /* no self-intersection: grow_guard.c */
}
