#version 450
#extension GL_GOOGLE_include_directive : require
// x += P xc on the free fine nodes: trilinear interpolation from the nested
// coarse grid (f0 x f1 x f2; fine node 2I is coarse node I, an odd fine node
// is the mean of its two coarse neighbours along that axis).  Coarse Dirichlet
// nodes hold 0, so no coarse mask is needed; fine Dirichlet nodes are left
// alone (their correction is zero).
#include "la_kernels.glsl"
#include "grid_index.glsl"
#include "texel_real.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2 || texelFetch(mask_t, int(node)).x != 0u) return;
  uvec3 f = grid_ijk(node), c0 = f >> 1u, odd = f & 1u, c1 = c0 + odd;
  REAL w1x = odd.x != 0u ? REAL(0.5) : REAL(0), w0x = REAL(1) - w1x;
  REAL w1y = odd.y != 0u ? REAL(0.5) : REAL(0), w0y = REAL(1) - w1y;
  REAL w1z = odd.z != 0u ? REAL(0.5) : REAL(0), w0z = REAL(1) - w1z;
  uint r00 = pc.f0 * (c0.y + pc.f1 * c0.z), r10 = pc.f0 * (c1.y + pc.f1 * c0.z);
  uint r01 = pc.f0 * (c0.y + pc.f1 * c1.z), r11 = pc.f0 * (c1.y + pc.f1 * c1.z);
  REAL v = w0z * (w0y * (w0x * texel_real(xc_t, r00 + c0.x) + w1x * texel_real(xc_t, r00 + c1.x)) +
                  w1y * (w0x * texel_real(xc_t, r10 + c0.x) + w1x * texel_real(xc_t, r10 + c1.x))) +
           w1z * (w0y * (w0x * texel_real(xc_t, r01 + c0.x) + w1x * texel_real(xc_t, r01 + c1.x)) +
                  w1y * (w0x * texel_real(xc_t, r11 + c0.x) + w1x * texel_real(xc_t, r11 + c1.x)));
  x[node] = texel_real(x_t, node) + v;
}
