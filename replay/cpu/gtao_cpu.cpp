#include "cpu/gtao_cpu.h"

#include <cmath>

#include <glm/gtc/packing.hpp>

#include "gtao/gtao.h"
#include "metrics/depth.h"

namespace aor {

namespace shader {
namespace {

// Everything gtao_pixel.glsl expects from its includer, as members.
struct GtaoCpuPixel {
  GtaoConstants pc;
  int kSlices;
  int kSteps;
  bool kBent;
  bool kThin;
  const std::vector<float>* distance;
  const std::vector<vec3>* viewNormals;
  uint64_t loads = 0;  // calls of the two load functions, as the counting build counts them

  float gtaoLoadDistance(ivec2 pixel) {
    ++loads;
    return (*distance)[size_t(pixel.y) * size_t(pc.size.x) + size_t(pixel.x)];
  }
  vec3 gtaoLoadViewNormal(ivec2 pixel) {
    ++loads;
    return (*viewNormals)[size_t(pixel.y) * size_t(pc.size.x) + size_t(pixel.x)];
  }
#include "gtao/gtao_pixel.glsl"
};

}  // namespace
}  // namespace shader

CpuAoImage gtaoOnCpu(const GBuffer& gbuffer, const FrameCamera& camera, const GtaoSettings& settings,
                     uint64_t* imageLoads) {
  size_t pixels = size_t(camera.width) * size_t(camera.height);
  std::vector<float> distance = linearViewDistances({gbuffer.depth.data(), pixels}, camera.projection);
  std::vector<glm::vec3> normals(pixels, glm::vec3(0.0f));
  glm::mat3 worldToView(camera.view);
  for (size_t i = 0; i < pixels && !gbuffer.normals.empty(); ++i) {
    // The GPU receives normals as half floats: quantise the same way.
    glm::vec3 n;
    for (int c = 0; c < 3; ++c) n[c] = glm::unpackHalf1x16(glm::packHalf1x16(gbuffer.normals[3 * i + size_t(c)]));
    normals[i] = worldToView * n;  // normalised (or replaced when unusable) by gtaoPixelCentre
  }
  shader::GtaoCpuPixel pixel{gtaoConstants(camera, settings), settings.slices, settings.steps, settings.bent,
                             settings.thin > 0.0f, &distance, &normals};
  // At half resolution texel t is pixel 2t with the texel's noise, as gtao.comp's main() does.
  int divisor = aoResolutionDivisor(settings);
  glm::ivec2 size = aoWorkingSize(camera, settings);
  CpuAoImage image = computeAoImage<float>(size.x, size.y, settings.bent, [&](glm::ivec2 t, glm::vec3& bent) {
    return pixel.gtaoPixelWithNoise(t * divisor, shader::gtaoNoise(t, camera.frameIndex), bent);
  });
  if (imageLoads) *imageLoads = pixel.loads;
  return image;
}

}  // namespace aor
