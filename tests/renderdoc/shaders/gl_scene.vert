#version 330 core
// rd_gl_scene's vertex shader. rd_gl_scene puts one #define after the #version line to choose
// where the camera lives (--camera):
// - ubo (no define): a std140 uniform block, view and projection apart, both column-major. The
//   block has no instance name: RenderDoc's GL reflection then lists its members as SceneData's
//   own variables (view, projection); with one (`} scene;`) it shows a single struct variable
//   named SceneData that holds them. light_projection, a spotlight's perspective projection that
//   the draw does not use, is there for the import tests to name as a wrong --projection (std140:
//   every member is active).
// - CAMERA_GLOBALS: view and projection as default-block uniforms (RenderDoc's $Globals).
// - CAMERA_COMBINED: one default-block view_projection (projection * view).
// The object's model matrix (identity) is a default-block uniform in every mode.
#if defined(CAMERA_GLOBALS)
uniform mat4 view;
uniform mat4 projection;
#elif defined(CAMERA_COMBINED)
uniform mat4 view_projection;
#else
layout(std140) uniform SceneData {
  mat4 view;
  mat4 projection;
  mat4 light_projection;
};
#endif

uniform mat4 model;

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
out vec3 worldNormal;

vec4 clipPosition(vec4 world) {
#if defined(CAMERA_COMBINED)
  return view_projection * world;
#else
  return projection * (view * world);
#endif
}

void main() {
  worldNormal = mat3(model) * normal;
  gl_Position = clipPosition(model * vec4(position, 1.0));
}
