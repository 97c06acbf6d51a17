#version 450
// Seed 003's trace pass on a frame that starts an accumulation, traced through the compute-shader BVH
// (rtao_body.glsl).
#extension GL_GOOGLE_include_directive : require
#define RTAO_ACCUMULATE 0
#define RTAO_RAY_QUERY 0
#include "rtao_body.glsl"
