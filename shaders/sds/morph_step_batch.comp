#version 450
#extension GL_GOOGLE_include_directive : require
// morph_step.glsl as one sub-step of a batch (kernels.def, SDS_MORPH_STEP_BATCH).
#define MORPH_TEXEL 0
#define MORPH_BATCH 1
#include "morph_step.glsl"
