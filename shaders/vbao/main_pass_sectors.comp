#version 450
// vbao's main pass writing the share of sectors occupied as well (--debug sectors).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
#define VBAO_SECTORS_VIEW
#include "main_pass_body.glsl"
