#version 450
// rd_scene's vertex shader. The camera block holds view and projection apart, one declared
// column-major and one row-major, so the import's handling of both orders is exercised, and the
// same camera as programs hold it otherwise: combined (P.V, and P.V.M with a rigid model), as vec4
// columns (as shaders translated from HLSL hold matrices), and in push constants. kCameraLayout
// (rd_scene --camera) picks which of them positions the vertices; every one is filled. The
// storage buffer's matrix (identity, so the result is exact) is where the import refuses to look
// for a camera. light_projection, a spotlight's perspective projection the draw does not use, is
// a wrong --projection for the self-check tests to name.
layout(constant_id = 0) const int kCameraLayout = 0;  // 0 separate, 1 P.V, 2 P.V.M, 3 vec4 columns, 4 push constants
// As OpenGL renderers brought to Vulkan do: the projection's depth row is GL's ([-1, 1]) and the
// shader maps clip z to [0, 1] itself (rd_scene --gl-depth-row).
layout(constant_id = 1) const bool kRemapClipZ = false;

layout(set = 0, binding = 0, std140) uniform Camera {
  layout(column_major) mat4 view;
  layout(row_major) mat4 projection;
  vec4 tint;
  layout(column_major) mat4 light_projection;
  layout(column_major) mat4 view_projection;        // projection * view
  layout(column_major) mat4 model_view_projection;  // projection * view * model
  layout(column_major) mat4 inverse_model;          // world -> the model's frame, for the P.V.M path
  vec4 columns[8];                                  // view's columns, then projection's
} camera;

layout(set = 0, binding = 1, std430) readonly buffer Extra {
  mat4 shadow;
} extra;

layout(push_constant) uniform Object {  // 128 bytes, every device's least maxPushConstantsSize
  mat4 view;
  mat4 projection;
} object;

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 0) out vec3 worldNormal;

void main() {
  worldNormal = mat3(extra.shadow) * normal;
  const vec4 world = vec4(position, 1.0);
  if (kCameraLayout == 1) {
    gl_Position = camera.view_projection * world;
  } else if (kCameraLayout == 2) {
    gl_Position = camera.model_view_projection * (camera.inverse_model * world);
  } else if (kCameraLayout == 3) {
    const mat4 view = mat4(camera.columns[0], camera.columns[1], camera.columns[2], camera.columns[3]);
    const mat4 projection = mat4(camera.columns[4], camera.columns[5], camera.columns[6], camera.columns[7]);
    gl_Position = projection * (view * world);
  } else if (kCameraLayout == 4) {
    gl_Position = object.projection * (object.view * world);
  } else {
    gl_Position = camera.projection * (camera.view * world);
  }
  if (kRemapClipZ) gl_Position.z = (gl_Position.z + gl_Position.w) * 0.5;
}
