#version 450
#extension GL_GOOGLE_include_directive : require
// One tetrahedron per invocation: flag[t] = 1 when its signed volume (eq 1)
// is <= 0 or not finite (§3.1.2: an inverted tetrahedron), else 0.
#include "sds_common.glsl"

void main() {
  uint t = sessile_gid();
  if (t >= pc.ntets) return;
  uint q0 = topo[4u * t], q1 = topo[4u * t + 1u], q2 = topo[4u * t + 2u], q3 = topo[4u * t + 3u];
  REAL a[3], b[3], c[3];
  for (int i = 0; i < 3; i++) {
    a[i] = x[3u * q1 + i] - x[3u * q0 + i];
    b[i] = x[3u * q2 + i] - x[3u * q0 + i];
    c[i] = x[3u * q3 + i] - x[3u * q0 + i];
  }
  REAL V = a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  flag[t] = (V > REAL(0) && is_finite(V)) ? 0u : 1u;
}
