// Shared by the weld kernels that read capsules (weld_sdf, weld_vert): the
// round cone's signed distance and the smooth union, operation by operation
// as host/mesh/weld_grid.c (weld_capsule_sdf, weld_smin), so the fp64 build
// gives the host reference's bits.  `precise` forbids fused multiply-adds.

// Signed distance from p to capsule c: the convex hull of the spheres
// (a, ra) and (b, rb).  In the meridian plane (y along the axis, x >= 0 off
// it) the side is the line tangent to both circles; s is the coordinate
// along that line, 0 at its contact with sphere a and L cos at sphere b.
REAL capsule_sdf(uint c, REAL px, REAL py, REAL pz) {
  uint o = c * uint(WC_STRIDE);
  precise REAL pa0 = px - cap[o + 0u], pa1 = py - cap[o + 1u], pa2 = pz - cap[o + 2u];
  REAL u0 = cap[o + 4u], u1 = cap[o + 5u], u2 = cap[o + 6u];
  precise REAL y = pa0 * u0 + pa1 * u1 + pa2 * u2;
  precise REAL r0 = pa0 - y * u0, r1 = pa1 - y * u1, r2 = pa2 - y * u2;
  precise REAL x = sqrt(r0 * r0 + r1 * r1 + r2 * r2);
  REAL sn = cap[o + uint(WC_SIN)], cs = cap[o + uint(WC_COS)];
  precise REAL s = y * cs - x * sn;
  precise REAL d;
  if (s < REAL(0)) {
    d = sqrt(pa0 * pa0 + pa1 * pa1 + pa2 * pa2) - cap[o + uint(WC_RA)];
  } else if (s > cap[o + uint(WC_L)] * cs) {
    precise REAL pb0 = px - cap[o + 8u], pb1 = py - cap[o + 9u], pb2 = pz - cap[o + 10u];
    d = sqrt(pb0 * pb0 + pb1 * pb1 + pb2 * pb2) - cap[o + uint(WC_RB)];
  } else {
    d = y * sn + x * cs - cap[o + uint(WC_RA)];
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

uint brick_of(uint x, uint y, uint z) {
  return x / pc.brick + pc.bx * (y / pc.brick + pc.by * (z / pc.brick));
}
