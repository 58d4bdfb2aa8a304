#version 450
#extension GL_GOOGLE_include_directive : require
// bmg_smooth.glsl reading the matrix and x through storage buffers.
#define BMG_TEXEL 0
#include "bmg_smooth.glsl"
