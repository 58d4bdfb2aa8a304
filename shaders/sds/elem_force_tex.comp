#version 450
#extension GL_GOOGLE_include_directive : require
// edge_force.glsl and tet_force.glsl in one dispatch: the edges, then the tets
// (kernels.def, SDS_ELEM_TEX).
#define SDS_TEXEL 1
#define SDS_ELEM_FUSED 1
#include "edge_force.glsl"
#include "tet_force.glsl"
void main() {
  uint i = sessile_gid();
  if (i < pc.nedges) edge_force_at(i);
  else tet_force_at(i - pc.nedges);
}
