#version 450
#extension GL_GOOGLE_include_directive : require
// morph_step.glsl reading its inputs through uniform texel buffers.
#define MORPH_TEXEL 1
#define MORPH_BATCH 0
#include "morph_step.glsl"
