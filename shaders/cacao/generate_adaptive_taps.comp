#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_control_flow_attributes : require
// CACAO SSAO generation Q3 counting its extra taps by importance (--debug adaptive_taps): generate_body.glsl.
#define CACAO_ADAPTIVE
#define CACAO_COUNT_TAPS
#include "generate_body.glsl"
