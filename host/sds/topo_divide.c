/* Cell division (§3.1.1): the star of the cell removed, its hull kept, two
 * daughters inside, the hull re-tetrahedralised by TetGen (docs/sds_topology.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "topo_internal.h"

/* Fraction of the distance from c to the hull at which a daughter sits:
 * strictly inside, and as far from the hull as from c. */
#define DIVIDE_FRAC 0.5

/* Ray o + t dir (dir unit) against triangle (a, b, c): t > 0 of the hit, or INFINITY. */
static double ray_tri(const double *o, const double *dir, const double *a, const double *b, const double *c) {
  double e1[3], e2[3], p[3], s[3], q[3];
  for (int k = 0; k < 3; k++) e1[k] = b[k] - a[k], e2[k] = c[k] - a[k], s[k] = o[k] - a[k];
  p[0] = dir[1] * e2[2] - dir[2] * e2[1], p[1] = dir[2] * e2[0] - dir[0] * e2[2],
  p[2] = dir[0] * e2[1] - dir[1] * e2[0];
  double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
  if (fabs(det) < 1e-300) return INFINITY;
  double inv = 1.0 / det, u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) * inv;
  if (u < -1e-12 || u > 1 + 1e-12) return INFINITY;
  q[0] = s[1] * e1[2] - s[2] * e1[1], q[1] = s[2] * e1[0] - s[0] * e1[2], q[2] = s[0] * e1[1] - s[1] * e1[0];
  double v = (dir[0] * q[0] + dir[1] * q[1] + dir[2] * q[2]) * inv;
  if (v < -1e-12 || u + v > 1 + 1e-12) return INFINITY;
  double t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv;
  return t > 0 ? t : INFINITY;
}

/* Distance from x[c] along dir to the nearest hull face not containing c. */
static double hull_distance(const double *x, uint32_t c, const double *dir, const uint32_t *hull, uint32_t nf) {
  double tmin = INFINITY;
  for (uint32_t f = 0; f < nf; f++) {
    const uint32_t *v = hull + 3 * (size_t)f;
    if (v[0] == c || v[1] == c || v[2] == c) continue;
    tmin =
        fmin(tmin, ray_tri(x + 3 * (size_t)c, dir, x + 3 * (size_t)v[0], x + 3 * (size_t)v[1], x + 3 * (size_t)v[2]));
  }
  return tmin;
}

/* Is p strictly inside one of the tets list[0..n) (all barycentric
 * coordinates above a relative 1e-9)? */
static int inside_star(const double *x, const uint32_t *tet, const uint32_t *list, uint32_t n, const double *p) {
  for (uint32_t i = 0; i < n; i++) {
    const uint32_t *t = tet + 4 * (size_t)list[i];
    double V = topo_vol4(x, t);
    if (!(V > 0)) continue;
    int ok = 1;
    for (int q = 0; q < 4 && ok; q++) {
      const double *y[4];
      for (int r = 0; r < 4; r++) y[r] = x + 3 * (size_t)t[r];
      y[q] = p;
      ok = sessile_sds_topo_volume(y[0], y[1], y[2], y[3]) > 1e-9 * V;
    }
    if (ok) return 1;
  }
  return 0;
}

/* The fallback when TetGen needs a Steiner point: the hull coned from the
 * apex (the tets (apex, f) over the hull faces f without it: valid when the
 * apex sees every face, i.e. lies in the hull's kernel), then the cone tet
 * holding b strictly inside split into four.  A poorer vertex degree than
 * TetGen's Delaunay mesh (the paper's reason for re-meshing), but always
 * possible for a star-shaped hull with the daughters near c. */
