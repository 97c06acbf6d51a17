// The capture content hash that keys a results-store series: the same for a copy of the capture
// in another folder, different when any file it names changes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "capture/capture.h"
#include "capture/content_hash.h"
#include "core/sha256.h"

namespace aor {
namespace {
namespace fs = std::filesystem;

TEST(CaptureContentHash, SameForACopyDifferentAfterAnEdit) {
  fs::path original = fs::path(AOR_SOURCE_DIR) / "captures" / "boxes-orbit";
  fs::path copy = fs::temp_directory_path() / ("aor-content-hash-" + std::to_string(getpid())) / "elsewhere";
  fs::remove_all(copy.parent_path());
  fs::create_directories(copy.parent_path());
  fs::copy(original, copy, fs::copy_options::recursive);
  auto hash = captureContentSha256(loadCapture(original));
  EXPECT_EQ(hash.size(), 64u);
  EXPECT_EQ(captureContentSha256(loadCapture(copy)), hash);
  // One byte of the last frame's G-buffer, inside the file (its header and size unchanged).
  auto capture = loadCapture(copy);
  fs::path gbuffer = capture.frames.back().gbuffer;
  {
    std::fstream file(gbuffer, std::ios::in | std::ios::out | std::ios::binary);
    file.seekg(-1, std::ios::end);
    char last = 0;
    file.read(&last, 1);
    file.seekp(-1, std::ios::end);
    last = char(last ^ 1);
    file.write(&last, 1);
  }
  EXPECT_NE(captureContentSha256(capture), hash);
  fs::remove_all(copy.parent_path());
}

TEST(ContentHash, KnownDigests) {  // as sha256sum prints them
  EXPECT_EQ(textSha256(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(textSha256("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

}  // namespace
}  // namespace aor
