/* Helpers shared by the surface files (not public). */
#ifndef SESSILE_MESH_INTERNAL_H
#define SESSILE_MESH_INTERNAL_H
#include <stddef.h>
#include <stdint.h>

/* (b - a) x (c - a) of triangle t = (a, b, c); |result| = 2 area.  One formula
 * everywhere, so normals computed by different files agree bit for bit. */
static inline void mesh_face_cross(const double *pos, const uint32_t *t, double c[3]) {
  const double *a = pos + 3 * t[0], *b = pos + 3 * t[1], *d = pos + 3 * t[2];
  double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double v[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  c[0] = u[1] * v[2] - u[2] * v[1];
  c[1] = u[2] * v[0] - u[0] * v[2];
  c[2] = u[0] * v[1] - u[1] * v[0];
}

/* Ascending LSD radix sort of n 64-bit keys; tmp has room for n keys. */
void mesh_sort_u64(uint64_t *keys, uint64_t *tmp, size_t n);



/* --- remesh phases (remesh.c drives them) --------------------------------- */
#include "sessile/surface.h"

/* The position of a vertex inserted on edge (a, b), or of the two fused: the
 * curve midpoint, clamped into the box; an edge whose ends lie on the same
 * box face keeps its point on that face.  Pass the end with
 * the lower index first so the result does not depend on the edge's direction. */
void remesh_edge_point(const double *pa, const double *na, const double *pb, const double *nb,
                       const sessile_remesh_options *o, double out[3]);
/* Splits until no edge is longer than insert_len.  *normals (3 cap_v doubles)
 * grows with the vertices; inserted vertices get the normalised mean of their
 * ends' normals. */
sessile_status remesh_split(sessile_surface *s, double **normals, const sessile_remesh_options *o,
                            uint32_t *splits);
/* Guarded fusions and area collapses to a fixed point, then compaction. */
sessile_status remesh_collapse(sessile_surface *s, const sessile_remesh_options *o,
                               sessile_remesh_stats *st);
#endif
