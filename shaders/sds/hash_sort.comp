#version 450
#extension GL_GOOGLE_include_directive : require
// One bucket per invocation: insertion sort of its faces by index (buckets
// hold a few faces at load 1/2), so the table's bytes do not depend on the
// order in which hash_fill's atomics were served.
#include "sds_common.glsl"

void main() {
  uint b = sessile_gid();
  if (b >= pc.tsize) return;
  uint T = pc.tsize, e0 = 3u * T + 1u, lo = hash[T + b], hi = hash[T + b + 1u];
  for (uint i = lo + 1u; i < hi; i++) {
    uint v = hash[e0 + i], j = i;
    while (j > lo && hash[e0 + j - 1u] > v) {
      hash[e0 + j] = hash[e0 + j - 1u];
      j--;
    }
    hash[e0 + j] = v;
  }
}
