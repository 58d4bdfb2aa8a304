#version 450
#extension GL_GOOGLE_include_directive : require
// The advected nutrient's cut-cell boundary on one box level (cutcell.glsl
// with the exponentially fitted weights of cut_adv.glsl).
#define CUT_ADV 1
#include "cutcell.glsl"
