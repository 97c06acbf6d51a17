#version 450
// spatial (rows) reading AO and column sums as rgba16f storage images (bent=1: bent.xyz, visibility).
#extension GL_GOOGLE_include_directive : require
#define AOR_AO_FORMAT rgba16f
#include "spatial_rows_body.glsl"
