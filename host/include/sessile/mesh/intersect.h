/* sessile — self-intersection of the sponge surface, and contact inhibition:
 * the guards that keep a growing surface from crossing itself
 * (docs/intersection.md).  Plain C on the host, double precision.
 *
 * "Intersect" means the closed triangles share a point other than what their
 * common vertices (by index) make them share: touching counts.  The
 * orientation predicates trust a sign only beyond Shewchuk's error bound and
 * read anything below it as zero (on the plane), so a pair is reported when
 * it intersects or lies within rounding of touching; the one miss possible
 * is a fold over a shared edge by a triangle of next to no area. */
#ifndef SESSILE_INTERSECT_H
#define SESSILE_INTERSECT_H

#include <stdint.h>
#include "sessile/status.h"
#include "sessile/mesh/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Do triangles a and b (corner positions, 9 doubles each) intersect?  va, vb:
 * their vertex ids; corners with one id are one point, and the vertex or edge
 * they share is no intersection: two triangles with one common vertex
 * intersect when anything else of them meets, two with a common edge when
 * they are coplanar and fold onto each other.  NULL ids: nothing shared.
 * Returns 1 or 0. */
int sessile_triangles_intersect(const double a[9], const uint32_t va[3], const double b[9],
                                const uint32_t vb[3]);

/* The intersecting triangle pairs of s: *count of them, and the first
 * max_pairs as (f, g), f < g, into pairs (2 max_pairs; NULL for the count
 * only), ordered by f then g.  A bounding-volume hierarchy over the
 * triangles (median splits, leaves of at most 4); deterministic. */
sessile_status sessile_surface_self_intersections(const sessile_surface *s, uint32_t max_pairs,
                                                  uint32_t *pairs, uint64_t *count);

/* --- incremental query: a grid of triangle boxes -------------------------- */
/* For a surface whose triangles change a few at a time (the remesher's
 * collapses): a uniform hash grid of the triangles' bounding boxes, cell size
 * twice the mean of their largest sides at creation.  Triangles that move must be
 * inserted again (a query finds a triangle through its box at its last
 * insertion, then tests it at its current position in s); entries are never
 * removed, dead triangles are skipped, so stale entries cost time only. */
typedef struct sessile_tri_grid sessile_tri_grid;
sessile_status sessile_tri_grid_create(const sessile_surface *s, sessile_tri_grid **out);
void sessile_tri_grid_destroy(sessile_tri_grid *g);
/* (Re-)inserts triangles faces[0..n) at their current positions. */
sessile_status sessile_tri_grid_insert(sessile_tri_grid *g, const sessile_surface *s,
                                       const uint32_t *faces, uint32_t n);
/* Does any of the n candidate triangles (vertex ids cand_v, 3 n; corner
 * positions cand_p, 9 n) intersect another candidate or a triangle of s
 * other than the nex listed in excluded?  alive (nf flags, NULL: all alive)
 * skips dead triangles.  Triangle ids must be below s->nf at creation.
 * Returns 1 or 0. */
int sessile_tri_grid_hits(sessile_tri_grid *g, const sessile_surface *s, const uint8_t *alive,
                          uint32_t n, const uint32_t *cand_v, const double *cand_p,
                          const uint32_t *excluded, uint32_t nex);

/* --- contact inhibition: the motion guard ---------------------------------- */
typedef struct sessile_guard_stats {
  uint32_t moved;     /* vertices whose new position differs from the old */
  uint32_t held_back; /* of those, vertices put back to their old position */
  uint32_t halfway;   /* of those, vertices left halfway (halfway mode) */
  uint32_t rounds;    /* rounds of finding pairs (1: the motion was clean) */
  uint32_t fallback;  /* 1 when the round limit put every moved vertex back */
  uint64_t preexisting; /* pairs that intersected before the motion (left alone) */
  double proposed_cm, kept_cm; /* summed |new - old| proposed, and kept */
} sessile_guard_stats;

/* Contact inhibition.  s at its old positions (s->pos), new_pos (3 nv) the
 * proposed ones; on return new_pos is a motion after which no triangle pair
 * intersects that did not intersect at s->pos (so a clean surface stays
 * clean).  Round by round, the vertices of both triangles of every pair that
 * intersects now but not before step back: to halfway first when halfway is
 * set, else (and then) to the old position; after 32 rounds every moved
 * vertex is put back.  Deterministic. */
sessile_status sessile_surface_guard_motion(const sessile_surface *s, double *new_pos, int halfway,
                                            sessile_guard_stats *st);

#ifdef __cplusplus
}
#endif
#endif
