#version 450
// Camera-space Z of both layers, packed in one RG target (csz_body.glsl).
#extension GL_GOOGLE_include_directive : require
#define SAO_DUAL_LAYER 1
#include "csz_body.glsl"
