#version 450
// spatial (rows) reading AO and column sums as r16f storage images (bent=0: visibility).
#extension GL_GOOGLE_include_directive : require
#define AOR_AO_FORMAT r16f
#include "spatial_rows_body.glsl"
