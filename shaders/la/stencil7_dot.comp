#version 450
#extension GL_GOOGLE_include_directive : require
// y = A x (masked 7-point operator) fused with the partial sums of x·y into
// set 0, as spmv_csr_dot.comp does for CG's p·Ap.  Grid-stride, MAXG groups.
#include "la_kernels.glsl"
#include "../common/reduce_shared.glsl"
#include "stencil7.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != REAL(0)) return;
  REAL2 acc = REAL2(0);
  uint n = pc.n0 * pc.n1 * pc.n2;
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint node = gl_GlobalInvocationID.x; node < n; node += stride) {
    REAL v = st_apply(node);
    y[pc.yoff + node] = v;
    acc_add(acc, v * x[pc.xoff + node]);
  }
  REAL2 t = group_reduce(acc);
  if (gl_LocalInvocationID.x == 0u) part[gl_WorkGroupID.x] = t;
}
