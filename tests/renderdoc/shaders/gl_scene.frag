#version 330 core
// Writes the world-space normal into the RGBA16F target.
in vec3 worldNormal;
layout(location = 0) out vec4 outNormal;

void main() {
  outNormal = vec4(normalize(worldNormal), 1.0);
}
