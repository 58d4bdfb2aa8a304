#version 450
#extension GL_GOOGLE_include_directive : require
// The V-cycle's last sweep on the finest level fused with the partial sums
// of b·y into set pc.set: with b = r and y = z = M r, CG's r·z.  Grid-stride,
// MAXG groups.
#include "mg_smooth.glsl"
#include "../common/reduce_shared.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  REAL2 acc = REAL2(0);
  uint n = pc.n0 * pc.n1 * pc.n2;
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint node = gl_GlobalInvocationID.x; node < n; node += stride) {
    REAL v = mg_sweep(node);
    y[node] = v;
    acc_add(acc, v * texel_real(b_t, node));
  }
  REAL2 t = group_reduce(acc);
  if (gl_LocalInvocationID.x == 0u) part[pc.set * MAXG + gl_WorkGroupID.x] = t;
}
