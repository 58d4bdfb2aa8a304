#version 450
#extension GL_GOOGLE_include_directive : require
// x += P xc, reading the mask and xc through texel views: bmg_prolong.glsl.
#define BMG_TEXEL 1
#include "bmg_prolong.glsl"
