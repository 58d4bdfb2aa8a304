// Shared GLSL of the growth kernels: box point location (mirrors
// sessile_box_locate in host/include/sessile/mesh/box.h exactly), the counter-based hash (mirrors sessile_growth_hash) and a
// double-precision pow (GLSL's pow/exp/log are float-only).
#ifndef GROWTH_COMMON_GLSL
#define GROWTH_COMMON_GLSL
// Push block, bindings and the parameter slots P_*: shaders/growth/kernels.def.
#include "growth_kernels.glsl"

// The 4 nodes and barycentric weights of the Kuhn tet holding p (clamped
// into the box), operation by operation as in sessile_box_locate.
void box_locate(REAL p[3], out uint nodes[4], out REAL w[4]) {
  uint n[3] = uint[3](pc.n0, pc.n1, pc.n2);
  REAL o[3] = REAL[3](gp[P_OX], gp[P_OY], gp[P_OZ]);
  uint c[3];
  REAL u[3];
  for (int a = 0; a < 3; a++) {
    precise REAL x = (p[a] - o[a]) / gp[P_H];
    REAL cells = REAL(n[a] - 1u);
    if (!(x > REAL(0))) x = REAL(0);
    if (x > cells) x = cells;
    REAL f = floor(x);
    if (f > cells - REAL(1)) f = cells - REAL(1);
    c[a] = uint(f);
    u[a] = x - f;
  }
  int ord[3] = int[3](0, 1, 2);
  for (int s = 0; s < 2; s++)
    for (int q = 0; q < 2 - s; q++)
      if (u[ord[q + 1]] > u[ord[q]]) {
        int t = ord[q];
        ord[q] = ord[q + 1];
        ord[q + 1] = t;
      }
  nodes[0] = c[0] + pc.n0 * (c[1] + pc.n1 * c[2]);
  w[0] = REAL(1) - u[ord[0]];
  for (int s = 0; s < 3; s++) {
    c[ord[s]]++;
    nodes[s + 1] = c[0] + pc.n0 * (c[1] + pc.n1 * c[2]);
    w[s + 1] = u[ord[s]] - (s < 2 ? u[ord[s + 1]] : REAL(0));
  }
}

// lowbias32 and the hash of (seed, iteration, vertex, component).
uint mix32(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}
uint growth_hash(uint vertex, uint component) {
  uint h = mix32(component + 0x9e3779b9u);
  h = mix32(h ^ vertex);
  h = mix32(h ^ pc.iteration);
  h = mix32(h ^ pc.seed_hi);
  return mix32(h ^ pc.seed_lo);
}
// Uniform in [0, 1) with 24 bits: exact in float and double.
REAL growth_uniform(uint vertex, uint component) {
  return REAL(growth_hash(vertex, component) >> 8) * REAL(5.9604644775390625e-8);
}

#if SESSILE_F64
// log and exp in double: log by atanh series on the mantissa in
// [sqrt(1/2), sqrt(2)) (|s| < 0.172, 12 terms: error < 1e-19), exp by
// Cody-Waite reduction to |r| <= ln2/2 and Taylor to degree 17 (< 1e-24).
const double LN2_HI = 6.93147180369123816490e-01LF;
const double LN2_LO = 1.90821492927058770002e-10LF;
double dlog(double x) {
  int e;
  double m = frexp(x, e);
  if (m < 0.70710678118654752440LF) {
    m *= 2.0LF;
    e -= 1;
  }
  double s = (m - 1.0LF) / (m + 1.0LF), s2 = s * s;
  double p = 1.0LF / 23.0LF;
  for (int j = 21; j >= 1; j -= 2) p = p * s2 + 1.0LF / double(j);
  double de = double(e);
  return de * LN2_HI + (de * LN2_LO + 2.0LF * s * p);
}
double dexp(double y) {
  double k = floor(y * 1.44269504088896340736LF + 0.5LF);
  double r = (y - k * LN2_HI) - k * LN2_LO;
  double p = 1.0LF;
  for (int j = 17; j >= 1; j--) p = 1.0LF + p * r / double(j);
  return ldexp(p, int(k));
}
REAL real_pow(REAL x, REAL n) { return dexp(n * dlog(x)); }
#else
REAL real_pow(REAL x, REAL n) { return pow(x, n); }
#endif

#endif
