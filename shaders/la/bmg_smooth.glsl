// The body of bmg_smooth.comp and bmg_smooth_tex.comp (BMG_TEXEL 0 or 1).
// One block smoothing pass over one matrix row chunk:
//   y_n = x_n + omega Dinv_n (b - A x)_n
// for every node of the chunk (colour 8: block Jacobi, y another buffer) or
// for the nodes of one parity colour (block Gauss-Seidel: y = x, in place;
// nodes of one colour share no Kuhn tet, so none reads another's update).
// BMG_ZERO: x is zero and not read (the first sweep from zero).
#include "la_kernels.glsl"
#include "grid_index.glsl"
#define BMG_ROWS
#include "bmg_common.glsl"
#if BMG_TEXEL // b and the block inverses through texels as well
#define BMG_B(i) bmg_tex4(b_t, i)
#define BMG_DINV(i) bmg_tex4(dinv_t, i)
#else
#define BMG_B(i) b[i]
#define BMG_DINV(i) dinv[i]
#endif
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint g = sessile_gid();
  if (g >= pc.items) return;
  uint node;
  if (pc.colour < 8u) {
    uint t = g + pc.first, a = grid_div(t, pc.s0, pc.ms0), kk = grid_div(a, pc.s1, pc.ms1);
    uvec3 par = uvec3(pc.colour & 1u, (pc.colour >> 1u) & 1u, (pc.colour >> 2u) & 1u);
    uvec3 ijk = 2u * uvec3(t - a * pc.s0, a - kk * pc.s1, kk) + par;
    node = ijk.x + pc.n0 * (ijk.y + pc.n1 * ijk.z);
    if (node < pc.row0 || node >= pc.row0 + pc.nrows) return;
  } else {
    node = pc.row0 + g;
  }
  uint row = node - pc.row0;
  bool zero = (pc.flags & BMG_ZERO) != 0u;
  REAL4 r = zero ? BMG_B(node) : bmg_row_residual(row, BMG_B(node));
  uint d = 4u * row;
  REAL4 dz = REAL4(dot(BMG_DINV(d), r), dot(BMG_DINV(d + 1u), r), dot(BMG_DINV(d + 2u), r), dot(BMG_DINV(d + 3u), r));
  y[node] = (zero ? REAL4(0) : bmg_x(node)) + pc.omega * dz;
}
