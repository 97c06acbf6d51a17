#version 450
// rd_scene's vertex shader. The camera block holds view and projection apart, one declared
// column-major and one row-major, so the import's handling of both orders is exercised.
layout(set = 0, binding = 0, std140) uniform Camera {
  layout(column_major) mat4 view;
  layout(row_major) mat4 projection;
  vec4 tint;
} camera;

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 0) out vec3 worldNormal;

void main() {
  worldNormal = normal;
  gl_Position = camera.projection * (camera.view * vec4(position, 1.0));
}
