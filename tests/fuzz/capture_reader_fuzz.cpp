// libFuzzer target for the capture reader: one input is a whole capture folder, so JSON
// validation, path checks, EXR header/channel checks and pixel decoding are all reachable.
// Input layout: capture.json text, then optionally a NUL byte and the bytes of frames/0000.exr
// (a NUL cannot occur in valid JSON, so the split is unambiguous). Bad input must surface as
// aor::InputError; any other exception, crash, leak, sanitizer report or disagreement of the
// bounded JSON parser's two paths is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "capture/capture.h"
#include "json_fuzz_support.h"

namespace {

namespace fs = std::filesystem;

// The private folder of json_fuzz_support.h (removed at exit), reused for every input (libFuzzer
// runs inputs one at a time).
const fs::path& captureFolder() {
  const fs::path& folder = aor::fuzz::privateFolder().path;
  static const bool made = fs::create_directories(folder / "frames") || true;
  (void)made;
  return folder;
}

void writeFile(const fs::path& path, const uint8_t* data, size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fs::path& folder = captureFolder();
  const auto* split = static_cast<const uint8_t*>(std::memchr(data, 0, size));
  const size_t jsonSize = split ? size_t(split - data) : size;
  aor::fuzz::checkBothParsersAgree(data, jsonSize, aor::kCaptureJsonLimits);
  writeFile(folder / "capture.json", data, jsonSize);
  std::error_code ignored;
  fs::remove(folder / "frames" / "0000.exr", ignored);
  if (split) writeFile(folder / "frames" / "0000.exr", split + 1, size - jsonSize - 1);
  try {
    aor::Capture capture = aor::loadCapture(folder);
    for (int frame = 0; frame < int(capture.frames.size()); ++frame) {
      aor::GBuffer gbuffer = aor::loadGBuffer(capture, frame);
      if (gbuffer.depth.size() != size_t(capture.width) * size_t(capture.height)) __builtin_trap();
      (void)aor::loadReference(capture, frame);
    }
  } catch (const aor::InputError&) {
    // The expected outcome for malformed input.
  }
  return 0;
}
