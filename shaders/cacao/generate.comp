#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
// CACAO SSAO generation Q0, Q1, Q2 and the adaptive base pass: generate_body.glsl.
#include "generate_body.glsl"
