#version 450
// XeGTAO pass 3, the last (or only) pass: denoise_body.glsl.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#define HORIZON_LAST_PASS
#include "horizon.h"
#include "denoise_body.glsl"
