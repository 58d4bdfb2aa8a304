#version 450
#extension GL_GOOGLE_include_directive : require
// bmg_smooth.glsl reading the matrix and x through uniform texel buffers.
#define BMG_TEXEL 1
#include "bmg_smooth.glsl"
