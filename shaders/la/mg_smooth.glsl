// One damped-Jacobi sweep of the cut-cell operator (stencil7_cut.glsl), for
// mg_smooth*.comp: y = x + omega (b - A x) / (h diag) on free nodes, y = b on
// Dirichlet nodes (their rows are the identity, so that is exact, and the
// residual there stays zero).  MG_ZERO: x = 0, y = omega b / (h diag), x unread.
#define CUT_TEXEL 1
#include "stencil7_cut.glsl"

REAL mg_sweep(uint node) {
  REAL bn = texel_real(b_t, node);
  if (ct_mask(node) != 0u) return bn;
  REAL d = ct_diag(node);
  if ((pc.flags & MG_ZERO) != 0u) return pc.omega * bn / (pc.h * d);
  REAL xc = ct_x(node);
  REAL ax = pc.h * (d * xc - ct_sum(node, grid_ijk(node)));
  return xc + pc.omega * (bn - ax) / (pc.h * d);
}
