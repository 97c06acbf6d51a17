#version 450
// XeGTAO pass 3, a pass before the last (denoise_passes 2 and 3): denoise_body.glsl.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
#include "horizon.h"
#include "denoise_body.glsl"
