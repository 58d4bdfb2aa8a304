#version 450
#extension GL_GOOGLE_include_directive : require
// The Laplace nutrient's cut-cell boundary on one box level (cutcell.glsl).
#define CUT_ADV 0
#include "cutcell.glsl"
