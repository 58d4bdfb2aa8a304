/* Tangential division of a surface cell (§3.1.1, "a surface cell can divide
 * tangential to the surface"): both daughters stay on the boundary, which
 * gains one vertex, by a vertex split of c's boundary fan; the open hull of
 * c's star closed by the new fan is re-tetrahedralised by TetGen
 * (docs/sds_topology.md, "Tangential division"). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "topo_internal.h"

/* A fan larger than this is not split (a boundary vertex of degree > 64
 * means a degenerate complex; the inward division handles it). */
#define FAN_MAX 64
/* The daughters sit at ±EPS_FRAC of the mean distance from c to its ring. */
#define EPS_FRAC 0.25
/* A new boundary face must face outward: cosine to c's normal at least this. */
#define MIN_COS 0.2

static void cross3(const double *a, const double *b, double *o) {
  o[0] = a[1] * b[2] - a[2] * b[1], o[1] = a[2] * b[0] - a[0] * b[2], o[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* det(p0 - o, p1 - o, p2 - o) / 6: a face's share of the enclosed volume. */
static double face_vol(const double *o, const double *p0, const double *p1, const double *p2) {
  double a[3], b[3], c[3], n[3];
  for (int k = 0; k < 3; k++) a[k] = p0[k] - o[k], b[k] = p1[k] - o[k], c[k] = p2[k] - o[k];
  cross3(b, c, n);
  return dot3(a, n) / 6;
}

/* The new fan: ring l[0..k), wings i != j; faces (a, l_m, l_m+1) from i to j,
 * (b, l_m, l_m+1) from j around to i, then (a, l_j, b) and (b, l_i, a).
 * Writes k + 2 faces (global indices). */
static uint32_t fan_faces(const uint32_t *l, int k, int i, int j, uint32_t a, uint32_t b, uint32_t *f) {
  uint32_t n = 0;
  for (int m = i; m != j; m = (m + 1) % k) f[3 * n] = a, f[3 * n + 1] = l[m], f[3 * n + 2] = l[(m + 1) % k], n++;
  for (int m = j; m != i; m = (m + 1) % k) f[3 * n] = b, f[3 * n + 1] = l[m], f[3 * n + 2] = l[(m + 1) % k], n++;
  f[3 * n] = a, f[3 * n + 1] = l[j], f[3 * n + 2] = b, n++;
  f[3 * n] = b, f[3 * n + 1] = l[i], f[3 * n + 2] = a, n++;
  return n;
}

/* Smallest quality 4√3 A / Σ e² (1 for an equilateral triangle) over faces,
 * or -1 if one does not face along nrm (cosine below MIN_COS). */
static double fan_quality(const double *x, const uint32_t *f, uint32_t nf, const double *nrm) {
  double q = 1;
  for (uint32_t i = 0; i < nf; i++) {
    const double *p0 = x + 3 * (size_t)f[3 * i], *p1 = x + 3 * (size_t)f[3 * i + 1], *p2 = x + 3 * (size_t)f[3 * i + 2];
    double e1[3], e2[3], e3[3], n[3];
    for (int k = 0; k < 3; k++) e1[k] = p1[k] - p0[k], e2[k] = p2[k] - p0[k], e3[k] = p2[k] - p1[k];
    cross3(e1, e2, n);
    double nl = sqrt(dot3(n, n)), s = dot3(e1, e1) + dot3(e2, e2) + dot3(e3, e3);
    if (!(nl > 0) || dot3(n, nrm) < MIN_COS * nl) return -1;
    q = fmin(q, 2 * sqrt(3.0) * nl / s); /* A = nl / 2 */
  }
  return q;
}

sessile_status topo_divide_tangential(sessile_sds_topo_complex *cx, uint32_t c, const double *dir, double eps_max,
                                      const uint32_t *hull, uint32_t nf, const uint8_t *rm,
                                      sessile_sds_topo_division *div) {
  uint32_t b = cx->nv, ring[FAN_MAX], next_of[FAN_MAX][2];
  int k = 0, nfan = 0;
  double nrm[3] = {0, 0, 0}, *x = cx->x, c0[3];
  memcpy(c0, x + 3 * (size_t)c, sizeof c0);
  /* c's boundary fan: each face (c, p, q) outward gives the ring step p -> q */
  for (uint32_t f = 0; f < nf; f++) {
    const uint32_t *v = hull + 3 * (size_t)f;
    int at = v[0] == c ? 0 : v[1] == c ? 1 : v[2] == c ? 2 : -1;
    if (at < 0) continue;
    if (nfan == FAN_MAX) return sessile_error_set(SESSILE_ERR_UNSUPPORTED, "surface cell %u has over %d boundary faces", c, FAN_MAX);
    next_of[nfan][0] = v[(at + 1) % 3], next_of[nfan][1] = v[(at + 2) % 3], nfan++;
    double e1[3], e2[3], n[3];
    for (int q = 0; q < 3; q++)
      e1[q] = x[3 * (size_t)v[(at + 1) % 3] + q] - c0[q], e2[q] = x[3 * (size_t)v[(at + 2) % 3] + q] - c0[q];
    cross3(e1, e2, n);
    for (int q = 0; q < 3; q++) nrm[q] += n[q];
  }
  /* one cycle through every fan face (the boundary is vertex-manifold) */
  ring[k++] = next_of[0][0];
  for (int steps = 0; steps < nfan; steps++) {
    uint32_t p = ring[k - 1], q = UINT32_MAX;
    for (int i = 0; i < nfan; i++)
      if (next_of[i][0] == p) q = next_of[i][1];
    if (q == UINT32_MAX) return sessile_error_set(SESSILE_ERR_UNSUPPORTED, "surface cell %u: its fan is open", c);
    if (q == ring[0]) break;
    if (k == nfan) return sessile_error_set(SESSILE_ERR_UNSUPPORTED, "surface cell %u: its fan is not one cycle", c);
    ring[k++] = q;
  }
  if (k != nfan || k < 3) return sessile_error_set(SESSILE_ERR_UNSUPPORTED, "surface cell %u: its fan is not one cycle", c);
  double nl = sqrt(dot3(nrm, nrm));
  if (!(nl > 0)) return sessile_error_set(SESSILE_ERR_UNSUPPORTED, "surface cell %u: no normal", c);
  for (int q = 0; q < 3; q++) nrm[q] /= nl;
  /* the split direction: d projected on the tangent plane */
  double t[3], dn = dot3(dir, nrm), tl, mean = 0;
  for (int q = 0; q < 3; q++) t[q] = dir[q] - dn * nrm[q];
  tl = sqrt(dot3(t, t));
  if (!(tl > 0)) return sessile_error_set(SESSILE_ERR_UNSUPPORTED, "surface cell %u: the direction is normal", c);
  for (int q = 0; q < 3; q++) t[q] /= tl;
  for (int m = 0; m < k; m++) {
    double e[3];
    for (int q = 0; q < 3; q++) e[q] = x[3 * (size_t)ring[m] + q] - c0[q];
    mean += sqrt(dot3(e, e)) / k;
  }
  double eps = EPS_FRAC * mean;
  if (eps_max > 0 && eps > eps_max) eps = eps_max;
  /* faces: the hull's faces not through c, then room for the new fan */
  uint32_t *faces = malloc(3 * ((size_t)nf + 2 + 1) * sizeof *faces), nkeep = 0;
  SESSILE_CHECK(faces, SESSILE_ERR_NO_MEMORY, "out of host memory dividing cell %u", c);
  for (uint32_t f = 0; f < nf; f++) {
    const uint32_t *v = hull + 3 * (size_t)f;
    if (v[0] != c && v[1] != c && v[2] != c) memcpy(faces + 3 * (size_t)nkeep++, v, 3 * sizeof *v);
  }
  uint32_t *fan = faces + 3 * (size_t)nkeep, *add = NULL, nadd = 0;
  sessile_status st = sessile_error_set(SESSILE_ERR_UNSUPPORTED, "surface cell %u: no valid tangential fan", c);
  double *xa = x + 3 * (size_t)c, *xb = x + 3 * (size_t)b, used = eps;
  for (int shrink = 0; shrink < 3 && st != SESSILE_OK; shrink++, eps *= 0.5) {
    used = eps;
    for (int q = 0; q < 3; q++) xa[q] = c0[q] + eps * t[q], xb[q] = c0[q] - eps * t[q];
    /* the wings giving the best-shaped outward fan */
    int bi = -1, bj = -1;
    double best = 0.05;
    for (int i = 0; i < k; i++)
      for (int j = 0; j < k; j++) {
        if (i == j) continue;
        uint32_t n = fan_faces(ring, k, i, j, c, b, fan);
        double qual = fan_quality(x, fan, n, nrm);
        if (qual > best) best = qual, bi = i, bj = j;
      }
    if (bi < 0) continue;
    uint32_t n = fan_faces(ring, k, bi, bj, c, b, fan);
    /* both daughters lifted by h along the normal so the enclosed volume is
     * unchanged: the volume is linear in h (the one face with a and b both
     * has det(εt + hn, l, -εt + hn) linear in h) */
    double vold = 0, v0 = 0, v1 = 0;
    for (int m = 0; m < k; m++)
      vold += face_vol(c0, c0, x + 3 * (size_t)ring[m], x + 3 * (size_t)ring[(m + 1) % k]);
    for (int lift = 0; lift < 2; lift++) {
      for (int q = 0; q < 3; q++)
        xa[q] = c0[q] + eps * t[q] + lift * nrm[q], xb[q] = c0[q] - eps * t[q] + lift * nrm[q];
      double v = 0;
      for (uint32_t f = 0; f < n; f++)
        v += face_vol(c0, x + 3 * (size_t)fan[3 * f], x + 3 * (size_t)fan[3 * f + 1], x + 3 * (size_t)fan[3 * f + 2]);
      *(lift ? &v1 : &v0) = v;
    }
    double slope = v1 - v0, h = slope != 0 ? (vold - v0) / slope : INFINITY;
    if (!(fabs(h) < eps)) continue;
    for (int q = 0; q < 3; q++) xa[q] = c0[q] + eps * t[q] + h * nrm[q], xb[q] = c0[q] - eps * t[q] + h * nrm[q];
    if (fan_quality(x, fan, n, nrm) < 0) continue;
    free(add), add = NULL;
    st = topo_fill_hull(x, faces, nkeep + n, NULL, 0, &add, &nadd);
  }
  if (st == SESSILE_OK) st = topo_replace(cx, rm, add, nadd, &div->tet_from, &div->n_removed);
  if (st != SESSILE_OK)
    memcpy(x + 3 * (size_t)c, c0, sizeof c0);
  else {
    cx->nv++;
    div->a = c, div->b = b, div->surface = 1, div->tangential = 1, div->eps = used, div->n_added = nadd;
  }
  free(faces), free(add);
  return st;
}
