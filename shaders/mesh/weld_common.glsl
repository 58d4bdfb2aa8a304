// Shared by the weld kernels that read capsules (weld_sdf, weld_vert): the
// round cone's signed distance and the smooth union, operation by operation
// as host/mesh/weld_grid.c (weld_capsule_sdf, weld_smin), so the fp64 build
// gives the host reference's bits.  `precise` forbids fused multiply-adds.

// Signed distance from p to capsule c: the convex hull of the spheres
// (a, ra) and (b, rb).  In the meridian plane (y along the axis, x >= 0 off
// it) the side is the line tangent to both circles; s is the coordinate
// along that line, 0 at its contact with sphere a and L cos at sphere b.
REAL capsule_sdf(uint c, REAL px, REAL py, REAL pz) {
  uint o = c * uint(WC_STRIDE / 4);
  REAL4 ca = cap[o], cu = cap[o + 1u], cb = cap[o + 2u], cs4 = cap[o + 3u];
  precise REAL pa0 = px - ca.x, pa1 = py - ca.y, pa2 = pz - ca.z;
  precise REAL y = pa0 * cu.x + pa1 * cu.y + pa2 * cu.z;
  precise REAL r0 = pa0 - y * cu.x, r1 = pa1 - y * cu.y, r2 = pa2 - y * cu.z;
  precise REAL x = sqrt(r0 * r0 + r1 * r1 + r2 * r2);
  REAL sn = cs4.x, cs = cs4.y;
  precise REAL s = y * cs - x * sn;
  precise REAL d;
  if (s < REAL(0)) {
    d = sqrt(pa0 * pa0 + pa1 * pa1 + pa2 * pa2) - cu.w;
  } else if (s > ca.w * cs) {
    precise REAL pb0 = px - cb.x, pb1 = py - cb.y, pb2 = pz - cb.z;
    d = sqrt(pb0 * pb0 + pb1 * pb1 + pb2 * pb2) - cb.w;
  } else {
    d = y * sn + x * cs - cu.w;
  }
  return d;
}

// Polynomial smooth minimum of radius k (> 0): min(a, b) - h^2 k / 4 with
// h = max(k - |a - b|, 0) / k; exactly min(a, b) when |a - b| >= k.
REAL weld_smin(REAL a, REAL b, REAL k) {
  precise REAL hh = max(k - abs(a - b), REAL(0)) / k;
  precise REAL r = min(a, b) - hh * hh * k * REAL(0.25);
  return r;
}
