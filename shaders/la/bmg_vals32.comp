#version 450
#extension GL_GOOGLE_include_directive : require
// The fp32 cycle's copy of the fine matrix values made on the device
// (kernels.def, K_BMG_VALS32): dst[dst4 + i] = vec4(src[src4 + i]) for
// i < n4, a grid-stride loop (a chunk may need more workgroups than a
// dispatch has).  float(double) rounds to nearest, as the host's cast.
#include "la_kernels.glsl"
void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = sessile_gid(); i < pc.n4; i += stride) dst[pc.dst4 + i] = vec4(src[pc.src4 + i]);
}
