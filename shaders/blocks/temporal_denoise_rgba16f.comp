#version 450
// temporal_denoise reading AO as a rgba16f storage image (bent=1: bent.xyz + visibility).
#extension GL_GOOGLE_include_directive : require
#define AOR_AO_FORMAT rgba16f
#include "temporal_denoise_body.glsl"