static sessile_status cone_split(const double *x, const uint32_t *hull, uint32_t nf, uint32_t apex, uint32_t b,
                                 uint32_t **out, uint32_t *nout) {
  uint32_t *t = malloc((4 * (size_t)nf + 16) * sizeof *t), n = 0, hold = UINT32_MAX;
  SESSILE_CHECK(t, SESSILE_ERR_NO_MEMORY, "out of host memory dividing a cell");
  for (uint32_t f = 0; f < nf; f++) {
    const uint32_t *h = hull + 3 * (size_t)f;
    if (h[0] == apex || h[1] == apex || h[2] == apex) continue;
    /* h is outward, so (h0, h2, h1) faces the apex: (h0, h2, h1, apex) positive */
    uint32_t *q = t + 4 * (size_t)n++;
    q[0] = h[0], q[1] = h[2], q[2] = h[1], q[3] = apex;
    double V = topo_vol4(x, q);
    if (!(V > 0)) {
      free(t);
      return sessile_error_set(SESSILE_ERR_NUMERIC, "the daughter does not see hull face (%u %u %u)", h[0], h[1], h[2]);
    }
    int in = 1;
    for (int k = 0; k < 4 && in; k++) {
      uint32_t r[4] = {q[0], q[1], q[2], q[3]};
      r[k] = b;
      in = topo_vol4(x, r) > 1e-9 * V;
    }
    if (in) hold = n - 1;
  }
  if (hold == UINT32_MAX) {
    free(t);
    return sessile_error_set(SESSILE_ERR_NUMERIC, "the second daughter lies on no cone tet's interior");
  }
  uint32_t q[4];
  memcpy(q, t + 4 * (size_t)hold, sizeof q);
  for (int k = 0; k < 4; k++) {
    uint32_t *r = k == 0 ? t + 4 * (size_t)hold : t + 4 * (size_t)n++;
    memcpy(r, q, sizeof q);
    r[k] = b;
  }
  *out = t, *nout = n;
  return SESSILE_OK;
}

/* Is dir within 45° of the tangent plane at surface cell c (normal: the
 * area-weighted normal of c's boundary faces in the hull)? */
static int tangential_enough(const double *x, uint32_t c, const double *dir, const uint32_t *hull, uint32_t nf) {
  double n[3] = {0, 0, 0};
  for (uint32_t f = 0; f < nf; f++) {
    const uint32_t *v = hull + 3 * (size_t)f;
    if (v[0] != c && v[1] != c && v[2] != c) continue;
    const double *p0 = x + 3 * (size_t)v[0], *p1 = x + 3 * (size_t)v[1], *p2 = x + 3 * (size_t)v[2];
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) e1[k] = p1[k] - p0[k], e2[k] = p2[k] - p0[k];
    n[0] += e1[1] * e2[2] - e1[2] * e2[1], n[1] += e1[2] * e2[0] - e1[0] * e2[2], n[2] += e1[0] * e2[1] - e1[1] * e2[0];
  }
  double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(nl > 0)) return 0;
  double cn = (n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2]) / nl;
  return fabs(cn) < sqrt(0.5);
}

