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

/* The sorts (mesh_sort_u64, mesh_order3 ...) are public: sds uses them. */
#include "sessile/mesh/mesh_sort.h"



/* --- remesh phases (remesh.c drives them) --------------------------------- */
#include "sessile/mesh/surface.h"

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
                            uint32_t *splits, uint32_t *chord_splits);
/* Phase 2's contact guard (remesh_contact.c). */
typedef struct remesh_contact {
  struct sessile_tri_grid *grid;
  uint32_t *cv, *ex;          /* scratch: the fan's vertex ids, the excluded triangles */
  double *cp;                 /* scratch: the fan's corners */
  double changed[6];          /* box of the last tested fan, before and after */
  double *rbox;               /* per refusal: the box of the fan it would have made */
  uint32_t *rv;               /* per refusal: the edge's ends */
  uint32_t nrec, cvcap, excap, cpcap, rboxcap, rvcap;
  uint32_t refusals;
  int failed;                 /* out of host memory: the caller reports it */
} remesh_contact;
sessile_status remesh_contact_begin(remesh_contact *k, const sessile_surface *s);
void remesh_contact_end(remesh_contact *k);
/* 1 when collapsing edge (lo, hi) into lo at p would make a triangle cross
 * the surface (or k->failed); fa, fb: the live triangles of lo and hi, sh
 * the edge's two.  A refusal is recorded for remesh_contact_commit. */
int remesh_contact_blocks(remesh_contact *k, const sessile_surface *s, const uint8_t *falive,
                          uint32_t lo, uint32_t hi, const double p[3], const uint32_t *fa,
                          uint32_t na, const uint32_t *fb, uint32_t nb, const uint32_t sh[2]);
/* After the collapse last tested was committed: its fan (lo's live
 * triangles) goes into the grid, and refused candidates whose fan box meets
 * the changed region are marked in ndirty. */
void remesh_contact_commit(remesh_contact *k, const sessile_surface *s, const uint32_t *fan,
                           uint32_t n, uint8_t *ndirty);
/* Guarded fusions and area collapses to a fixed point, then compaction. */
sessile_status remesh_collapse(sessile_surface *s, const sessile_remesh_options *o,
                               sessile_remesh_stats *st);
#endif
