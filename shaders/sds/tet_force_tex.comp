#version 450
#extension GL_GOOGLE_include_directive : require
// tet_force.glsl reading its inputs through uniform texel buffers (sds_load.glsl).
#define SDS_TEXEL 1
#include "tet_force.glsl"
