#version 450
#extension GL_GOOGLE_include_directive : require
// BiCGSTAB half step: s = r − α v, with partial sums of s·s (set 0).
#include "../common/sessile.glsl"
#include "../common/vecpush.glsl"
#include "../common/reduce_shared.glsl"
#include "../common/solver_slots.glsl"
layout(std430, binding = 1) readonly buffer R { REAL4 r[]; };
layout(std430, binding = 2) readonly buffer V { REAL4 v[]; };
layout(std430, binding = 3) writeonly buffer SV { REAL4 sv[]; };
layout(std430, binding = 4) writeonly buffer PART { REAL2 part[]; };
void main() {
  if (guarded()) return;
  REAL a = s[BI_ALPHA];
  REAL2 ss = REAL2(0);
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < pc.n4; i += stride) {
    REAL4 si = r[i] - a * v[i];
    sv[i] = si;
    REAL4 t = si * si;
    acc_add(ss, t.x); acc_add(ss, t.y); acc_add(ss, t.z); acc_add(ss, t.w);
  }
  REAL2 a0 = group_reduce(ss);
  if (gl_LocalInvocationID.x == 0u) part[gl_WorkGroupID.x] = a0;
}
