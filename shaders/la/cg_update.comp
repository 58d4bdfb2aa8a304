#version 450
#extension GL_GOOGLE_include_directive : require
// CG step, fused: x += α p; r -= α q; partial sums of r·D⁻¹r (set 0) and r·r
// (set 1).  z = D⁻¹ r is never stored: cg_direction.comp recomputes it.
#include "../common/sessile.glsl"
#include "../common/vecpush.glsl"
#include "../common/reduce_shared.glsl"
#include "../common/solver_slots.glsl"
layout(std430, binding = 1) readonly buffer P { REAL4 p[]; };
layout(std430, binding = 2) readonly buffer Q { REAL4 q[]; };
layout(std430, binding = 3) readonly buffer D { REAL4 dinv[]; };
layout(std430, binding = 4) buffer X { REAL4 x[]; };
layout(std430, binding = 5) buffer R { REAL4 r[]; };
layout(std430, binding = 6) writeonly buffer PART { REAL2 part[]; };
void main() {
  if (guarded()) return;
  REAL a = s[CG_ALPHA];
  REAL2 rz = REAL2(0), rr = REAL2(0);
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = gl_GlobalInvocationID.x; i < pc.n4; i += stride) {
    x[i] += a * p[i];
    REAL4 ri = r[i] - a * q[i];
    r[i] = ri;
    REAL4 zi = dinv[i] * ri;
    REAL4 t = ri * zi, u = ri * ri;
    acc_add(rz, t.x); acc_add(rz, t.y); acc_add(rz, t.z); acc_add(rz, t.w);
    acc_add(rr, u.x); acc_add(rr, u.y); acc_add(rr, u.z); acc_add(rr, u.w);
  }
  REAL2 a0 = group_reduce(rz);
  REAL2 a1 = group_reduce(rr);
  if (gl_LocalInvocationID.x == 0u) {
    part[gl_WorkGroupID.x] = a0;
    part[MAXG + gl_WorkGroupID.x] = a1;
  }
}
