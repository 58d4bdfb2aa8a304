/* Remesh, phase 1 (§4.6 vertex insertion): every edge longer than insert_len
 * gets a vertex on the curve its ends' normals define, and every triangle is
 * re-triangulated by the pattern of its split edges (1, 2 or 3: red-green
 * refinement).  All long edges of a sweep are split at once, so the result
 * does not depend on an order of visits; sweeps repeat until no edge is long.
 * Edges are found through the sorted vertex-neighbour CSR (no hashing). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "mesh/intersect_internal.h"
#include "mesh/mesh_internal.h"

#define NONE UINT32_MAX

static double dist2(const double *p, const double *q) {
  double x = p[0] - q[0], y = p[1] - q[1], z = p[2] - q[2];
  return x * x + y * y + z * z;
}

/* Midpoint vertex of edge (a, b), or NONE: the entry sits in the lower end's row. */
static uint32_t mid_of(const uint32_t *off, const uint32_t *nbr, const uint32_t *mid, uint32_t a,
                       uint32_t b) {
  uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
  for (uint32_t k = off[lo]; k < off[lo + 1]; k++)
    if (nbr[k] == hi) return mid[k];
  return NONE;
}

static uint32_t *emit(uint32_t *t, uint32_t a, uint32_t b, uint32_t c) {
  t[0] = a, t[1] = b, t[2] = c;
  return t + 3;
}

/* New triangles of triangle v (CCW) with edge midpoints m[e] on (v[e], v[e+1]). */
static uint32_t *refine(const sessile_surface *s, const uint32_t v[3], const uint32_t m[3],
                        uint32_t *t) {
  int n = (m[0] != NONE) + (m[1] != NONE) + (m[2] != NONE);
  if (n == 0) return emit(t, v[0], v[1], v[2]);
  if (n == 3) {
    t = emit(t, v[0], m[0], m[2]);
    t = emit(t, v[1], m[1], m[0]);
    t = emit(t, v[2], m[2], m[1]);
    return emit(t, m[0], m[1], m[2]);
  }
  if (n == 1) {
    int i = m[0] != NONE ? 0 : m[1] != NONE ? 1 : 2;
    t = emit(t, v[i], m[i], v[(i + 2) % 3]);
    return emit(t, m[i], v[(i + 1) % 3], v[(i + 2) % 3]);
  }
  /* Two split: rotate so the unsplit edge is (c, a); split edges ab, bc. */
  int j = m[0] == NONE ? 0 : m[1] == NONE ? 1 : 2;
  uint32_t c = v[j], a = v[(j + 1) % 3], b = v[(j + 2) % 3];
  uint32_t mab = m[(j + 1) % 3], mbc = m[(j + 2) % 3];
  t = emit(t, mab, b, mbc);
  /* quad (a, mab, mbc, c): the shorter diagonal */
  if (dist2(s->pos + 3 * mab, s->pos + 3 * c) <= dist2(s->pos + 3 * a, s->pos + 3 * mbc)) {
    t = emit(t, a, mab, c);
    return emit(t, mab, mbc, c);
  }
  t = emit(t, a, mab, mbc);
  return emit(t, a, mbc, c);
}

/* Contact inhibition for the sweep's new vertices: a curve point may not
 * make the surface cross itself.  Put on its edge's midpoint instead, a new
 * vertex only re-triangulates the old flat triangles, which cannot cross
 * anything they did not cross before; so the motion guard runs from those
 * midpoints to the curve points and sends back (all the way) the vertices
 * of every pair it finds. */
static sessile_status guard_points(sessile_surface *s, const uint32_t *off, const uint32_t *nbr,
                                   const uint32_t *mid, uint32_t nv0, uint32_t *chord) {
  double *flat = malloc((size_t)s->nv * 3 * sizeof *flat);
  SESSILE_CHECK(flat, SESSILE_ERR_NO_MEMORY, "out of host memory for %u vertices", s->nv);
  memcpy(flat, s->pos, (size_t)s->nv * 3 * sizeof *flat);
  for (uint32_t a = 0; a < nv0; a++)
    for (uint32_t k = off[a]; k < off[a + 1]; k++)
      if (mid[k] != NONE)
        for (int c = 0; c < 3; c++)
          flat[3 * mid[k] + c] = 0.5 * (s->pos[3 * a + c] + s->pos[3 * nbr[k] + c]);
  sessile_guard_stats gs;
  sessile_status r = isect_guard(s->tri, s->nf, s->nv, flat, s->pos, 0, &gs);
  *chord += gs.held_back;
  free(flat);
  return r;
}

