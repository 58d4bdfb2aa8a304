#version 450
#extension GL_GOOGLE_include_directive : require
// edge_force.glsl reading its inputs through storage buffers (sds_load.glsl).
#define SDS_TEXEL 0
#include "edge_force.glsl"
