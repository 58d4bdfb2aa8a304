#version 450
#extension GL_GOOGLE_include_directive : require
// edge_force.glsl and tet_force.glsl in one dispatch, invocation i edge i
// and tet i (kernels.def, SDS_ELEM_TEX): llvmpipe runs both codes in every lane
// whatever the branch, so max(nedges, ntets) lanes rather than their sum.
#define SDS_TEXEL 1
#define SDS_ELEM_FUSED 1
#include "edge_force.glsl"
#include "tet_force.glsl"
void main() {
  uint i = sessile_gid();
  edge_force_at(i); // each returns past its count
  tet_force_at(i);
}
