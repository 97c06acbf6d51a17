#version 450
// Camera-space Z of layer 0 (csz_body.glsl).
#extension GL_GOOGLE_include_directive : require
#define SAO_DUAL_LAYER 0
#include "csz_body.glsl"
