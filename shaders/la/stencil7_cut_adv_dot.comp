#version 450
#extension GL_GOOGLE_include_directive : require
// y = A x (advective cut-cell operator, CUT_ADV, texel reads) fused with the partial
// sums of x·y into set 0, as stencil7_dot.comp.  Grid-stride, MAXG groups.
#define CUT_TEXEL 1
#define CUT_ADV 1
#include "stencil7_cut.glsl"
#include "../common/reduce_shared.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  REAL2 acc = REAL2(0);
  uint n = pc.n0 * pc.n1 * pc.n2;
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint node = gl_GlobalInvocationID.x; node < n; node += stride) {
    REAL v = ct_apply(node);
    y[pc.yoff + node] = v;
    acc_add(acc, v * ct_x(node));
  }
  REAL2 t = group_reduce(acc);
  if (gl_LocalInvocationID.x == 0u) part[gl_WorkGroupID.x] = t;
}
