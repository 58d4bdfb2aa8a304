#version 450
#extension GL_GOOGLE_include_directive : require
// morph_bound.glsl reading through storage buffers.
#define MB_TEXEL 0
#include "morph_bound.glsl"
