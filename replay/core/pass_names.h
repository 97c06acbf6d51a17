#pragma once
// The passes that move data between host and device: copies of the harness (G-buffer upload,
// result read-back), timed and reported like the others but not part of the AO algorithm. Pipeline
// totals leave them out, and `aoreplay compare` does not judge them unless asked.
#include <string_view>

namespace aor {

inline constexpr std::string_view kUploadPass = "upload";
inline constexpr std::string_view kReadbackPass = "readback";

inline bool isHostCopyPass(std::string_view name) { return name == kUploadPass || name == kReadbackPass; }

}  // namespace aor
