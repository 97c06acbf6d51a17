#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// CACAO postprocess importance map A: postprocess_importance_map_body.glsl.
#include "postprocess_importance_map_body.glsl"
