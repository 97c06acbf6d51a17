#version 330 core
// rd_gl_scene's vertex shader: the camera in a std140 uniform block (view and projection apart,
// both column-major), the object's model matrix (identity) in the default block. The block has no
// instance name: RenderDoc's GL reflection then lists its members as SceneData's own variables
// (view, projection); with one (`} scene;`) it shows a single struct variable named SceneData that
// holds them. light_projection, a spotlight's perspective projection that the draw does not use,
// is there for the import tests to name as a wrong --projection (std140: every member is active).
layout(std140) uniform SceneData {
  mat4 view;
  mat4 projection;
  mat4 light_projection;
};

uniform mat4 model;

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
out vec3 worldNormal;

void main() {
  worldNormal = mat3(model) * normal;
  gl_Position = projection * (view * (model * vec4(position, 1.0)));
}
