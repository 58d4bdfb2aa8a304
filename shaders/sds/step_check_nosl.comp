#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// step_check.glsl for a batch without lasting slivers (its table empty: any
// inverted tet stops it, as in step_check.comp): the quiet slivers' cubic
// left out, since llvmpipe runs the tail's code, masked, in every subgroup
// of the dispatch (docs/sds.md, "Tails that every subgroup runs").  The
// same bits as step_check.comp with an empty table.
#define SDS_SLIVERS 0
#include "step_check.glsl"
