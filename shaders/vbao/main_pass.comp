#version 450
// vbao's main pass (main_pass_body.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#include "main_pass_body.glsl"
