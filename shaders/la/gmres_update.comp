#version 450
#extension GL_GOOGLE_include_directive : require
// GMRES solution update with right Jacobi preconditioning:
// x += D⁻¹ Σ_{i<k} y_i v_i, with k and y from the scalar slots and the basis
// v_i stored one after another in V (stride off0 REAL4 chunks).
#include "la_kernels.glsl"
#include "../common/vecpush.glsl"
void main() {
  uint e = sessile_gid();
  if (e >= pc.n4 || guarded()) return;
  uint m = pc.off1;
  uint ybase = GM_BASE + (m + 1u) * m + (m + 1u) + 2u * m;
  int k = int(s[GM_K]);
  REAL4 acc = REAL4(0);
  for (int i = 0; i < k; i++) acc += s[ybase + uint(i)] * v[uint(i) * pc.off0 + e];
  x[e] += dinv[e] * acc;
}
