#version 450
#extension GL_GOOGLE_include_directive : require
// One boundary face per invocation: takes a slot in its bucket through the
// bucket's cursor (the order inside a bucket depends on timing here;
// hash_sort makes it the ascending face order).
#include "sds_common.glsl"
#include "sds_contact.glsl"

void main() {
  uint f = sessile_gid();
  if (f >= pc.nfaces) return;
  uint T = pc.tsize, of = o_face() + 3u * f;
  REAL g[3], h = sp[SP_H_SELF];
  uint q0 = topo[of], q1 = topo[of + 1u], q2 = topo[of + 2u];
  for (int i = 0; i < 3; i++) g[i] = (x[3u * q0 + i] + x[3u * q1 + i] + x[3u * q2 + i]) / REAL(3);
  uint b = grid_hash(grid_coord(g[0], h), grid_coord(g[1], h), grid_coord(g[2], h), T);
  uint slot = atomicAdd(hash[2u * T + 1u + b], 1u);
  hash[3u * T + 1u + slot] = f;
}
