#pragma once
// rd_scene's Vulkan side: a headless device that rasterises the known scene (scene.h) with a
// graphics pipeline into a depth attachment and a world-space normal target, then a colour-only
// overlay pass (a draw without depth), and reads both G-buffer images back.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "scene.h"

namespace aor::rdtest {

struct RenderOptions {
  int width = 160, height = 90;
  VkFormat depthFormat = VK_FORMAT_D32_SFLOAT;
  bool reversed = false;
  bool validate = false;  // Khronos validation with synchronization validation; messages counted
  int cameraLayout = 0;   // scene.vert's kCameraLayout: which copy of the camera positions the vertices
  bool strippedNames = false;  // the vertex shader without its SPIR-V names (as stripped release shaders)
  int samples = 1;  // the G-buffer's sample count; above 1 the read-back is sample 0 (depth) and the average (normals)
  bool finalComposite = false;  // after the scene, a draw in the G-buffer pass with depth test and writes off
  bool glDepthRow = false;      // camera.projection holds GL's depth row; the shader maps clip z to [0, 1]
  float minDepth = 0.0f, maxDepth = 1.0f;  // the viewport's depth range
};

// The rigid model the P.V.M copy of the camera folds in (world -> the model's frame is its inverse).
inline glm::mat4 sceneModel() {
  return glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 0.0f, -0.2f)) * glm::rotate(glm::mat4(1.0f), 0.7f, glm::vec3(0, 1, 0));
}

struct FrameReadback {
  std::vector<float> depth;           // width*height, the attachment's values as floats (Vulkan's unorm rule)
  std::vector<uint16_t> normalsHalf;  // width*height*4, the RGBA16F normal target's bits
};

class SceneRenderer {
 public:
  explicit SceneRenderer(const RenderOptions& options);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  VkInstance instance() const;
  FrameReadback renderFrame(const Camera& camera);
  size_t validationMessages() const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// The float value Vulkan defines for a stored depth texel of `format` (raw = the texel's bits as
// vkCmdCopyImageToBuffer writes them for the depth aspect).
float depthTexelToFloat(VkFormat format, uint32_t raw);

}  // namespace aor::rdtest