sessile_status sessile_sds_topo_divide(sessile_sds_topo_complex *cx, uint32_t c, const double d[3], double eps_max,
                                       sessile_sds_topo_division *div) {
  memset(div, 0, sizeof *div);
  SESSILE_CHECK(c < cx->nv, SESSILE_ERR_USAGE, "division of cell %u: only %u cells", c, cx->nv);
  double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  SESSILE_CHECK(len > 0 && isfinite(len), SESSILE_ERR_USAGE, "division of cell %u: the direction is zero or not finite",
                c);
  SESSILE_CHECK(cx->nv < UINT32_MAX - 1, SESSILE_ERR_TOO_LARGE, "division: too many cells");
  double dir[3] = {d[0] / len, d[1] / len, d[2] / len};
  /* T_c: the tets around c. */
  uint32_t *star = malloc(((size_t)cx->nt + 1) * sizeof *star), ns = 0;
  uint8_t *rm = calloc((size_t)cx->nt + 1, 1);
  uint32_t *hull = NULL, nf = 0, *add = NULL, nadd = 0;
  sessile_status st = SESSILE_OK;
  if (!star || !rm) {
    st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory dividing cell %u", c);
    goto done;
  }
  for (uint32_t t = 0; t < cx->nt; t++) {
    const uint32_t *v = cx->tet + 4 * (size_t)t;
    if (v[0] == c || v[1] == c || v[2] == c || v[3] == c) star[ns++] = t, rm[t] = 1;
  }
  if (!ns) {
    st = sessile_error_set(SESSILE_ERR_USAGE, "division of cell %u: the cell is in no tetrahedron", c);
    goto done;
  }
  st = topo_cavity_hull(cx->tet, star, ns, &hull, &nf);
  if (st != SESSILE_OK) goto done;
  int surface = 0;
  for (uint32_t f = 0; f < 3 * nf; f++) surface |= hull[f] == c;
  /* Room for b (appended only on success). */
  double *nx = realloc(cx->x, 3 * ((size_t)cx->nv + 1) * sizeof *nx);
  if (!nx) {
    st = sessile_error_set(SESSILE_ERR_NO_MEMORY, "out of host memory dividing cell %u", c);
    goto done;
  }
  cx->x = nx;
  double *xc = cx->x + 3 * (size_t)c, *xb = cx->x + 3 * (size_t)cx->nv, c0[3];
  memcpy(c0, xc, sizeof c0);
  uint32_t b = cx->nv, pts[2];
  uint32_t npts;
  double eps = 0, bdir[3] = {0, 0, 0};
  if (!surface) {
    double mdir[3] = {-dir[0], -dir[1], -dir[2]};
    double tp = hull_distance(cx->x, c, dir, hull, nf), tm = hull_distance(cx->x, c, mdir, hull, nf);
    double reach = fmin(tp, tm);
    if (!isfinite(reach)) {
      st =
          sessile_error_set(SESSILE_ERR_NUMERIC, "division of cell %u: the ray along the direction misses the hull", c);
      goto done;
    }
    int ok = 0;
    for (double frac = DIVIDE_FRAC; frac > 0.05 && !ok; frac *= 0.8) {
      eps = frac * reach;
      if (eps_max > 0 && eps > eps_max) eps = eps_max;
      double pa[3], pb[3];
      for (int k = 0; k < 3; k++) pa[k] = c0[k] + eps * dir[k], pb[k] = c0[k] - eps * dir[k];
      ok = inside_star(cx->x, cx->tet, star, ns, pa) && inside_star(cx->x, cx->tet, star, ns, pb);
      if (ok) memcpy(xc, pa, sizeof pa), memcpy(xb, pb, sizeof pb);
    }
    if (!ok) {
      st =
          sessile_error_set(SESSILE_ERR_NUMERIC, "division of cell %u: found no daughter positions inside the hull", c);
      goto done;
    }
    pts[0] = c, pts[1] = b, npts = 2;
    for (int k = 0; k < 3; k++) bdir[k] = -dir[k];
  } else {
    /* along the surface when d is within 45° of the tangent plane: both
     * daughters on the boundary (topo_divide_surface.c) */
    if (tangential_enough(cx->x, c, dir, hull, nf)) {
      st = topo_divide_tangential(cx, c, dir, eps_max, hull, nf, rm, div);
      if (st == SESSILE_OK || st == SESSILE_ERR_NO_MEMORY) goto done;
      st = SESSILE_OK; /* the inward split below */
    }
    /* a stays at c on the boundary; b goes inside along ±d, else along the
     * inward normal of c's boundary faces. */
    double cand[4][3], n[3] = {0, 0, 0};
    for (uint32_t f = 0; f < nf; f++) {
      const uint32_t *v = hull + 3 * (size_t)f;
      if (v[0] != c && v[1] != c && v[2] != c) continue;
      const double *p0 = cx->x + 3 * (size_t)v[0], *p1 = cx->x + 3 * (size_t)v[1], *p2 = cx->x + 3 * (size_t)v[2];
      double e1[3], e2[3];
      for (int k = 0; k < 3; k++) e1[k] = p1[k] - p0[k], e2[k] = p2[k] - p0[k];
      n[0] -= e1[1] * e2[2] - e1[2] * e2[1], n[1] -= e1[2] * e2[0] - e1[0] * e2[2],
          n[2] -= e1[0] * e2[1] - e1[1] * e2[0];
    }
    double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) cand[0][k] = dir[k], cand[1][k] = -dir[k], cand[2][k] = nl > 0 ? n[k] / nl : 0;
    /* Last resort, always inside: toward the centroid of the star tet most
     * aligned with ±d (the segment from a corner to the centroid lies in the
     * tet); capped below at that distance. */
    double gbest = 0, gdist = 0;
    for (uint32_t i = 0; i < ns; i++) {
      const uint32_t *t = cx->tet + 4 * (size_t)star[i];
      double g[3] = {0, 0, 0}, gl = 0;
      for (int q = 0; q < 4; q++)
        for (int k = 0; k < 3; k++) g[k] += 0.25 * cx->x[3 * (size_t)t[q] + k];
      for (int k = 0; k < 3; k++) g[k] -= c0[k], gl += g[k] * g[k];
      gl = sqrt(gl);
      double cosang = fabs(g[0] * dir[0] + g[1] * dir[1] + g[2] * dir[2]) / gl;
      if (gl > 0 && cosang >= gbest)
        for (int k = 0; k < 3; k++) gbest = cosang, gdist = gl, cand[3][k] = g[k] / gl;
    }
    int ok = 0;
    for (int ci = 0; ci < 4 && !ok; ci++) {
      double reach = hull_distance(cx->x, c, cand[ci], hull, nf);
      if (!isfinite(reach)) continue;
      for (double frac = DIVIDE_FRAC; frac > 0.05 && !ok; frac *= 0.8) {
        eps = frac * reach;
        if (eps_max > 0 && eps > eps_max) eps = eps_max;
        if (ci == 3 && eps > gdist) eps = frac * gdist;
        double pb[3];
        for (int k = 0; k < 3; k++) pb[k] = c0[k] + eps * cand[ci][k];
        ok = inside_star(cx->x, cx->tet, star, ns, pb);
        if (ok) memcpy(xb, pb, sizeof pb), memcpy(bdir, cand[ci], sizeof bdir);
      }
    }
    if (!ok) {
      st = sessile_error_set(SESSILE_ERR_NUMERIC,
                             "division of surface cell %u: found no inside position for the daughter", c);
      goto done;
    }
    pts[0] = b, npts = 1;
  }
  /* TetGen's mesh must make the daughters neighbours (§3.1.1: "the new cells
   * are neighbours"); when it does not (about 1 division in 200), the pair is
   * pulled together along the same line (eps halved: both stay inside, the
   * segment from c to a point inside a star tet lies in it) and meshed again. */
  int adjacent = 0;
  for (int tries = 0; tries < 4 && !adjacent; tries++) {
    if (tries > 0) {
      eps *= 0.5;
      for (int k = 0; k < 3; k++) {
        if (!surface) xc[k] = c0[k] + eps * dir[k];
        xb[k] = c0[k] + eps * bdir[k];
      }
    }
    free(add), add = NULL;
    st = topo_fill_hull(cx->x, hull, nf, pts, npts, &add, &nadd);
    if (st != SESSILE_OK) break;
    for (uint32_t i = 0; i < nadd && !adjacent; i++) {
      const uint32_t *v = add + 4 * (size_t)i;
      adjacent =
          (v[0] == c || v[1] == c || v[2] == c || v[3] == c) && (v[0] == b || v[1] == b || v[2] == b || v[3] == b);
    }
  }
  if (st == SESSILE_OK && !adjacent)
    st = sessile_error_set(SESSILE_ERR_NUMERIC, "TetGen's meshes never joined the daughters by an edge");
  if (st == SESSILE_ERR_NUMERIC) {
    /* TetGen needed a Steiner point (or refused, or kept the daughters
     * apart): cone from a, split at b (they are neighbours then); an
     * interior pair pulled toward c until a sees the whole hull. */
    char why[256];
    snprintf(why, sizeof why, "%s", sessile_error_message());
    free(add), add = NULL;
    for (int tries = 0; tries < 12 && st != SESSILE_OK; tries++) {
      if (!surface && tries > 0) {
        eps *= 0.5;
        for (int k = 0; k < 3; k++) xc[k] = c0[k] + eps * dir[k], xb[k] = c0[k] + eps * bdir[k];
      }
      st = cone_split(cx->x, hull, nf, c, b, &add, &nadd);
      if (surface) break;
    }
    if (st != SESSILE_OK)
      st = sessile_error_set(SESSILE_ERR_NUMERIC, "division of cell %u: %s; the cone fallback failed too: %s", c, why,
                             sessile_error_message());
    else
      div->fallback = 1;
  }
  if (st != SESSILE_OK) {
    memcpy(xc, c0, sizeof c0);
    goto done;
  }
  st = topo_replace(cx, rm, add, nadd, &div->tet_from, &div->n_removed);
  if (st != SESSILE_OK) {
    memcpy(xc, c0, sizeof c0);
    goto done;
  }
  cx->nv++;
  div->a = c, div->b = b, div->surface = surface, div->eps = eps, div->n_added = nadd;
done:
  free(star), free(rm), free(hull), free(add);
  return st;
}
