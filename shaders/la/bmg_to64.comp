#version 450
#extension GL_GOOGLE_include_directive : require
// The fp32 cycle's exit (kernels.def, K_BMG_TO64): z[off4 + i] = double(x).
#include "la_kernels.glsl"
void main() {
  if (pc.guard >= 0 && s[pc.guard] != 0.0) return;
  uint i = sessile_gid();
  if (i >= pc.n4) return;
  z[pc.off4 + i] = dvec4(x[i]);
}
