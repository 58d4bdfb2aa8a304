#version 450
#extension GL_GOOGLE_include_directive : require
// The fp32 cycle's entry (kernels.def, K_BMG_TO32): b = float(r[off4 + i]),
// and the cycle's stop flag from the solver's fp64 stop slot.
#include "la_kernels.glsl"
void main() {
  bool stopped = pc.guard >= 0 && s[pc.guard] != 0.0;
  uint i = sessile_gid();
  if (i == 0u) stop[0] = stopped ? 1.0 : 0.0;
  if (stopped || i >= pc.n4) return;
  b[i] = vec4(r[pc.off4 + i]);
}
