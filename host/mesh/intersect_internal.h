/* Shared by the intersection files (not public): the triangle pair test, the
 * bounding-volume hierarchy, pair lists and the guard's core. */
#ifndef SESSILE_INTERSECT_INTERNAL_H
#define SESSILE_INTERSECT_INTERNAL_H
#include <stddef.h>
#include <stdint.h>
#include "sessile/mesh/intersect.h"

/* Bounding box of triangle t (ids into pos): lo[3], hi[3] into box[6]. */
static inline void isect_tri_box(const double *pos, const uint32_t *t, double box[6]) {
  for (int k = 0; k < 3; k++) {
    double a = pos[3 * t[0] + k], b = pos[3 * t[1] + k], c = pos[3 * t[2] + k];
    double lo = a < b ? a : b, hi = a < b ? b : a;
    box[k] = c < lo ? c : lo;
    box[3 + k] = c > hi ? c : hi;
  }
}

/* Closed boxes overlap (touching counts, as for the triangles). */
static inline int isect_box_overlap(const double *a, const double *b) {
  return a[0] <= b[3] && b[0] <= a[3] && a[1] <= b[4] && b[1] <= a[4] && a[2] <= b[5] &&
         b[2] <= a[5];
}

/* The pair test without the box pre-check (the callers did it). */
int isect_tri_tri(const double *a, const uint32_t *va, const double *b, const uint32_t *vb);

/* The hierarchy: node n is a leaf of count triangles order[first ..] when
 * count > 0, else its children are nodes first and first + 1. */
typedef struct {
  double box[6];
  uint32_t first, count;
} isect_node;
typedef struct {
  isect_node *node;
  uint32_t *order; /* triangle ids, leaves' ranges */
  double *box;     /* 6 per triangle */
  uint32_t nnode;
} isect_bvh;
sessile_status isect_bvh_build(isect_bvh *b, const uint32_t *tri, uint32_t nf, const double *pos);
void isect_bvh_free(isect_bvh *b);

/* A growable list of pairs (f, g), f < g. */
typedef struct {
  uint32_t *p;
  size_t n, cap;
} isect_pairs;
/* Every intersecting pair at positions pos with at least one triangle active
 * (all when active is NULL), each once, sorted by (f, g).  out is reset. */
sessile_status isect_self_pairs(const uint32_t *tri, uint32_t nf, const double *pos,
                                const uint8_t *active, isect_pairs *out);

/* The motion guard on raw arrays: cur (3 nv) enters as the proposed
 * positions and leaves guarded; old_pos the positions before. */
sessile_status isect_guard(const uint32_t *tri, uint32_t nf, uint32_t nv, const double *old_pos,
                           double *cur, int halfway, sessile_guard_stats *st);
#endif
