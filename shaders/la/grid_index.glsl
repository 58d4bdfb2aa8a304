// Node index -> (i, j, k) on an n0 x n1 x n2 grid (node i + n0 (j + n1 k))
// without integer division: lavapipe has no vector divide and would divide
// lane by lane.  Push fields: n0, n1, m0 = 0xffffffff / n0, m1 = 0xffffffff / n1.

// a / d as the multiply-high by m = 0xffffffff / d, exact after one correction
// (the estimate is the quotient or one less).
uint grid_div(uint a, uint d, uint m) {
  uint q, lo;
  umulExtended(a, m, q, lo);
  return a - q * d >= d ? q + 1u : q;
}

uvec3 grid_ijk(uint node) {
  uint t = grid_div(node, pc.n0, pc.m0), k = grid_div(t, pc.n1, pc.m1);
  return uvec3(node - t * pc.n0, t - k * pc.n1, k);
}
