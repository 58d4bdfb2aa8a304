#version 450
#extension GL_GOOGLE_include_directive : require
// Area-weighted vertex normals: the sum of the incident faces' cross
// products (|cross| = 2 area), in ascending face order from the vertex->face
// CSR, normalised.  Reference: sessile_surface_normals.
#include "growth_common.glsl"

void main() {
  uint v = sessile_gid();
  if (v >= pc.nv) return;
  REAL s[3] = REAL[3](REAL(0), REAL(0), REAL(0));
  for (uint q = vf_off[v]; q < vf_off[v + 1u]; q++) {
    uint f = vf[q];
    uint ia = tri[3u * f], ib = tri[3u * f + 1u], ic = tri[3u * f + 2u];
    precise REAL u0 = pos[3u * ib] - pos[3u * ia];
    precise REAL u1 = pos[3u * ib + 1u] - pos[3u * ia + 1u];
    precise REAL u2 = pos[3u * ib + 2u] - pos[3u * ia + 2u];
    precise REAL w0 = pos[3u * ic] - pos[3u * ia];
    precise REAL w1 = pos[3u * ic + 1u] - pos[3u * ia + 1u];
    precise REAL w2 = pos[3u * ic + 2u] - pos[3u * ia + 2u];
    precise REAL c0 = u1 * w2 - u2 * w1;
    precise REAL c1 = u2 * w0 - u0 * w2;
    precise REAL c2 = u0 * w1 - u1 * w0;
    s[0] += c0;
    s[1] += c1;
    s[2] += c2;
  }
  precise REAL l = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  for (int a = 0; a < 3; a++) nrm[3u * v + uint(a)] = l > REAL(0) ? s[a] / l : s[a];
}
