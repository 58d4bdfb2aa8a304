#version 450
#extension GL_GOOGLE_include_directive : require
// R r on the coarse grid, reading the masks and r through texel views:
// bmg_restrict.glsl.
#define BMG_TEXEL 1
#include "bmg_restrict.glsl"
