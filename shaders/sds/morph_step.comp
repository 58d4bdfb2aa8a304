#version 450
#extension GL_GOOGLE_include_directive : require
// morph_step.glsl reading its inputs through storage buffers.
#define MORPH_TEXEL 0
#define MORPH_BATCH 0
#include "morph_step.glsl"
