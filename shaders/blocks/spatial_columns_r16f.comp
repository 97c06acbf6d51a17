#version 450
// spatial_columns reading AO as a r16f storage image (bent=0: visibility).
#extension GL_GOOGLE_include_directive : require
#define AOR_AO_FORMAT r16f
#include "spatial_columns_body.glsl"
