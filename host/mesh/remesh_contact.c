/* Remesh, phase 2's contact guard (docs/intersection.md): a collapse whose
 * new triangles (the fan of the merged vertex) would cross the surface, or
 * each other, is refused.  The surface's triangles sit in a grid of their
 * boxes (sessile_tri_grid) built when the collapses start; a committed
 * collapse re-inserts its fan.
 *
 * Such a refusal depends on triangles beyond the 2-ring that the collapse
 * code re-examines after a change, so each one is recorded with the box of
 * the fan it would have made: a later collapse that changes triangles in
 * that box marks the refused edge's ends dirty, and the candidate is tried
 * again in the next sweep.  So the fixed point stays a fixed point: nothing
 * a refused candidate read changes without it being re-examined. */
#include <stdlib.h>
#include <string.h>
#include "mesh/intersect_internal.h"
#include "mesh/mesh_internal.h"

static int grow_to(void **p, uint32_t *cap, uint32_t need, size_t each) {
  if (need <= *cap) return 1;
  uint32_t c = *cap ? *cap : 16;
  while (c < need) c *= 2;
  void *q = realloc(*p, c * each);
  if (!q) return 0;
  *p = q, *cap = c;
  return 1;
}

sessile_status remesh_contact_begin(remesh_contact *k, const sessile_surface *s) {
  memset(k, 0, sizeof *k);
  return sessile_tri_grid_create(s, &k->grid);
}

void remesh_contact_end(remesh_contact *k) {
  sessile_tri_grid_destroy(k->grid);
  free(k->cv), free(k->cp), free(k->ex), free(k->rbox), free(k->rv);
  memset(k, 0, sizeof *k);
}

static void box_add(double *box, const double *p) {
  for (int a = 0; a < 3; a++) {
    if (p[a] < box[a]) box[a] = p[a];
    if (p[a] > box[3 + a]) box[3 + a] = p[a];
  }
}

int remesh_contact_blocks(remesh_contact *k, const sessile_surface *s, const uint8_t *falive,
                          uint32_t lo, uint32_t hi, const double p[3], const uint32_t *fa,
                          uint32_t na, const uint32_t *fb, uint32_t nb, const uint32_t sh[2]) {
  uint32_t m = na + nb;
  if (!grow_to((void **)&k->cv, &k->cvcap, 3 * m, sizeof *k->cv) ||
      !grow_to((void **)&k->cp, &k->cpcap, 9 * m, sizeof *k->cp) ||
      !grow_to((void **)&k->ex, &k->excap, m, sizeof *k->ex)) {
    k->failed = 1;
    return 1;
  }
  /* The fan after the collapse: the triangles of lo and hi but the edge's
   * two (the only ones with both), hi relabelled to lo, lo at p.  All of
   * lo's and hi's triangles are replaced, so none is tested against it.
   * changed: the box of the fan before and after (for the commit). */
  uint32_t n = 0;
  double fan[6] = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
  for (int a = 0; a < 3; a++) k->changed[a] = 1e300, k->changed[3 + a] = -1e300;
  memcpy(k->ex, fa, na * sizeof *k->ex);
  memcpy(k->ex + na, fb, nb * sizeof *k->ex);
  for (uint32_t i = 0; i < m; i++) {
    uint32_t f = k->ex[i];
    const uint32_t *t = s->tri + 3 * f;
    for (int c = 0; c < 3; c++) box_add(k->changed, s->pos + 3 * t[c]);
    if (f == sh[0] || f == sh[1]) continue;
    for (int c = 0; c < 3; c++) {
      int moved = t[c] == lo || t[c] == hi;
      k->cv[3 * n + c] = moved ? lo : t[c];
      memcpy(k->cp + 9 * n + 3 * c, moved ? p : s->pos + 3 * t[c], 3 * sizeof *k->cp);
      box_add(fan, k->cp + 9 * n + 3 * c);
    }
    n++;
  }
  box_add(k->changed, fan), box_add(k->changed, fan + 3);
  if (!sessile_tri_grid_hits(k->grid, s, falive, n, k->cv, k->cp, k->ex, m)) return 0;
  k->refusals++;
  if (!grow_to((void **)&k->rbox, &k->rboxcap, 6 * (k->nrec + 1), sizeof *k->rbox) ||
      !grow_to((void **)&k->rv, &k->rvcap, 2 * (k->nrec + 1), sizeof *k->rv)) {
    k->failed = 1;
    return 1;
  }
  memcpy(k->rbox + 6 * k->nrec, fan, sizeof fan);
  k->rv[2 * k->nrec] = lo, k->rv[2 * k->nrec + 1] = hi;
  k->nrec++;
  return 1;
}

void remesh_contact_commit(remesh_contact *k, const sessile_surface *s, const uint32_t *fan,
                           uint32_t n, uint8_t *ndirty) {
  if (sessile_tri_grid_insert(k->grid, s, fan, n) != SESSILE_OK) k->failed = 1;
  for (uint32_t i = 0; i < k->nrec; i++)
    if (isect_box_overlap(k->rbox + 6 * i, k->changed))
      ndirty[k->rv[2 * i]] = ndirty[k->rv[2 * i + 1]] = 1;
}
