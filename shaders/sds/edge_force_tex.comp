#version 450
#extension GL_GOOGLE_include_directive : require
// edge_force.glsl reading its inputs through uniform texel buffers (sds_load.glsl).
#define SDS_TEXEL 1
#include "edge_force.glsl"
