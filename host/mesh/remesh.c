/* Remeshing the sponge surface (O'Hagan et al. §4.6; thresholds from Table 1):
 * the driver, the options and the curve point of a new vertex.  Phase 1
 * (remesh_split.c) inserts vertices until no edge is longer than insert_len;
 * phase 2 (remesh_collapse.c) fuses short edges and deletes small triangles
 * under guards that never make an edge longer than insert_len.  Why this
 * reading of the thresholds cannot oscillate: docs/remesh.md. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "mesh/mesh_internal.h"

void sessile_remesh_options_default(sessile_remesh_options *o) {
  memset(o, 0, sizeof *o);
  o->insert_len = 0.6;
  o->fuse_len = 0.5;
  o->min_area = 0.1;
  o->max_passes = 8;
  o->max_turn_deg = 60.0;
  for (int a = 0; a < 3; a++) o->clamp_lo[a] = -INFINITY, o->clamp_hi[a] = INFINITY;
  o->guard_intersections = 1;
}

void sessile_surface_curve_midpoint(const double p0[3], const double n0[3], const double p1[3],
                                    const double n1[3], double out[3]) {
  /* Bezier control points p0 + t0/3, p1 - t1/3 (ti = d - (d.ni) ni); the
   * midpoint (p0 + 3 b1 + 3 b2 + p1)/8 simplifies to the line below. */
  double d[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  double w0 = d[0] * n0[0] + d[1] * n0[1] + d[2] * n0[2];
  double w1 = d[0] * n1[0] + d[1] * n1[1] + d[2] * n1[2];
  for (int a = 0; a < 3; a++) out[a] = 0.5 * (p0[a] + p1[a]) + 0.125 * (w1 * n1[a] - w0 * n0[a]);
}

void remesh_edge_point(const double *pa, const double *na, const double *pb, const double *nb,
                       const sessile_remesh_options *o, double out[3]) {
  sessile_surface_curve_midpoint(pa, na, pb, nb, out);
  for (int a = 0; a < 3; a++) {
    /* Both ends on the same box face: the point stays on that face (the
     * tilted normals near a crease would lift it off). */
    if (pa[a] == pb[a] && (pa[a] == o->clamp_lo[a] || pa[a] == o->clamp_hi[a])) out[a] = pa[a];
    if (out[a] < o->clamp_lo[a]) out[a] = o->clamp_lo[a];
    if (out[a] > o->clamp_hi[a]) out[a] = o->clamp_hi[a];
  }
}

sessile_status sessile_remesh(sessile_surface *s, const double *normals,
                              const sessile_remesh_options *opt, sessile_remesh_stats *st) {
  sessile_remesh_options def;
  if (!opt) sessile_remesh_options_default(&def), opt = &def;
  sessile_remesh_stats dummy;
  if (!st) st = &dummy;
  memset(st, 0, sizeof *st);
  SESSILE_CHECK(isfinite(opt->insert_len) && opt->insert_len > 0 && opt->fuse_len >= 0 &&
                    opt->min_area >= 0 && opt->max_passes >= 0 && opt->max_turn_deg > 0 &&
                    opt->max_turn_deg <= 180,
                SESSILE_ERR_USAGE,
                "remesh: bad thresholds (insert_len %g, fuse_len %g, min_area %g, max_passes %d, "
                "max_turn_deg %g); need insert_len > 0, the others >= 0, 0 < turn <= 180",
                opt->insert_len, opt->fuse_len, opt->min_area, opt->max_passes, opt->max_turn_deg);
  for (int a = 0; a < 3; a++)
    SESSILE_CHECK(!(opt->clamp_lo[a] > opt->clamp_hi[a]), SESSILE_ERR_USAGE,
                  "remesh: clamp box is empty on axis %d (%g > %g)", a, opt->clamp_lo[a],
                  opt->clamp_hi[a]);
  if (!s->nf) return SESSILE_OK;
  for (size_t i = 0; i < (size_t)s->nv * 3; i++)
    SESSILE_CHECK(isfinite(s->pos[i]), SESSILE_ERR_NUMERIC,
                  "remesh: vertex %zu has a non-finite coordinate", i / 3);
  for (size_t k = 0; k < (size_t)s->nf * 3; k++)
    SESSILE_CHECK(s->tri[k] < s->nv, SESSILE_ERR_INTERNAL,
                  "remesh: triangle %zu refers to vertex %u of %u", k / 3, s->tri[k], s->nv);
  double *n = malloc((size_t)(s->cap_v ? s->cap_v : 1) * 3 * sizeof *n);
  SESSILE_CHECK(n, SESSILE_ERR_NO_MEMORY, "out of host memory for %u normals", s->nv);
  if (normals) memcpy(n, normals, (size_t)s->nv * 3 * sizeof *n);
  else sessile_surface_normals(s, n);
  sessile_status r = remesh_split(s, &n, opt, &st->splits, &st->chord_splits);
  free(n);
  SESSILE_CALL(r);
  return remesh_collapse(s, opt, st);
}
