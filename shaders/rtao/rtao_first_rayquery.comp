#version 460
// Seed 003's trace pass on a frame that starts an accumulation, traced with ray queries (rtao_body.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_query : require
#define RTAO_ACCUMULATE 0
#define RTAO_RAY_QUERY 1
#include "rtao_body.glsl"