sessile_status remesh_split(sessile_surface *s, double **normals, const sessile_remesh_options *o,
                            uint32_t *splits, uint32_t *chord) {
  const double L2 = o->insert_len * o->insert_len;
  for (int pass = 0;; pass++) {
    uint32_t *off, *nbr;
    SESSILE_CALL(sessile_surface_vertex_neighbours(s, &off, &nbr));
    uint32_t nlong = 0;
    double worst = 0;
    for (uint32_t a = 0; a < s->nv; a++)
      for (uint32_t k = off[a]; k < off[a + 1]; k++) {
        double l2 = dist2(s->pos + 3 * a, s->pos + 3 * nbr[k]);
        if (nbr[k] > a && l2 > L2) nlong++, worst = l2 > worst ? l2 : worst;
      }
    if (!nlong || pass == o->max_passes) {
      free(off), free(nbr);
      SESSILE_CHECK(!nlong, SESSILE_ERR_NUMERIC,
                    "remesh: after %d split sweeps an edge is still %g long (insert_len %g); the "
                    "surface moved too far in one growth step",
                    pass, sqrt(worst), o->insert_len);
      return SESSILE_OK;
    }
    if (s->nf > UINT32_MAX / 4 || s->nv > UINT32_MAX - nlong) {
      free(off), free(nbr);
      return sessile_error_set(SESSILE_ERR_TOO_LARGE,
                               "remesh: splitting %u edges of %u triangles overflows 32-bit indices",
                               nlong, s->nf);
    }
    uint32_t *mid = malloc(((size_t)off[s->nv] + 1) * sizeof *mid);
    uint32_t *nt = malloc((size_t)s->nf * 12 * sizeof *nt);
    sessile_status r = mid && nt ? sessile_surface_reserve(s, s->nv + nlong, s->nf * 4)
                                 : sessile_error_set(SESSILE_ERR_NO_MEMORY,
                                                     "out of host memory splitting %u edges", nlong);
    double *n = r == SESSILE_OK ? realloc(*normals, (size_t)s->cap_v * 3 * sizeof *n) : NULL;
    if (r == SESSILE_OK && !n)
      r = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory for %u normals", s->cap_v);
    if (r != SESSILE_OK) {
      free(off), free(nbr), free(mid), free(nt);
      return r;
    }
    *normals = n;
    uint32_t nv0 = s->nv;
    for (uint32_t a = 0; a < nv0; a++)
      for (uint32_t k = off[a]; k < off[a + 1]; k++) {
        uint32_t b = nbr[k];
        mid[k] = NONE;
        if (b < a || dist2(s->pos + 3 * a, s->pos + 3 * b) <= L2) continue;
        uint32_t v = s->nv++;
        remesh_edge_point(s->pos + 3 * a, n + 3 * a, s->pos + 3 * b, n + 3 * b, o, s->pos + 3 * v);
        double *nm = n + 3 * v, l;
        for (int c = 0; c < 3; c++) nm[c] = n[3 * a + c] + n[3 * b + c];
        l = sqrt(nm[0] * nm[0] + nm[1] * nm[1] + nm[2] * nm[2]);
        if (l > 0) nm[0] /= l, nm[1] /= l, nm[2] /= l;
        else memcpy(nm, n + 3 * a, 3 * sizeof *nm);
        mid[k] = v;
      }
    uint32_t *t = nt;
    for (uint32_t f = 0; f < s->nf; f++) {
      const uint32_t *v = s->tri + 3 * f;
      uint32_t m[3];
      for (int e = 0; e < 3; e++) m[e] = mid_of(off, nbr, mid, v[e], v[(e + 1) % 3]);
      t = refine(s, v, m, t);
    }
    s->nf = (uint32_t)((t - nt) / 3);
    memcpy(s->tri, nt, (size_t)s->nf * 3 * sizeof *nt);
    *splits += nlong;
    r = o->guard_intersections ? guard_points(s, off, nbr, mid, nv0, chord) : SESSILE_OK;
    free(off), free(nbr), free(mid), free(nt);
    SESSILE_CALL(r);
  }
}
