#pragma once
// AO settings of a run: presets and `--set KEY=VALUE` parsing with range checks. The same struct
// keys history validity: history recorded under other settings is never blended.
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "gtao.h"  // kGtaoFalloffRange

namespace aor {

// gtao: the real-time pipeline (GTAO -> spatial -> temporal). reference: the same GTAO integral
// evaluated exhaustively on the depth buffer (no noise, no denoise; see shaders/gtao_reference.comp).
enum class AoTechnique { Gtao, Reference };

struct AoSettings {
  AoTechnique technique = AoTechnique::Gtao;
  float radius = 1.0f;        // world units; default: the capture's scene.ao_radius, else 1
  int slices = 3;             // preset "high"
  int steps = 3;
  float falloff = shader::kGtaoFalloffRange;  // fraction of the radius over which sample weight fades; 0 = hard cut-off
  float power = 1.0f;         // final exponent
  float thin = 0.0f;          // thin-occluder compensation
  int spatial = 1;            // 0/1
  float temporal = 0.9f;      // history weight 0..0.98; 0 = no temporal pass
  int bent = 1;               // 0/1: bent normals computed and written
  int halfRes = 0;            // 0/1: GTAO and the spatial blur at half resolution, upsampled in the last pass

  bool operator==(const AoSettings&) const = default;
};

// Presets set slices x steps: low 1x2, medium 2x2, high 3x3, ultra 9x3. Throws InputError.
void applyPreset(AoSettings& settings, std::string_view preset);
// "KEY=VALUE"; unknown keys and out-of-range values throw InputError naming the key.
void applySetting(AoSettings& settings, std::string_view assignment);
nlohmann::json toJson(const AoSettings& settings);
const char* techniqueName(AoTechnique technique);
AoTechnique parseTechnique(std::string_view name);  // "gtao" | "reference"; throws InputError
// Sets the technique; `reference` also sets spatial=0, temporal=0 (it is never denoised) and
// half_res=0 (it is the full-resolution yardstick).
void applyTechnique(AoSettings& settings, AoTechnique technique);
std::string describeSettingKeys();

}  // namespace aor
