#version 450
// Seed 003's trace pass adding one frame to last frame's running mean, traced through the
// compute-shader BVH (rtao_body.glsl).
#extension GL_GOOGLE_include_directive : require
#define RTAO_ACCUMULATE 1
#define RTAO_RAY_QUERY 0
#include "rtao_body.glsl"
