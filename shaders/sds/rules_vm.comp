#version 450
#extension GL_GOOGLE_include_directive : require
// The rules' bytecode per cell (rules_vm.glsl).
#include "rules_vm.glsl"
