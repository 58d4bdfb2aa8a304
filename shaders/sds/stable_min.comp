#version 450
#extension GL_GOOGLE_include_directive : require
// One workgroup: the stable bound, min(dt_max, min_c h_c) (a NaN h_c is
// skipped, as sessile_sds_stable_dt does; a min is exact in any order, so
// the bits do not depend on the schedule), the cap hmax = dt_max lowered to
// stable_safety x the bound, and the step h = min(pc.dt, hmax) that the
// gather takes in mode 2: stab[n] = h, stab[n + 1] = hmax, stab[n + 2] = the
// bound, copied to step for the host.  The cap is the one
// sessile_sds_gpu_advance applied on the host before this kernel existed.
#include "sds_common.glsl"

shared REAL part[SDS_SCAN_MAX];

void main() {
  uint l = gl_LocalInvocationID.x, L = gl_WorkGroupSize.x, n = pc.ncells;
  REAL best = sp[SP_DT_MAX];
  for (uint c = l; c < n; c += L)
    if (stab[c] < best) best = stab[c];
  part[l] = best;
  barrier();
  for (uint w = L / 2u; w > 0u; w /= 2u) {
    if (l < w && part[l + w] < part[l]) part[l] = part[l + w];
    barrier();
  }
  if (l == 0u) {
    REAL bound = part[0], hmax = sp[SP_DT_MAX];
    if (sp[SP_SAFETY] > REAL(0) && sp[SP_SAFETY] * bound < hmax) hmax = sp[SP_SAFETY] * bound;
    REAL h = pc.dt > hmax ? hmax : pc.dt;
    stab[n] = h, stab[n + 1u] = hmax, stab[n + 2u] = bound;
    step[0] = h, step[1] = hmax, step[2] = bound;
  }
}
