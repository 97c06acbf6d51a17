#pragma once
// A user's technique as its technique.json declares it (format "aoreplay-technique" version 1,
// user_techniques/FORMAT.md), read and checked in full before anything is compiled or run: unknown
// keys, bad names, reads of undeclared images and writes nothing reads are InputErrors naming the
// file and the key ("passes[1].reads[0]").
#include <filesystem>
#include <string>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "technique_api/technique.h"

namespace aor {

struct UserImageWrite {
  std::string name;
  std::string formatName;  // as written: r8 | r16f | r32f | rgba8 | rgba16f
  VkFormat format = VK_FORMAT_UNDEFINED;
  bool half = false;  // "scale": "half": ceil(W/2) x ceil(H/2)
};

struct UserPass {
  std::string name;
  std::string shaderText;                // as written in technique.json
  std::filesystem::path shader;          // absolute, inside the technique folder
  std::vector<std::string> reads;        // built-in inputs or earlier writes, in binding order
  std::vector<UserImageWrite> writes;    // in binding order; the first sets the invocation grid
  uint32_t workgroup[2] = {8, 8};
};

enum class UserDenoise { None, Seed000 };

struct UserTechniqueSpec {
  std::filesystem::path file;    // technique.json, absolute
  std::filesystem::path folder;  // its folder, absolute: shader and include paths are relative to it
  std::string display;           // the path as the user gave it, for messages
  std::string name;
  std::vector<Parameter> parameters;  // the file's own, in its order (the shared keys are added by the technique)
  std::vector<Preset> presets;
  std::string defaultPreset;
  std::vector<UserPass> passes;
  std::string output;
  UserDenoise denoise = UserDenoise::None;

  const UserPass* pass(std::string_view name) const;
  const UserImageWrite* write(std::string_view image) const;  // the write of that name in any pass
};

// The built-in inputs a pass may read, in the order FORMAT.md lists them.
const std::vector<std::string>& userBuiltinInputs();
// Pass names the shared blocks and the host use (a user pass may not take them).
const std::vector<std::string>& reservedPassNames();

// Reads and checks `path` (a technique.json); `display` names it in messages. Throws InputError.
UserTechniqueSpec loadUserTechniqueSpec(const std::filesystem::path& path, const std::string& display);

// A relative path written in technique.json (a shader, an #include), checked as capture.json's
// paths are: relative, forward slashes, inside the folder also through symbolic links, an existing
// file. Returns it absolute; throws InputError(file, field).
std::filesystem::path resolveTechniqueFile(const std::filesystem::path& folder, const std::string& text,
                                           const std::string& file, const std::string& field);

}  // namespace aor
