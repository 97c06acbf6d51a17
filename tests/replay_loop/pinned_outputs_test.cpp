// Outputs of the built-in techniques on the shipped captures, pinned as hashes of the decoded float
// values (visibility, bent.xyz) taken before techniques became modules (issue 17). A refactor that
// changes one bit of one pixel of one frame fails here.
//
// Pinned on lavapipe (Mesa 22.3, LLVM 15) on an "AMD EPYC" with AVX-512 (avx512f, avx512vl, fma,
// f16c): llvmpipe compiles shaders for the host CPU, so another instruction set may round
// differently. The test states the CPU it runs on and skips, saying why, on one without AVX-512.
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "gpu_test_support.h"

namespace aor::test {
namespace {

// FNV-1a over the bytes of the floats, in frame order.
struct Fnv1a {
  uint64_t h = 1469598103934665603ull;
  void add(const std::vector<float>& values) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
    for (size_t i = 0; i < values.size() * sizeof(float); ++i) h = (h ^ bytes[i]) * 1099511628211ull;
  }
};

std::string cpuFlag(const std::string& flag) {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("flags", 0) == 0) return (line + " ").find(" " + flag + " ") != std::string::npos ? flag : "";
  return "";
}

std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

struct Pinned {
  const char* capture;
  const char* technique;
  std::vector<std::string> set;  // --set assignments on top of the default preset
  int frames;                    // frames 0:frames are replayed
  uint64_t visibility, bent;     // hashes; bent 0xcbf29ce484222325 (nothing hashed) when bent=0
};

std::string describe(const Pinned& p) {
  std::string set;
  for (const auto& s : p.set) set += " " + s;
  return fmt::format("{} --technique {}{} --frames 0:{}", p.capture, p.technique, set, p.frames);
}

class PinnedOutputs : public ::testing::TestWithParam<Pinned> {};

TEST_P(PinnedOutputs, MatchTheHashesTakenBeforeTechniquesBecameModules) {
  if (cpuFlag("avx512f").empty())
    GTEST_SKIP() << "pinned on an AVX-512 CPU; this one (" << cpuModel() << ") has none, so llvmpipe may round differently";
  const Pinned& p = GetParam();
  auto replayed = replayWithSettings(std::string(AOR_SOURCE_DIR) + "/captures/" + p.capture, p.technique, p.set, 0, p.frames);
  ASSERT_EQ(int(replayed.frames.size()), p.frames);
  Fnv1a visibility, bent;
  for (const auto& f : replayed.frames) {
    visibility.add(f.visibility);
    bent.add(f.bent);
  }
  EXPECT_EQ(visibility.h, p.visibility) << describe(p) << fmt::format(": visibility hash 0x{:016x}", visibility.h);
  EXPECT_EQ(bent.h, p.bent) << describe(p) << fmt::format(": bent hash 0x{:016x}", bent.h);
}

std::vector<Pinned> pinned() {
  return {
#include "pinned_outputs.inc"
  };
}

INSTANTIATE_TEST_SUITE_P(ShippedCaptures, PinnedOutputs, ::testing::ValuesIn(pinned()), [](const auto& info) {
  std::string name = fmt::format("{}_{}", info.param.capture, info.param.technique);
  for (const auto& s : info.param.set) name += "_" + s;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

}  // namespace
}  // namespace aor::test
