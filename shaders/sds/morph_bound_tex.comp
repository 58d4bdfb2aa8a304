#version 450
#extension GL_GOOGLE_include_directive : require
// morph_bound.glsl reading the positions and neighbours through uniform texel buffers.
#define MB_TEXEL 1
#include "morph_bound.glsl"
