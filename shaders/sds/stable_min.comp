#version 450
#extension GL_GOOGLE_include_directive : require
// stable_min.glsl: the stable bound's minimum and a batch's checks.
#include "stable_min.glsl"
