/* The inversion time of a tet under linear motion (§3.1.2, the cubic) and
 * its case (Figure 3). */
#include <math.h>
#include <string.h>
#include "topo_internal.h"

static double poly(const double c[4], double s) { return ((c[3] * s + c[2]) * s + c[1]) * s + c[0]; }
static int sgn(double v) { return (v > 0) - (v < 0); }

/* Root of p on [a, b] where sgn p(a) = -sgn p(b) != 0: bisection until the
 * interval cannot shrink (about 60 halvings; exact sign of the evaluated p). */
static double bisect(const double c[4], double a, double b) {
  int sa = sgn(poly(c, a));
  for (int it = 0; it < 200; it++) {
    double m = 0.5 * (a + b);
    if (m <= a || m >= b) break;
    int sm = sgn(poly(c, m));
    if (sm == 0) return m;
    if (sm == sa)
      a = m;
    else
      b = m;
  }
  return 0.5 * (a + b);
}

int sessile_sds_topo_cubic_root(const double c[4], double *s) {
  /* Breakpoints: 0, the real roots of p' = c1 + 2 c2 s + 3 c3 s^2 in (0, 1), 1. */
  double br[4];
  int nb = 0;
  br[nb++] = 0.0;
  double A = 3 * c[3], B = 2 * c[2], C = c[1];
  double r[2];
  int nr = 0;
  double scale = fabs(A) + fabs(B) + fabs(C);
  if (scale > 0) {
    if (fabs(A) <= 1e-300 || fabs(A) < 1e-14 * scale) {
      if (B != 0) r[nr++] = -C / B;
    } else {
      double disc = B * B - 4 * A * C;
      if (disc >= 0) {
        /* the stable pair of quadratic roots */
        double q = -0.5 * (B + copysign(sqrt(disc), B));
        if (q != 0)
          r[nr++] = q / A, r[nr++] = C / q;
        else
          r[nr++] = 0.0;
      }
    }
  }
  if (nr == 2 && r[0] > r[1]) {
    double t = r[0];
    r[0] = r[1], r[1] = t;
  }
  for (int i = 0; i < nr; i++)
    if (r[i] > 0 && r[i] < 1) br[nb++] = r[i];
  br[nb++] = 1.0;
  for (int i = 0; i + 1 < nb; i++) {
    double a = br[i], b = br[i + 1];
    double pa = poly(c, a), pb = poly(c, b);
    if (pa == 0) {
      *s = a;
      return 1;
    }
    if (sgn(pa) != sgn(pb)) {
      *s = pb == 0 ? b : bisect(c, a, b);
      return 1;
    }
  }
  return 0;
}

static double det3(const double *a, const double *b, const double *c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}
static void cross(const double *a, const double *b, double *o) {
  o[0] = a[1] * b[2] - a[2] * b[1], o[1] = a[2] * b[0] - a[0] * b[2], o[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Signed doubled area of (a, b, c) projected along n. */
static double area_n(const double *a, const double *b, const double *c, const double *n) {
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; k++) u[k] = b[k] - a[k], v[k] = c[k] - a[k];
  cross(u, v, w);
  return dot(w, n);
}

int sessile_sds_topo_inversion_time(const double p[12], const double q[12], double u1, double u2,
                                    sessile_sds_topo_inversion *inv) {
  /* vol(s) ∝ det(A + s dA, B + s dB, C + s dC) with A = p1 - p0 etc. */
  double A[3][3], D[3][3];
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++) {
      A[i][k] = p[3 * (i + 1) + k] - p[k];
      D[i][k] = (q[3 * (i + 1) + k] - p[3 * (i + 1) + k]) - (q[k] - p[k]);
    }
  double c[4];
  c[0] = det3(A[0], A[1], A[2]);
  c[1] = det3(D[0], A[1], A[2]) + det3(A[0], D[1], A[2]) + det3(A[0], A[1], D[2]);
  c[2] = det3(D[0], D[1], A[2]) + det3(D[0], A[1], D[2]) + det3(A[0], D[1], D[2]);
  c[3] = det3(D[0], D[1], D[2]);
  double s;
  if (!sessile_sds_topo_cubic_root(c, &s)) return 0;
  memset(inv, 0, sizeof *inv);
  inv->s = s;
  inv->u = u1 + s * (u2 - u1);
  /* The flat configuration at s: classify in its plane. */
  double x[4][3];
  for (int i = 0; i < 4; i++)
    for (int k = 0; k < 3; k++) x[i][k] = p[3 * i + k] + s * (q[3 * i + k] - p[3 * i + k]);
  /* plane normal: the largest of the four face normals */
  double n[3] = {0, 0, 0}, best = -1;
  for (int f = 0; f < 4; f++) {
    const int *fo = topo_face_of[f];
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; k++) u[k] = x[fo[1]][k] - x[fo[0]][k], v[k] = x[fo[2]][k] - x[fo[0]][k];
    cross(u, v, w);
    if (dot(w, w) > best) best = dot(w, w), memcpy(n, w, sizeof n);
  }
  /* case 1: vertex i inside the triangle of the other three (barycentric
   * areas all of the triangle's sign); the most interior one wins */
  double score = -INFINITY;
  int vbest = -1;
  for (int i = 0; i < 4; i++) {
    const int *fo = topo_face_of[i];
    const double *a = x[fo[0]], *b = x[fo[1]], *cc = x[fo[2]];
    double T = area_n(a, b, cc, n);
    if (T == 0) continue;
    double l0 = area_n(x[i], b, cc, n) / T, l1 = area_n(a, x[i], cc, n) / T, l2 = area_n(a, b, x[i], n) / T;
    double m = fmin(l0, fmin(l1, l2));
    if (m > score) score = m, vbest = i;
  }
  if (vbest >= 0 && score >= 0) {
    inv->kind = SESSILE_SDS_TOPO_VERTEX_FACE;
    inv->vertex = vbest;
    return 1;
  }
  /* case 2: the pair of opposite edges whose segments cross in the plane */
  static const int pairs[3][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}};
  double sc2 = -INFINITY;
  int pb = 0;
  for (int k = 0; k < 3; k++) {
    const double *a = x[pairs[k][0]], *b = x[pairs[k][1]], *e = x[pairs[k][2]], *f = x[pairs[k][3]];
    /* e, f on opposite sides of ab, and a, b on opposite sides of ef */
    double s1 = area_n(a, b, e, n) * area_n(a, b, f, n), s2 = area_n(e, f, a, n) * area_n(e, f, b, n);
    double m = fmin(-s1, -s2);
    if (m > sc2) sc2 = m, pb = k;
  }
  inv->kind = SESSILE_SDS_TOPO_EDGE_EDGE;
  inv->edge[0][0] = pairs[pb][0], inv->edge[0][1] = pairs[pb][1];
  inv->edge[1][0] = pairs[pb][2], inv->edge[1][1] = pairs[pb][3];
  return 1;
}
