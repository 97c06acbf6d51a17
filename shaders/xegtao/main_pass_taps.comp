#version 450
// XeGTAO pass 2 counting its depth taps by MIP level (--debug mip_taps): main_pass_body.glsl.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#define XEGTAO_COUNT_TAPS
#include "main_pass_body.glsl"
