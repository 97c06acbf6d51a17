#version 450
// Writes the world-space normal; the overlay pass uses the same shader into a colour-only target.
layout(location = 0) in vec3 worldNormal;
layout(location = 0) out vec4 outNormal;

void main() {
  outNormal = vec4(normalize(worldNormal), 1.0);
}
