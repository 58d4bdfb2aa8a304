#version 450
#extension GL_GOOGLE_include_directive : require
// BiCGSTAB update: x += α p̂ + ω ŝ; r = s − ω t; partial sums of r·r (set 0)
// and r̂0·r (set 1).
#include "../common/sessile.glsl"
#include "../common/vecpush.glsl"
#include "../common/reduce_shared.glsl"
#include "../common/solver_slots.glsl"
layout(std430, binding = 1) buffer X { REAL4 x[]; };
layout(std430, binding = 2) readonly buffer PH { REAL4 ph[]; };
layout(std430, binding = 3) readonly buffer SH { REAL4 sh[]; };
layout(std430, binding = 4) readonly buffer SV { REAL4 sv[]; };
layout(std430, binding = 5) readonly buffer T { REAL4 t[]; };
layout(std430, binding = 6) buffer R { REAL4 r[]; };
layout(std430, binding = 7) readonly buffer R0 { REAL4 r0[]; };
layout(std430, binding = 8) writeonly buffer PART { REAL2 part[]; };
void main() {
  if (guarded()) return;
  REAL a = s[BI_ALPHA], w = s[BI_OMEGA];
  REAL2 rr = REAL2(0), rho = REAL2(0);
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < pc.n4; i += stride) {
    x[i] += a * ph[i] + w * sh[i];
    REAL4 ri = sv[i] - w * t[i];
    r[i] = ri;
    REAL4 u = ri * ri, v = r0[i] * ri;
    acc_add(rr, u.x); acc_add(rr, u.y); acc_add(rr, u.z); acc_add(rr, u.w);
    acc_add(rho, v.x); acc_add(rho, v.y); acc_add(rho, v.z); acc_add(rho, v.w);
  }
  REAL2 a0 = group_reduce(rr);
  REAL2 a1 = group_reduce(rho);
  if (gl_LocalInvocationID.x == 0u) {
    part[gl_WorkGroupID.x] = a0;
    part[MAXG + gl_WorkGroupID.x] = a1;
  }
}
