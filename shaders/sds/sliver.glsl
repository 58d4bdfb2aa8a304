// Lasting slivers in a batch (kernels.def, SL_*; docs/sds.md, "The loop on
// the device"): an inverted tet the host's loop would only count, because
// it is in the repair's backoff table, not yet due for a try, and began the
// step inverted (no root of its volume's cubic in the step, so no
// transformation).  The cubic's test is sessile_sds_topo_inversion_time's
// and sessile_sds_topo_cubic_root's without the bisection, operation for
// operation (precise: no fused multiply-adds), so that a step goes on here
// exactly when the host's loop would let it stand.  In fp32 no tet is quiet
// (the host's bits need fp64; the loop with the rules refuses fp32 anyway).
// Needs the bindings sl, xs, xe and topo (storage).

#if SESSILE_F64
REAL sl_det3(REAL a[3], REAL b[3], REAL c[3]) {
  precise REAL d = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                   a[2] * (b[0] * c[1] - b[1] * c[0]);
  return d;
}
REAL sl_poly(REAL c[4], REAL s) {
  precise REAL p = ((c[3] * s + c[2]) * s + c[1]) * s + c[0];
  return p;
}
int sl_sgn(REAL v) { return (v > REAL(0) ? 1 : 0) - (v < REAL(0) ? 1 : 0); }

// Has p(s) = c0 + c1 s + c2 s^2 + c3 s^3 a root in [0, 1]?  The host's
// breakpoints (0, the roots of p' inside, 1) and its sign tests.
bool sl_cubic_root(REAL c[4]) {
  REAL br[4];
  int nb = 0;
  br[nb++] = REAL(0);
  precise REAL A = REAL(3) * c[3], B = REAL(2) * c[2], C = c[1];
  REAL r[2];
  int nr = 0;
  precise REAL scale = abs(A) + abs(B) + abs(C);
  if (scale > REAL(0)) {
    if (abs(A) <= 1e-300lf || abs(A) < 1e-14lf * scale) {
      if (B != REAL(0)) {
        precise REAL q = -C / B;
        r[nr++] = q;
      }
    } else {
      precise REAL disc = B * B - REAL(4) * A * C;
      if (disc >= REAL(0)) {
        precise REAL sq = sqrt(disc);
        precise REAL q = -0.5lf * (B + ((unpackDouble2x32(B).y & 0x80000000u) != 0u ? -sq : sq)); // copysign
        if (q != REAL(0)) {
          precise REAL r0 = q / A, r1 = C / q;
          r[nr++] = r0, r[nr++] = r1;
        } else
          r[nr++] = REAL(0);
      }
    }
  }
  if (nr == 2 && r[0] > r[1]) {
    REAL w = r[0];
    r[0] = r[1], r[1] = w;
  }
  for (int i = 0; i < nr; i++)
    if (r[i] > REAL(0) && r[i] < REAL(1)) br[nb++] = r[i];
  br[nb++] = REAL(1);
  for (int i = 0; i + 1 < nb; i++) {
    REAL pa = sl_poly(c, br[i]), pb = sl_poly(c, br[i + 1]);
    if (pa == REAL(0) || sl_sgn(pa) != sl_sgn(pb)) return true;
  }
  return false;
}
#endif

// Is tet t, inverted after the batch's step j, a lasting sliver the step
// may keep?
bool sl_quiet(uint t, uint j) {
#if SESSILE_F64
  uint ns = sl[SL_COUNT];
  bool kept = false; // in the table, its try not due at step j
  for (uint e = 0u; e < ns; e++)
    if (sl[uint(SL_TAB) + 2u * e] == t && j < sl[uint(SL_TAB) + 2u * e + 1u]) kept = true;
  if (!kept) return false;
  uint v[4] = uint[4](topo[4u * t], topo[4u * t + 1u], topo[4u * t + 2u], topo[4u * t + 3u]);
  // vol(s) ∝ det(A + s D) over the step, linear motion (the host's A, D)
  REAL A[3][3], D[3][3];
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++) {
      precise REAL a = xs[3u * v[i + 1] + uint(k)] - xs[3u * v[0] + uint(k)];
      precise REAL d = (xe[3u * v[i + 1] + uint(k)] - xs[3u * v[i + 1] + uint(k)]) -
                       (xe[3u * v[0] + uint(k)] - xs[3u * v[0] + uint(k)]);
      A[i][k] = a, D[i][k] = d;
    }
  REAL c[4];
  c[0] = sl_det3(A[0], A[1], A[2]);
  precise REAL c1 = sl_det3(D[0], A[1], A[2]) + sl_det3(A[0], D[1], A[2]) + sl_det3(A[0], A[1], D[2]);
  precise REAL c2 = sl_det3(D[0], D[1], A[2]) + sl_det3(D[0], A[1], D[2]) + sl_det3(A[0], D[1], D[2]);
  c[1] = c1, c[2] = c2;
  c[3] = sl_det3(D[0], D[1], D[2]);
  for (int k = 0; k < 4; k++)
    if (!is_finite(c[k])) return false; // the host's loop decides
  return !sl_cubic_root(c);
#else
  return false;
#endif
}
