#version 450
#extension GL_GOOGLE_include_directive : require
// morph_step_batch.comp reading its inputs through uniform texel buffers.
#define MORPH_TEXEL 1
#define MORPH_BATCH 1
#include "morph_step.glsl"
