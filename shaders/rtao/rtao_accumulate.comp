#version 450
// Seed 003's trace pass adding one frame to last frame's running mean (rtao_body.glsl).
#extension GL_GOOGLE_include_directive : require
#define RTAO_ACCUMULATE 1
#include "rtao_body.glsl"
