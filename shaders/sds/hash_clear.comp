#version 450
#extension GL_GOOGLE_include_directive : require
// One bucket per invocation: its count and its largest face radius to zero
// (and the largest face radius of all, by invocation 0), before hash_count
// (kernels.def, "The surface hash").
#include "sds_common.glsl"

void main() {
  uint i = sessile_gid();
  if (i >= pc.tsize) return;
  hash[i] = 0u;
  hash[3u * pc.tsize + 2u + pc.nfaces + i] = 0u;
  if (i == 0u) hash[3u * pc.tsize + 1u + pc.nfaces] = 0u;
}
