// Contacts of a cell (docs/sds.md, "Collisions"): the spatial hash of
// Teschner et al. 2003 (a grid cell (i, j, k) goes to bucket
// (i p1 xor j p2 xor k p3) mod T), the closest point on a triangle, and the
// penalty of a cell against its nearest triangle.  Mirrors host/sds/sds_hash.c
// operation by operation.
#ifndef SDS_CONTACT_GLSL
#define SDS_CONTACT_GLSL

REAL dot3(REAL a[3], REAL b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Grid coordinate of v at cell size h, clamped so that a blown-up state
// cannot overflow the integer (as sds_grid_coord).
int grid_coord(REAL v, REAL h) {
  REAL q = floor(v / h);
  q = clamp(q, REAL(-1073741824), REAL(1073741824));
  return int(q);
}
uint grid_hash(int i, int j, int k, uint T) {
  return ((uint(i) * SDS_P1) ^ (uint(j) * SDS_P2) ^ (uint(k) * SDS_P3)) % T;
}

// Closest point to p on triangle (a, b, c) (Ericson §5.1.5), as closest_on_tri.
// Regions: 0 face, 1-3 vertices a, b, c, 4 edge ab, 5 edge ac, 6 edge bc
// (host/sds/sds_internal.h, SDS_REGION_*).
int closest_on_tri(REAL p[3], REAL a[3], REAL b[3], REAL c[3], out REAL q[3]) {
  REAL ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int i = 0; i < 3; i++) ab[i] = b[i] - a[i], ac[i] = c[i] - a[i], ap[i] = p[i] - a[i];
  REAL d1 = dot3(ab, ap), d2 = dot3(ac, ap);
  if (d1 <= REAL(0) && d2 <= REAL(0)) { q = a; return 1; }
  for (int i = 0; i < 3; i++) bp[i] = p[i] - b[i];
  REAL d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  if (d3 >= REAL(0) && d4 <= d3) { q = b; return 2; }
  REAL vc = d1 * d4 - d3 * d2;
  if (vc <= REAL(0) && d1 >= REAL(0) && d3 <= REAL(0)) {
    REAL v = d1 / (d1 - d3);
    for (int i = 0; i < 3; i++) q[i] = a[i] + v * ab[i];
    return 4;
  }
  for (int i = 0; i < 3; i++) cp[i] = p[i] - c[i];
  REAL d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  if (d6 >= REAL(0) && d5 <= d6) { q = c; return 3; }
  REAL vb = d5 * d2 - d1 * d6;
  if (vb <= REAL(0) && d2 >= REAL(0) && d6 <= REAL(0)) {
    REAL w = d2 / (d2 - d6);
    for (int i = 0; i < 3; i++) q[i] = a[i] + w * ac[i];
    return 5;
  }
  REAL va = d3 * d6 - d5 * d4;
  if (va <= REAL(0) && (d4 - d3) >= REAL(0) && (d5 - d6) >= REAL(0)) {
    REAL w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    for (int i = 0; i < 3; i++) q[i] = b[i] + w * (c[i] - b[i]);
    return 6;
  }
  REAL den = REAL(1) / (va + vb + vc), v = vb * den, w = vc * den;
  for (int i = 0; i < 3; i++) q[i] = a[i] + ab[i] * v + ac[i] * w;
  return 0;
}

// Squared distance from p to triangle (a, b, c).
REAL tri_dist2(REAL p[3], REAL a[3], REAL b[3], REAL c[3]) {
  REAL q[3];
  closest_on_tri(p, a, b, c, q);
  REAL d[3] = REAL[3](p[0] - q[0], p[1] - q[1], p[2] - q[2]);
  return dot3(d, d);
}

// The distance s of a cell at p from its nearest triangle (a, b, c) and
// the unit direction w of the push: with has_nrm (the obstacle) the
// distance is signed by the pseudo-normal of the closest point's region,
// nrm[3 region] (negative inside, the push pointing out); without (the
// organism's surface) it is unsigned, the push away from the closest point.
// As contact_dist (host/sds/sds_hash.c).
REAL contact_geom(REAL p[3], REAL a[3], REAL b[3], REAL c[3], bool has_nrm, REAL nrm[21], out REAL w[3]) {
  REAL q[3], e1[3], e2[3], n[3], d[3];
  int region = closest_on_tri(p, a, b, c, q);
  for (int i = 0; i < 3; i++) d[i] = p[i] - q[i], e1[i] = b[i] - a[i], e2[i] = c[i] - a[i];
  n[0] = e1[1] * e2[2] - e1[2] * e2[1];
  n[1] = e1[2] * e2[0] - e1[0] * e2[2];
  n[2] = e1[0] * e2[1] - e1[1] * e2[0];
  // Within 2^-30 of the triangle's size of it (a cell on the face, say)
  // p - q is rounding noise, whose direction a GPU's FMA contraction and the
  // host's separate roundings pick differently: the push takes the face's
  // normal there, as at dd = 0.  2^-30 is exact as a float literal.  In
  // fp32 the noise is float's, about 2^-23 of the coordinates: the tie
  // reaches 2^-16 of the triangle's size or of the cell's largest
  // coordinate, whichever is larger (test_sds_collide --fp32).
  REAL ln = sqrt(dot3(n, n)), dd = sqrt(dot3(d, d)), s;
#if SESSILE_F64
  REAL tie = REAL(9.313225746154785e-10) * sqrt(ln);
#else
  REAL tie = REAL(1.52587890625e-05) * max(sqrt(ln), max(max(abs(p[0]), abs(p[1])), abs(p[2])));
#endif
  if (dd > tie) {
    REAL sg = REAL(1);
    if (has_nrm) {
      REAL pn[3] = REAL[3](nrm[3 * region], nrm[3 * region + 1], nrm[3 * region + 2]);
      if (dot3(d, pn) < REAL(0)) sg = REAL(-1);
    }
    for (int i = 0; i < 3; i++) w[i] = sg * d[i] / dd;
    s = sg * dd;
  } else {
    for (int i = 0; i < 3; i++) w[i] = n[i] / ln;
    s = REAL(0);
  }
  return s;
}

// The penalty of a cell at p whose nearest triangle is (a, b, c):
// acceleration k (delta - s) w.  As sessile_sds_contact_accel.
void contact_add(REAL p[3], REAL a[3], REAL b[3], REAL c[3], REAL delta, REAL k, bool has_nrm, REAL nrm[21],
                 inout REAL acc[3]) {
  REAL w[3];
  REAL s = contact_geom(p, a, b, c, has_nrm, nrm, w);
  for (int i = 0; i < 3; i++) acc[i] += k * (delta - s) * w[i];
}
#endif
