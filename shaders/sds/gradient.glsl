// sessile_morph_gradient (host/sds/morph.c) on the device, operation for
// operation: the rules' `divide toward grad(...)` (rules_vm.glsl) and the
// oriented growth (axial_grad.comp).  The includer defines RV_X, RV_PHI,
// RV_OFF and RV_NBR (how it reads positions, amounts and the neighbour
// lists) and a push constant block pc with nmorph.
#ifndef SDS_GRADIENT_GLSL
#define SDS_GRADIENT_GLSL
REAL det3(REAL m00, REAL m01, REAL m02, REAL m10, REAL m11, REAL m12, REAL m20, REAL m21, REAL m22) {
  precise REAL d = m00 * (m11 * m22 - m12 * m21) - m01 * (m10 * m22 - m12 * m20) + m02 * (m10 * m21 - m11 * m20);
  return d;
}

// sessile_morph_gradient of morphogen k at cell c (least squares, else the
// fallback sum), in the host's order; false when it vanishes.
bool gradient(uint c, uint k, out REAL g0, out REAL g1, out REAL g2) {
  uint nm = pc.nmorph;
  precise REAL a00 = REAL(0), a01 = REAL(0), a02 = REAL(0), a11 = REAL(0), a12 = REAL(0), a22 = REAL(0);
  precise REAL b0 = REAL(0), b1 = REAL(0), b2 = REAL(0), f0 = REAL(0), f1 = REAL(0), f2 = REAL(0);
  REAL pcen = RV_PHI(c * nm + k);
  for (uint q = RV_OFF(c); q < RV_OFF(c + 1u); q++) {
    uint n = RV_NBR(q);
    precise REAL d0 = RV_X(3u * n) - RV_X(3u * c), d1 = RV_X(3u * n + 1u) - RV_X(3u * c + 1u),
                 d2 = RV_X(3u * n + 2u) - RV_X(3u * c + 2u);
    precise REAL dp = RV_PHI(n * nm + k) - pcen;
    precise REAL dd = REAL(0);
    dd += d0 * d0;
    dd += d1 * d1;
    dd += d2 * d2;
    b0 += d0 * dp, b1 += d1 * dp, b2 += d2 * dp;
    if (dd > REAL(0)) f0 += dp * d0 / dd, f1 += dp * d1 / dd, f2 += dp * d2 / dd;
    a00 += d0 * d0, a01 += d0 * d1, a02 += d0 * d2, a11 += d1 * d1, a12 += d1 * d2, a22 += d2 * d2;
  }
  // A is symmetric and the host sums A[s][a] and A[a][s] alike: the same values
  REAL det = det3(a00, a01, a02, a01, a11, a12, a02, a12, a22);
  precise REAL scale = a00 + a11 + a22;
  precise REAL tiny = REAL(1e-12) * scale * scale * scale;
  if (abs(det) > tiny) {
    g0 = det3(b0, a01, a02, b1, a11, a12, b2, a12, a22) / det;
    g1 = det3(a00, b0, a02, a01, b1, a12, a02, b2, a22) / det;
    g2 = det3(a00, a01, b0, a01, a11, b1, a02, a12, b2) / det;
  } else {
    g0 = f0, g1 = f1, g2 = f2;
  }
  return g0 != REAL(0) || g1 != REAL(0) || g2 != REAL(0);
}
#endif
