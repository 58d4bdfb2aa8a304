#version 450
#extension GL_GOOGLE_include_directive : require
// R r on the coarse grid, reading storage buffers: bmg_restrict.glsl.
#define BMG_TEXEL 0
#include "bmg_restrict.glsl"
