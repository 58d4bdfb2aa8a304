/* Triangle-triangle intersection (closed triangles, double precision) from
 * orientation predicates only: no intersection points are computed, so the
 * only rounding is in the signs.  Each sign is trusted beyond Shewchuk's
 * static error bound and read as 0 below it; every test is closed (0 counts
 * as touching), so an uncertain sign can only add a pair that lies within
 * rounding of touching, never lose one; except the shared-edge fold, which
 * needs strict sides (docs/intersection.md).
 *
 * Two non-coplanar triangles meet exactly when an edge of one meets the
 * other (their common points lie on the planes' line; an end of that
 * segment is on an edge of one of them).  Coplanar ones are tested in 2D,
 * projected along their normal's largest component.  Shared vertices (by id)
 * are no intersection: with one shared, the opposite edge of each is tested
 * against the other (complete: the rest of each triangle's intersection is a
 * segment from the shared point ending on that edge); with a shared edge,
 * only a coplanar fold can add anything. */
#include <math.h>
#include "mesh/intersect_internal.h"

/* Shewchuk, "Adaptive precision floating-point arithmetic and fast robust
 * geometric predicates" (1997): eps = 2^-53, errboundA of each determinant. */
#define EPS 0x1p-53
static const double O3D_BOUND = (7.0 + 56.0 * EPS) * EPS;
static const double O2D_BOUND = (3.0 + 16.0 * EPS) * EPS;

/* Beyond the bound but within NEAR of it: a sign that is right but whose
 * point lies within rounding, times NEAR, of the plane (docs/intersection.md). */
#define NEAR 0x1p20

/* Sign of det[a - d; b - d; c - d] (Shewchuk's orient3d order of operations):
 * 0 below the error bound, +-1 within NEAR times it, +-2 beyond. */
static int orient3d(const double *a, const double *b, const double *c, const double *d) {
  double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
  double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
  double adz = a[2] - d[2], bdz = b[2] - d[2], cdz = c[2] - d[2];
  double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  double cdxady = cdx * ady, adxcdy = adx * cdy;
  double adxbdy = adx * bdy, bdxady = bdx * ady;
  double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  double perm = (fabs(bdxcdy) + fabs(cdxbdy)) * fabs(adz) + (fabs(cdxady) + fabs(adxcdy)) * fabs(bdz) +
                (fabs(adxbdy) + fabs(bdxady)) * fabs(cdz);
  double bound = O3D_BOUND * perm;
  if (!(fabs(det) > bound)) return 0;
  return (det > 0 ? 1 : -1) * (fabs(det) > NEAR * bound ? 2 : 1);
}

static int orient2d(const double *a, const double *b, const double *c) {
  double l = (a[0] - c[0]) * (b[1] - c[1]), r = (a[1] - c[1]) * (b[0] - c[0]);
  double det = l - r, bound = O2D_BOUND * (fabs(l) + fabs(r));
  return det > bound ? 1 : det < -bound ? -1 : 0;
}

/* --- 2D (coplanar) --------------------------------------------------------- */

/* The axis to drop: the largest component of t's normal (a degenerate t
 * gives axis 0: its tests are then only as good as that projection). */
static int drop_axis(const double *t) {
  double u[3], v[3], n[3];
  for (int k = 0; k < 3; k++) u[k] = t[3 + k] - t[k], v[k] = t[6 + k] - t[k];
  n[0] = fabs(u[1] * v[2] - u[2] * v[1]);
  n[1] = fabs(u[2] * v[0] - u[0] * v[2]);
  n[2] = fabs(u[0] * v[1] - u[1] * v[0]);
  return n[0] >= n[1] && n[0] >= n[2] ? 0 : n[1] >= n[2] ? 1 : 2;
}

static void proj(const double *p, int ax, double out[2]) {
  out[0] = p[(ax + 1) % 3];
  out[1] = p[(ax + 2) % 3];
}

/* p within the closed box of segment ab (p is known to be on its line). */
static int in_span(const double *a, const double *b, const double *p) {
  return fmin(a[0], b[0]) <= p[0] && p[0] <= fmax(a[0], b[0]) && fmin(a[1], b[1]) <= p[1] &&
         p[1] <= fmax(a[1], b[1]);
}

static int seg_seg2(const double *a, const double *b, const double *c, const double *d) {
  int o1 = orient2d(a, b, c), o2 = orient2d(a, b, d), o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return 1;
  return (!o1 && in_span(a, b, c)) || (!o2 && in_span(a, b, d)) || (!o3 && in_span(c, d, a)) ||
         (!o4 && in_span(c, d, b));
}

/* p in the closed triangle t (either orientation). */
static int in_tri2(double t[3][2], const double *p) {
  int d0 = orient2d(t[0], t[1], p), d1 = orient2d(t[1], t[2], p), d2 = orient2d(t[2], t[0], p);
  return (d0 >= 0 && d1 >= 0 && d2 >= 0) || (d0 <= 0 && d1 <= 0 && d2 <= 0);
}

static int seg_tri2(const double *a3, const double *b3, const double *t3, int ax) {
  double a[2], b[2], t[3][2];
  proj(a3, ax, a), proj(b3, ax, b);
  for (int i = 0; i < 3; i++) proj(t3 + 3 * i, ax, t[i]);
  if (in_tri2(t, a)) return 1;
  for (int e = 0; e < 3; e++)
    if (seg_seg2(a, b, t[e], t[(e + 1) % 3])) return 1;
  return 0;
}

