#version 450
#extension GL_GOOGLE_include_directive : require
// y = b - A x on one matrix row chunk: bmg_residual.glsl, texel reads.
#define BMG_TEXEL 1
#include "bmg_residual.glsl"
