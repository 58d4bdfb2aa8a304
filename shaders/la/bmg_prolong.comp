#version 450
#extension GL_GOOGLE_include_directive : require
// x += P xc, reading storage buffers: bmg_prolong.glsl.
#define BMG_TEXEL 0
#include "bmg_prolong.glsl"
