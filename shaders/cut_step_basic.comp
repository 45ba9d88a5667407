#version 450
// shaders/cut_step_basic.comp - cut_step.comp for updates that merge
// nothing (basic mode: pc.merge is 0), without the merge check
// (shaders/cut_step.glsl says why).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_EXT_control_flow_attributes : require
#define MLOD_CUT_PASS_FILTER
#define MLOD_CUT_NO_MERGE
#include "cut_step.glsl"
