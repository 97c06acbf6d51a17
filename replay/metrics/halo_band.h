#pragma once
// The halo band: the background just behind a nearer silhouette, where a screen-space AO
// technique that sees only the nearest layer misses (or invents) what the silhouette hides. Used to
// measure what a second depth layer buys (replay/techniques/sao/README.md).
//
// From linear view distances d (sky <= 0): a pixel q is a silhouette pixel when a 4-neighbour lies
// more than `jump` (relative) farther than it. A non-sky pixel p is in the band when, within its
// AO radius projected to the screen (pixelsPerUnit * radius / d_p pixels, at least 1, at most
// `maxBandPixels`; a square window), there is a silhouette pixel q that p lies more than `jump`
// behind (d_p > d_q (1 + jump)).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace aor {

// The band's radius where a capture has no scene.ao_radius (report.json's metrics.error.halo_band).
inline constexpr double kHaloBandDefaultRadius = 1.0;

struct HaloBandOptions {
  float radius = 1.0f;        // the AO radius, world units
  float pixelsPerUnit = 1.0f; // pixels one world unit covers at distance 1 (horizontal)
  float jump = 0.25f;         // relative depth step that makes a silhouette
  int maxBandPixels = 32;
};

// Width*height flags, 1 in the band.
std::vector<uint8_t> haloBandMask(const std::vector<float>& distances, int width, int height, const HaloBandOptions& options);

struct MaskedError {
  int64_t pixels = 0;
  double rmse = 0, bias = 0;  // bias: mean of output - reference (> 0: too open)
};
// Error of `output` against `reference` over the pixels the mask flags.
MaskedError maskedError(const float* output, const float* reference, const std::vector<uint8_t>& mask);

}  // namespace aor
