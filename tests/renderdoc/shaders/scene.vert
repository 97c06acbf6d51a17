#version 450
// rd_scene's vertex shader. The camera block holds view and projection apart, one declared
// column-major and one row-major, so the import's handling of both orders is exercised. The
// object's model matrix (a push constant) and the storage buffer's matrix (both identity, so the
// result is exact) are where the import refuses to look for a camera. light_projection, a
// spotlight's perspective projection the draw does not use, is a wrong --projection for the
// self-check tests to name.
layout(set = 0, binding = 0, std140) uniform Camera {
  layout(column_major) mat4 view;
  layout(row_major) mat4 projection;
  vec4 tint;
  layout(column_major) mat4 light_projection;
} camera;

layout(set = 0, binding = 1, std430) readonly buffer Extra {
  mat4 shadow;
} extra;

layout(push_constant) uniform Object {
  mat4 model;
} object;

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 0) out vec3 worldNormal;

void main() {
  worldNormal = mat3(extra.shadow) * normal;
  gl_Position = camera.projection * (camera.view * (object.model * vec4(position, 1.0)));
}
