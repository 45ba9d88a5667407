#version 450
// shaders/cut_exact.comp - one round of the cut, between cut_step and
// cut_scan: the entries cut_step deferred, done again with the exact
// path where the float filter is unsure (shaders/cut_step.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_EXT_control_flow_attributes : require
#include "cut_step.glsl"
