#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// step_check.glsl: a batch step's inverted flags, check and morphogens'
// bound in one dispatch, the lasting slivers' table honoured.
#include "step_check.glsl"
