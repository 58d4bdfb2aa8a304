#version 450
#extension GL_GOOGLE_include_directive : require
// Restriction R = P^T onto coarse node (I,J,K) = fine node (2I,2J,2K): the
// gather of the up to 27 fine residuals around it with the trilinear weights
// (1, 1/2 per axis offset), not averaged (the operators carry the scaling h,
// so R A_h P ~ A_2h).  0 on coarse Dirichlet nodes.  Also writes the coarse
// level's first sweep from zero, x = omega b / (h diag) (mg_smooth.glsl).
#include "la_kernels.glsl"
#include "grid_index.glsl"
#include "texel_real.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  uint node = sessile_gid();
  if (node >= pc.n0 * pc.n1 * pc.n2) return;
  if (texelFetch(mask_t, int(node)).x != 0u) {
    b[node] = REAL(0);
    x[node] = REAL(0);
    return;
  }
  uvec3 c = grid_ijk(node), f = 2u * c;
  uvec3 lo = uvec3(greaterThan(f, uvec3(0))), hi = uvec3(lessThan(f + 1u, uvec3(pc.f0, pc.f1, pc.f2)));
  REAL sum = REAL(0);
  // Offsets -1, 0, 1 per axis; a missing fine node (outside the grid) reads
  // the centre with weight 0.
  for (int dk = -1; dk <= 1; dk++) {
    bool okk = dk == 0 || (dk < 0 ? lo.z != 0u : hi.z != 0u);
    uint k = okk ? uint(int(f.z) + dk) : f.z;
    REAL wk = okk ? (dk == 0 ? REAL(1) : REAL(0.5)) : REAL(0);
    for (int dj = -1; dj <= 1; dj++) {
      bool okj = dj == 0 || (dj < 0 ? lo.y != 0u : hi.y != 0u);
      uint j = okj ? uint(int(f.y) + dj) : f.y;
      REAL wj = okj ? (dj == 0 ? wk : REAL(0.5) * wk) : REAL(0);
      uint row = pc.f0 * (j + pc.f1 * k);
      for (int di = -1; di <= 1; di++) {
        bool oki = di == 0 || (di < 0 ? lo.x != 0u : hi.x != 0u);
        uint i = oki ? uint(int(f.x) + di) : f.x;
        REAL w = oki ? (di == 0 ? wj : REAL(0.5) * wj) : REAL(0);
        sum += w * texel_real(r_t, row + i);
      }
    }
  }
  b[node] = sum;
  x[node] = pc.omega * sum / (pc.h * texel_real(diag_t, node));
}
