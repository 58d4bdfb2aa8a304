/* Remeshing the particle sponge and carrying its per-vertex growth counts
 * over.  sessile_remesh keeps the surviving vertices' relative order and
 * positions but returns no map, so the counts follow positions: a vertex at
 * exactly an old vertex's position keeps its count; a new one (a split's
 * curve point, a collapse's merged vertex) takes the mean, rounded down, of
 * its neighbours that kept theirs (docs/sponge_particles.md). */
#include <stdlib.h>
#include <string.h>
#include "particles_internal.h"
#include "sessile/mesh/intersect.h"

typedef struct {
  double x[3];
  uint32_t v;
} keyed;

static int cmp_keyed(const void *a, const void *b) {
  const keyed *p = a, *q = b;
  for (int k = 0; k < 3; k++)
    if (p->x[k] != q->x[k]) return p->x[k] < q->x[k] ? -1 : 1;
  return p->v < q->v ? -1 : p->v > q->v;
}

sessile_status particles_remesh(sessile_sponge_particles *ps, uint32_t *refused) {
  const sessile_sponge_particles_params *p = &ps->p;
  *refused = 0;
  sessile_surface copy = {0}, *s = &copy;
  SESSILE_CALL(sessile_surface_copy(&ps->surf, &copy));
  uint32_t nv0 = s->nv;
  keyed *old = malloc(((size_t)nv0 + 1) * sizeof *old);
  if (!old) {
    sessile_surface_free(&copy);
    return sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %u vertices", nv0);
  }
  for (uint32_t v = 0; v < nv0; v++) memcpy(old[v].x, s->pos + 3 * v, sizeof old[v].x), old[v].v = v;
  qsort(old, nv0, sizeof *old, cmp_keyed);
  sessile_remesh_options ro;
  sessile_remesh_options_default(&ro);
  ro.insert_len = p->splitting_threshold;
  ro.fuse_len = p->collapse_threshold;
  /* ours: triangles below a tenth of a collapse-length square are slivers */
  ro.min_area = 0.1 * p->collapse_threshold * p->collapse_threshold;
  double half = p->cube_size / 2;
  ro.clamp_lo[0] = ro.clamp_lo[1] = -half, ro.clamp_lo[2] = 0;
  ro.clamp_hi[0] = ro.clamp_hi[1] = half, ro.clamp_hi[2] = p->cube_size;
  ro.guard_intersections = 1;
  sessile_remesh_stats rs;
  sessile_status st = sessile_remesh(s, NULL, &ro, &rs);
  /* The remesher's contact guard should make this impossible, but a crossing
   * remesh was seen (docs/sponge_particles.md, "Known problems"): the
   * invariant is ours to keep, so such a remesh is dropped. */
  uint64_t crossings = 0;
  if (st == SESSILE_OK) st = sessile_surface_self_intersections(s, 0, NULL, &crossings);
  if (st == SESSILE_OK && crossings) {
    *refused = 1;
    free(old);
    sessile_surface_free(&copy);
    return SESSILE_OK;
  }
  uint32_t nv = s->nv, *counts = NULL, *off = NULL, *nbr = NULL;
  uint8_t *known = NULL;
  if (st == SESSILE_OK) {
    counts = calloc((size_t)nv + 1, sizeof *counts);
    known = calloc((size_t)nv + 1, 1);
    if (!counts || !known) st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %u vertices", nv);
  }
  if (st == SESSILE_OK) st = sessile_surface_vertex_neighbours(s, &off, &nbr);
  if (st == SESSILE_OK) {
    for (uint32_t v = 0; v < nv; v++) {
      keyed key;
      memcpy(key.x, s->pos + 3 * v, sizeof key.x);
      key.v = 0;
      /* the first old vertex at this position (lower bound) */
      size_t lo = 0, hi = nv0;
      while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (cmp_keyed(&old[mid], &key) < 0) lo = mid + 1;
        else hi = mid;
      }
      if (lo < nv0 && old[lo].x[0] == key.x[0] && old[lo].x[1] == key.x[1] && old[lo].x[2] == key.x[2]) {
        counts[v] = ps->counts[old[lo].v];
        known[v] = 1;
      }
    }
    for (uint32_t v = 0; v < nv; v++) {
      if (known[v]) continue;
      uint64_t sum = 0, n = 0;
      for (uint32_t e = off[v]; e < off[v + 1]; e++)
        if (known[nbr[e]]) sum += counts[nbr[e]], n++;
      counts[v] = n ? (uint32_t)(sum / n) : 0;
    }
    free(ps->counts);
    ps->counts = counts;
    counts = NULL;
    sessile_surface_free(&ps->surf);
    ps->surf = copy;
    copy = (sessile_surface){0};
  }
  sessile_surface_free(&copy);
  free(old), free(counts), free(known), free(off), free(nbr);
  return st;
}
