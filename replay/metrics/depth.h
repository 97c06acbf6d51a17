#pragma once
// Depth-attachment conventions shared by the metrics, the CPU mirrors, the replayer's camera
// checks and the GPU passes' projection terms (passes/camera.cpp).
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace aor {

// Reversed depth (near = 1, far = 0): depth = -P22 + P32 / distance falls with distance exactly
// when P32 > 0.
inline bool isReversedDepth(const glm::mat4& projection) { return projection[3][2] > 0.0f; }

// Linear view distance of every pixel with the shader's own conversion (shaders/linearize_depth.h):
// sky and invalid depth give a distance <= 0.
std::vector<float> linearViewDistances(std::span<const float> depth, const glm::mat4& projection);
// The same into `distances` (as many elements as `depth`), for callers that split the work.
void linearViewDistances(std::span<const float> depth, const glm::mat4& projection, std::span<float> distances);

}  // namespace aor
