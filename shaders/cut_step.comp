#version 450
// shaders/cut_step.comp - one round of the cut, first pass: each entry's
// status by the float filter alone, its action and output count, the
// workgroup's block sum; an entry the filter is unsure of is deferred to
// cut_exact (shaders/cut_step.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_EXT_control_flow_attributes : require
#define MLOD_CUT_PASS_FILTER
#include "cut_step.glsl"
