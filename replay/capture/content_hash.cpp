#include "capture/content_hash.h"

#include <set>

#include <fmt/format.h>

#include "core/sha256.h"

namespace aor {
namespace fs = std::filesystem;

std::string captureContentSha256(const Capture& capture) {
  std::set<std::string> files{"capture.json"};  // relative, generic form: the same on every machine
  for (const auto& frame : capture.frames) {
    files.insert(fs::relative(frame.gbuffer, capture.folder).generic_string());
    if (frame.reference) files.insert(fs::relative(*frame.reference, capture.folder).generic_string());
  }
  if (capture.geometry) files.insert(fs::relative(*capture.geometry, capture.folder).generic_string());
  Sha256 digest;
  for (const auto& name : files) {
    const fs::path path = capture.folder / name;
    digest.update(fmt::format("{}\n{}\n", name, fs::file_size(path)));
    digest.updateWithFile(path);
  }
  return digest.hex();
}

}  // namespace aor
