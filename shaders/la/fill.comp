#version 450
#extension GL_GOOGLE_include_directive : require
// y = a (the padding past n stays zero)
#include "la_kernels.glsl"
#include "../common/vecpush.glsl"
void main() {
  uint i = sessile_gid();
  if (i >= pc.n4 || guarded()) return;
  REAL a = coef();
  uvec4 k = uvec4(4u * i) + uvec4(0u, 1u, 2u, 3u);
  y[pc.off0 + i] = mix(REAL4(0), REAL4(a), lessThan(k, uvec4(pc.n)));
}
