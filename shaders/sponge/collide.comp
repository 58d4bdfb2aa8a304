#version 450
#extension GL_GOOGLE_include_directive : require
// Particle-vertex collisions over a uniform grid, one particle per
// invocation (a gather: no atomics, nothing depends on scheduling).  Keeps
// the feed smallest vertex indices within the particle's radius, ascending,
// and counts them all.  Operation by operation as
// sessile_sponge_particles_collide_grid (host/sponge/particles_collide.c).
#include "sponge_kernels.glsl"

const uint SPONGE_NO_HIT = 0xFFFFFFFFu; // = SESSILE_SPONGE_PARTICLES_NO_HIT

void main() {
  uint i = sessile_gid();
  if (i >= pc.n) return;
  vec3 p = part[i].xyz;
  uint best[SPONGE_MAX_FEED];
  uint kept = 0u, total = 0u;
  uint dims[3] = uint[3](pc.d0, pc.d1, pc.d2);
  float lo[3] = float[3](pc.lo0, pc.lo1, pc.lo2);
  uint c0[3], c1[3];
  bool inside = pc.nv > 0u;
  for (int a = 0; a < 3; a++) {
    precise float x0 = (p[a] - pc.radius - lo[a]) * pc.inv_h - pc.margin;
    precise float x1 = (p[a] + pc.radius - lo[a]) * pc.inv_h + pc.margin;
    float top = float(dims[a] - 1u);
    // the last cell spans [d - 1, d) in cell units
    if (!(x1 >= 0.0) || !(x0 < float(dims[a]))) inside = false;
    c0[a] = x0 <= 0.0 ? 0u : uint(x0);
    c1[a] = x1 >= top ? dims[a] - 1u : uint(x1);
  }
  if (inside) {
    for (uint z = c0[2]; z <= c1[2]; z++)
      for (uint y = c0[1]; y <= c1[1]; y++)
        for (uint x = c0[0]; x <= c1[0]; x++) {
          uint c = x + pc.d0 * (y + pc.d1 * z);
          uint e1 = cell_off[c + 1u];
          for (uint e = cell_off[c]; e < e1; e++) {
            uint v = cell_vtx[e];
            vec3 q = vtx[v].xyz;
            precise float dx = p.x - q.x;
            precise float dy = p.y - q.y;
            precise float dz = p.z - q.z;
            precise float d2 = dx * dx + dy * dy;
            precise float d3 = d2 + dz * dz;
            if (d3 <= pc.r2) {
              total++;
              // insertion into the sorted list of the feed smallest
              uint k = kept;
              bool take = true;
              if (kept == pc.feed) {
                if (v >= best[pc.feed - 1u]) take = false;
                k = pc.feed - 1u;
              } else {
                kept++;
              }
              if (take) {
                while (k > 0u && best[k - 1u] > v) {
                  best[k] = best[k - 1u];
                  k--;
                }
                best[k] = v;
              }
            }
          }
        }
  }
  for (uint k = 0u; k < pc.feed; k++) hit[pc.feed * i + k] = k < kept ? best[k] : SPONGE_NO_HIT;
  count[i] = total;
}
