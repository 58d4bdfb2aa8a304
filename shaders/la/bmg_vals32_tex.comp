#version 450
#extension GL_GOOGLE_include_directive : require
// bmg_vals32.comp reading the fp64 values through a texel view (raw bits, a
// dvec4 being two RGBA32UI texels; kernels.def, K_BMG_VALS32_TEX): lavapipe
// gathers texels with vector loads where it loads storage lane by lane.
// The same casts, so the same bits.
#include "la_kernels.glsl"
void main() {
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint i = sessile_gid(); i < pc.n4; i += stride) {
    uint t = 2u * (pc.src4 + i);
    uvec4 a = texelFetch(src_t, int(t)), c = texelFetch(src_t, int(t + 1u));
    dvec4 v = dvec4(packDouble2x32(a.xy), packDouble2x32(a.zw), packDouble2x32(c.xy), packDouble2x32(c.zw));
    dst[pc.dst4 + i] = vec4(v);
  }
}
