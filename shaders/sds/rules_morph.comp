#version 450
#extension GL_GOOGLE_include_directive : require
// rules_morph.glsl with the interpreter (device_rules = bytecode); the
// generated kernel includes the same file after its evaluate_gen.
#include "rules_morph.glsl"