static int tri_tri2(const double *p3, const double *q3) {
  int ax = drop_axis(p3);
  double p[3][2], q[3][2];
  for (int i = 0; i < 3; i++) proj(p3 + 3 * i, ax, p[i]), proj(q3 + 3 * i, ax, q[i]);
  for (int e = 0; e < 3; e++)
    for (int f = 0; f < 3; f++)
      if (seg_seg2(p[e], p[(e + 1) % 3], q[f], q[(f + 1) % 3])) return 1;
  return in_tri2(q, p[0]) || in_tri2(p, q[0]);
}

/* --- 3D -------------------------------------------------------------------- */

/* Closed segment ab against closed triangle t; sa, sb: the sides of a and b
 * (orient3d(t0, t1, t2, .)). */
static int seg_tri(const double *a, const double *b, int sa, int sb, const double *t) {
  if (sa * sb > 0) return 0;
  /* Both ends on t's plane or within rounding (times NEAR) of it: the line
   * below is then nearly parallel to the plane and its signs say nothing
   * reliable about where it meets it (side-by-side split triangles in one
   * plane came out crossing): test the segment in the plane. */
  if (sa > -2 && sa < 2 && sb > -2 && sb < 2) return seg_tri2(a, b, t, drop_axis(t));
  /* The line ab crosses the plane (at a, at b, or between): inside the
   * triangle when it passes every edge on the same side. */
  int s0 = orient3d(a, b, t, t + 3), s1 = orient3d(a, b, t + 3, t + 6), s2 = orient3d(a, b, t + 6, t);
  /* All three 0: the line lies in t's plane as far as these signs can tell. */
  if (!s0 && !s1 && !s2) return seg_tri2(a, b, t, drop_axis(t));
  return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
}

static int same_strict(const int d[3]) {
  return (d[0] > 0 && d[1] > 0 && d[2] > 0) || (d[0] < 0 && d[1] < 0 && d[2] < 0);
}

static int general(const double *p, const double *q) {
  int dq[3], dp[3];
  for (int i = 0; i < 3; i++) dq[i] = orient3d(p, p + 3, p + 6, q + 3 * i);
  if (same_strict(dq)) return 0;
  for (int i = 0; i < 3; i++) dp[i] = orient3d(q, q + 3, q + 6, p + 3 * i);
  if (same_strict(dp)) return 0;
  if ((!dq[0] && !dq[1] && !dq[2]) || (!dp[0] && !dp[1] && !dp[2])) return tri_tri2(p, q);
  for (int e = 0; e < 3; e++) {
    int f = (e + 1) % 3;
    if (seg_tri(p + 3 * e, p + 3 * f, dp[e], dp[f], q)) return 1;
    if (seg_tri(q + 3 * e, q + 3 * f, dq[e], dq[f], p)) return 1;
  }
  return 0;
}

/* One shared vertex: p = (s, a, b) and q = (s, c, d) after rotation.  When
 * a and b lie strictly on one side of q's plane, p meets that plane in s
 * alone: nothing more to test (the usual case, two orientations). */
static int share_vertex(const double *p, int i, const double *q, int j) {
  const double *a = p + 3 * ((i + 1) % 3), *b = p + 3 * ((i + 2) % 3);
  const double *c = q + 3 * ((j + 1) % 3), *d = q + 3 * ((j + 2) % 3);
  int sa = orient3d(q, q + 3, q + 6, a), sb = orient3d(q, q + 3, q + 6, b);
  if (sa * sb > 0) return 0;
  int sc = orient3d(p, p + 3, p + 6, c), sd = orient3d(p, p + 3, p + 6, d);
  if (sc * sd > 0) return 0;
  return seg_tri(a, b, sa, sb, q) || seg_tri(c, d, sc, sd, p);
}

/* Shared edge: p's corners other than i are the edge, q's corner j is off it.
 * Only a coplanar fold (both third corners on one side) intersects. */
static int share_edge(const double *p, int i, const double *q, int j) {
  const double *a = p + 3 * ((i + 1) % 3), *b = p + 3 * ((i + 2) % 3), *c = p + 3 * i;
  const double *d = q + 3 * j;
  if (orient3d(a, b, c, d)) return 0;
  int ax = drop_axis(p);
  double a2[2], b2[2], c2[2], d2[2];
  proj(a, ax, a2), proj(b, ax, b2), proj(c, ax, c2), proj(d, ax, d2);
  return orient2d(a2, b2, c2) * orient2d(a2, b2, d2) > 0;
}

int isect_tri_tri(const double *p, const uint32_t *vp, const double *q, const uint32_t *vq) {
  int mate[3] = {-1, -1, -1}, k = 0;
  if (vp && vq)
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        if (vp[i] == vq[j]) mate[i] = j, k++;
  if (k == 0) return general(p, q);
  if (k >= 3) return 1; /* the same triangle twice */
  if (k == 1) {
    int i = mate[0] >= 0 ? 0 : mate[1] >= 0 ? 1 : 2;
    return share_vertex(p, i, q, mate[i]);
  }
  int i = mate[0] < 0 ? 0 : mate[1] < 0 ? 1 : 2, used = 0;
  for (int m = 0; m < 3; m++)
    if (mate[m] >= 0) used |= 1 << mate[m];
  int j = !(used & 1) ? 0 : !(used & 2) ? 1 : 2;
  return share_edge(p, i, q, j);
}

int sessile_triangles_intersect(const double a[9], const uint32_t va[3], const double b[9],
                                const uint32_t vb[3]) {
  static const uint32_t loc[3] = {0, 1, 2};
  double ba[6], bb[6];
  isect_tri_box(a, loc, ba);
  isect_tri_box(b, loc, bb);
  if (!isect_box_overlap(ba, bb)) return 0;
  return isect_tri_tri(a, va, b, vb);
}
