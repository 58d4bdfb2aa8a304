// The cut-cell 7-point operator of host/la/stencil_cut.c (la.h defines it),
// shared by its kernels (stencil7_cut*.comp) and the multigrid's (mg_*.comp).
// Node (i,j,k) of an n0 x n1 x n2 grid has index i + n0 (j + n1 k).  A node
// with mask != 0 is a Dirichlet node (identity row and column); for a free one
//   (A x)_n = h (diag_n x_n - sum over free existing neighbours m of f_nm x_m),
// f_nm = product over the two axes other than the edge's of 1/2 on the grid's
// boundary in that axis, else 1 (the zero-flux walls' half and quarter faces).
// The includer sets CUT_TEXEL: 0 reads mask, diag and x from storage buffers,
// 1 from the uniform texel buffers mask_t, diag_t, x_t (lavapipe gathers texels
// with vector loads; docs/la.md).  Push fields: n0, n1, n2, m0, m1, xoff, h.
// CUT_ADV 1 (texel reads only): each free neighbour's term carries the weight
// coef[6 n + d] (d = 0..5: -x, +x, -y, +y, -z, +z), the advective operator of
// host/la/stencil_cut_adv.c.
#include "la_kernels.glsl"
#include "grid_index.glsl"

#if CUT_TEXEL
#include "texel_real.glsl"
uint ct_mask(uint i) { return texelFetch(mask_t, int(i)).x; }
REAL ct_x(uint i) { return texel_real(x_t, pc.xoff + i); }
REAL ct_diag(uint i) { return texel_real(diag_t, i); }
#else
uint ct_mask(uint i) { return mask[i]; }
REAL ct_x(uint i) { return x[pc.xoff + i]; }
REAL ct_diag(uint i) { return diag[i]; }
#endif

#ifndef CUT_ADV
#define CUT_ADV 0
#endif
#if CUT_ADV
REAL ct_w(uint n, uint d) { return texel_real(coef_t, 6u * n + d); }
#define CT_W(n, d) ct_w(n, d) *
#else
#define CT_W(n, d)
#endif

// x_m when neighbour m exists (ok) and is free, else 0.  Both reads happen
// anyway (a missing neighbour reads the node itself) so the lanes stay in step.
REAL ct_nb(bool ok, uint node, uint m) {
  uint a = ok ? m : node;
  REAL v = ct_x(a);
  return ok && ct_mask(a) == 0u ? v : REAL(0);
}

// sum of f_nm x_m over the free neighbours of node n at p.
REAL ct_sum(uint n, uvec3 p) {
  uint s1 = pc.n0, s2 = pc.n0 * pc.n1;
  REAL bx = p.x == 0u || p.x == pc.n0 - 1u ? REAL(0.5) : REAL(1);
  REAL by = p.y == 0u || p.y == pc.n1 - 1u ? REAL(0.5) : REAL(1);
  REAL bz = p.z == 0u || p.z == pc.n2 - 1u ? REAL(0.5) : REAL(1);
  REAL sx = CT_W(n, 0u) ct_nb(p.x > 0u, n, n - 1u) + CT_W(n, 1u) ct_nb(p.x + 1u < pc.n0, n, n + 1u);
  REAL sy = CT_W(n, 2u) ct_nb(p.y > 0u, n, n - s1) + CT_W(n, 3u) ct_nb(p.y + 1u < pc.n1, n, n + s1);
  REAL sz = CT_W(n, 4u) ct_nb(p.z > 0u, n, n - s2) + CT_W(n, 5u) ct_nb(p.z + 1u < pc.n2, n, n + s2);
  return by * bz * sx + bx * bz * sy + bx * by * sz;
}

// (A x)_node.
REAL ct_apply(uint node) {
  REAL xc = ct_x(node);
  if (ct_mask(node) != 0u) return xc;
  return pc.h * (ct_diag(node) * xc - ct_sum(node, grid_ijk(node)));
}
