// writeCapture -> loadCapture / loadGBuffer / loadReference round trips, and deterministic output.
#include <algorithm>
#include <limits>
#include <map>
#include <set>

#include <Imath/half.h>
#include <fmt/format.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include "test_support.h"

namespace aor::test {
namespace {

constexpr int kW = 8, kH = 6;

// Frames with awkward values: NaN, infinities, -0, denormals, exact 0 and 1 (sky).
std::vector<CaptureFrameData> awkwardFrames() {
  auto frames = makeFrames(kW, kH, 3, /*normals=*/true, /*depth2=*/true, /*refEvery=*/2);
  auto& d = frames[0].gbuffer.depth;
  d[1] = std::numeric_limits<float>::quiet_NaN();
  d[2] = std::numeric_limits<float>::infinity();
  d[3] = -0.0f;
  d[4] = 1e-40f;  // denormal
  d[5] = 0.1f;
  d[6] = std::nextafter(1.0f, 0.0f);
  frames[1].gbuffer.depth2[7] = -std::numeric_limits<float>::infinity();
  (*frames[0].reference)[0] = 0.0f;
  (*frames[0].reference)[1] = 1.0f;
  (*frames[2].reference)[2] = 0.3f;
  frames[0].view[3][0] = 0.1f;  // not exactly representable in decimal
  frames[0].view[3][1] = -1.0f / 3.0f;
  frames[0].view[3][2] = 12345.678f;
  frames[2].view[3][0] = 1e-30f;
  return frames;
}

nlohmann::json awkwardScene() {
  return {{"ao_radius", 0.75}, {"name", "unit-test"}, {"extra", {{"nested", {1, 2, 3}}}}};
}

void expectSameFloats(const std::vector<float>& a, const std::vector<float>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i)
    ASSERT_TRUE(sameBits(a[i], b[i])) << what << "[" << i << "]: wrote " << a[i] << ", read " << b[i];
}

void expectSameMatrix(const glm::mat4& a, const glm::mat4& b, const char* what, int frame) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      EXPECT_TRUE(sameBits(a[c][r], b[c][r]))
          << what << " of frame " << frame << " [" << c << "][" << r << "]: " << a[c][r] << " vs " << b[c][r];
}

// All files below `root`, as relative path -> bytes.
std::map<std::string, std::string> snapshot(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file()) files[fs::relative(e.path(), root).string()] = readBytes(e.path());
  return files;
}

using RoundTrip = TempDirTest;

TEST_F(RoundTrip, ValuesMatricesAndFlagsSurvive) {
  const auto frames = awkwardFrames();
  const fs::path folder = dir / "cap";
  writeCapture(folder, kW, kH, frames, awkwardScene());

  const Capture c = loadCapture(folder);
  EXPECT_EQ(c.width, kW);
  EXPECT_EQ(c.height, kH);
  EXPECT_EQ(c.name, "cap");
  EXPECT_TRUE(c.folder.is_absolute());
  EXPECT_EQ(fs::canonical(c.folder), fs::canonical(folder));
  EXPECT_TRUE(c.hasNormals);
  EXPECT_TRUE(c.hasDepth2);
  EXPECT_EQ(c.scene, awkwardScene());
  ASSERT_EQ(c.frames.size(), frames.size());

  for (int i = 0; i < static_cast<int>(frames.size()); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i));
    const CaptureFrame& cf = c.frames[i];
    EXPECT_EQ(cf.cut, frames[i].cut);
    expectSameMatrix(frames[i].view, cf.view, "view", i);
    expectSameMatrix(frames[i].projection, cf.projection, "projection", i);
    EXPECT_TRUE(cf.gbuffer.is_absolute());
    EXPECT_EQ(cf.gbuffer.filename().string(), fmt::format("{:04}.exr", i));
    EXPECT_EQ(cf.reference.has_value(), frames[i].reference.has_value());

    const GBuffer g = loadGBuffer(c, i);
    EXPECT_EQ(g.width, kW);
    EXPECT_EQ(g.height, kH);
    expectSameFloats(frames[i].gbuffer.depth, g.depth, "depth");
    expectSameFloats(frames[i].gbuffer.depth2, g.depth2, "depth2");
    // Normals are stored as HALF: exactly the half rounding of what was written.
    ASSERT_EQ(g.normals.size(), frames[i].gbuffer.normals.size());
    for (size_t k = 0; k < g.normals.size(); ++k) {
      const float wrote = frames[i].gbuffer.normals[k];
      EXPECT_EQ(g.normals[k], static_cast<float>(Imath::half(wrote))) << "normal component " << k;
      EXPECT_NEAR(g.normals[k], wrote, std::abs(wrote) * (1.0f / 2048) + 1e-7f) << "normal component " << k;
    }

    const auto ref = loadReference(c, i);
    ASSERT_EQ(ref.has_value(), frames[i].reference.has_value());
    if (ref) expectSameFloats(*frames[i].reference, *ref, "visibility");
  }
  // The special values really went through (the checks above compare bit patterns).
  const GBuffer g0 = loadGBuffer(c, 0);
  EXPECT_TRUE(std::isnan(g0.depth[1]));
  EXPECT_TRUE(std::isinf(g0.depth[2]));
  EXPECT_TRUE(std::signbit(g0.depth[3]));
}

TEST_F(RoundTrip, CaptureWithoutNormalsOrReferences) {
  const fs::path folder = dir / "plain";
  writeCapture(folder, kW, kH, makeFrames(kW, kH, 2, /*normals=*/false, /*depth2=*/false, /*refEvery=*/0), nullptr);
  const Capture c = loadCapture(folder);
  EXPECT_FALSE(c.hasNormals);
  EXPECT_FALSE(c.hasDepth2);
  EXPECT_TRUE(c.scene.is_object());
  EXPECT_TRUE(c.scene.empty());
  const GBuffer g = loadGBuffer(c, 1);
  EXPECT_EQ(g.depth.size(), static_cast<size_t>(kW * kH));
  EXPECT_TRUE(g.normals.empty());
  EXPECT_TRUE(g.depth2.empty());
  EXPECT_FALSE(loadReference(c, 0).has_value());
  const auto header = readExrHeader(c.frames[0].gbuffer);
  EXPECT_EQ(header.channels.size(), 1u);
}

TEST_F(RoundTrip, OutputIsByteIdenticalAcrossRuns) {
  const auto frames = awkwardFrames();
  writeCapture(dir / "a", kW, kH, frames, awkwardScene());
  writeCapture(dir / "b", kW, kH, frames, awkwardScene());
  const auto a = snapshot(dir / "a");
  const auto b = snapshot(dir / "b");
  ASSERT_EQ(a.size(), 1u + 3u + 2u + 1u);  // capture.json, 3 G-buffers, 2 references, .aoreplay-result.json
  EXPECT_TRUE(a == b) << "two writes of the same capture differ";
  // Rewriting in place replaces the folder and gives the same bytes again.
  writeCapture(dir / "a", kW, kH, frames, awkwardScene());
  EXPECT_TRUE(snapshot(dir / "a") == a);
  // No temporary folder is left next to it.
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST_F(RoundTrip, ExrHeadersCarryOnlyTheRequiredAttributes) {
  writeCapture(dir / "cap", kW, kH, makeFrames(kW, kH, 1, true, true), nullptr);
  for (const char* name : {"frames/0000.exr", "frames/0000.ref.exr"}) {
    Imf::InputFile file((dir / "cap" / name).c_str());
    std::set<std::string> attributes;
    for (auto it = file.header().begin(); it != file.header().end(); ++it) attributes.insert(it.name());
    const std::set<std::string> required = {"channels",         "compression",        "dataWindow",
                                            "displayWindow",    "lineOrder",          "pixelAspectRatio",
                                            "screenWindowCenter", "screenWindowWidth"};
    EXPECT_EQ(attributes, required) << name;  // in particular no capDate / utcOffset
    EXPECT_EQ(file.header().compression(), Imf::ZIP_COMPRESSION) << name;
  }
  const auto g = readExrHeader(dir / "cap/frames/0000.exr");
  const std::map<std::string, ExrPixelType> expected = {{"depth", ExrPixelType::Float},
                                                        {"depth2", ExrPixelType::Float},
                                                        {"normal.X", ExrPixelType::Half},
                                                        {"normal.Y", ExrPixelType::Half},
                                                        {"normal.Z", ExrPixelType::Half}};
  EXPECT_EQ(g.channels, expected);
  const auto r = readExrHeader(dir / "cap/frames/0000.ref.exr");
  EXPECT_EQ(r.channels, (std::map<std::string, ExrPixelType>{{"visibility", ExrPixelType::Float}}));
}

TEST_F(RoundTrip, CaptureJsonLayout) {
  auto frames = makeFrames(kW, kH, 3, true, false, 2);
  writeCapture(dir / "cap", kW, kH, frames, {{"ao_radius", 0.5}});
  const std::string text = readBytes(dir / "cap/capture.json");
  // Fixed key order, pretty-printed.
  const auto pos = [&](const char* key) { return text.find(std::string("\"") + key + "\""); };
  EXPECT_LT(pos("format"), pos("version"));
  EXPECT_LT(pos("version"), pos("width"));
  EXPECT_LT(pos("width"), pos("height"));
  EXPECT_LT(pos("height"), pos("frames"));
  EXPECT_LT(pos("frames"), pos("scene"));
  EXPECT_NE(text.find("\n  \"format\": \"aoreplay-capture\""), std::string::npos) << text;
  const auto j = nlohmann::json::parse(text);
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(j["frames"][0]["gbuffer"], "frames/0000.exr");
  EXPECT_EQ(j["frames"][0]["reference"], "frames/0000.ref.exr");
  EXPECT_FALSE(j["frames"][1].contains("reference"));
  EXPECT_EQ(j["frames"][2]["cut"], true);
  // Column-major: element 12..14 is the translation column of the view matrix.
  for (int k = 0; k < 16; ++k)
    EXPECT_EQ(j["frames"][1]["view"][k].get<double>(), static_cast<double>(frames[1].view[k / 4][k % 4])) << k;
  EXPECT_EQ(j["scene"]["ao_radius"], 0.5);
}

TEST_F(RoundTrip, NameAndFolderWithTrailingSlash) {
  writeCapture(dir / "named", kW, kH, makeFrames(kW, kH, 1), nullptr);
  const Capture c = loadCapture(fs::path((dir / "named").string() + "/"));
  EXPECT_EQ(c.name, "named");
  EXPECT_TRUE(c.folder.is_absolute());
  EXPECT_EQ(c.folder.filename().string(), "named");
}

TEST_F(RoundTrip, WriteReplacesAnEarlierCapture) {
  writeCapture(dir / "cap", kW, kH, makeFrames(kW, kH, 3), nullptr);
  writeCapture(dir / "cap", kW, kH, makeFrames(kW, kH, 1), nullptr);
  EXPECT_EQ(loadCapture(dir / "cap").frames.size(), 1u);
  EXPECT_FALSE(fs::exists(dir / "cap/frames/0002.exr"));  // old files are gone
}

TEST_F(RoundTrip, WriteRefusesToReplaceAFolderThatIsNotACapture) {
  fs::create_directories(dir / "precious");
  writeBytes(dir / "precious/notes.txt", "keep me");
  EXPECT_INPUT_ERROR(writeCapture(dir / "precious", kW, kH, makeFrames(kW, kH, 1), nullptr), "precious",
                     "holds \"notes.txt\", which aoreplay did not write there");
  EXPECT_EQ(readBytes(dir / "precious/notes.txt"), "keep me");
}

TEST_F(RoundTrip, InvalidInputLeavesNoPartialOutput) {
  writeCapture(dir / "cap", kW, kH, makeFrames(kW, kH, 2), nullptr);
  const auto before = snapshot(dir / "cap");
  auto frames = makeFrames(kW, kH, 2);
  frames[1].gbuffer.depth.pop_back();  // wrong size
  EXPECT_THROW(writeCapture(dir / "cap", kW, kH, frames, nullptr), std::invalid_argument);
  frames = makeFrames(kW, kH, 2);
  frames[1].projection = glm::orthoRH_ZO(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 10.0f);
  EXPECT_THROW(writeCapture(dir / "cap", kW, kH, frames, nullptr), std::invalid_argument);
  frames = makeFrames(kW, kH, 2);
  frames[1].gbuffer.normals.clear();  // layout differs from frame 0
  EXPECT_THROW(writeCapture(dir / "cap", kW, kH, frames, nullptr), std::invalid_argument);
  EXPECT_TRUE(snapshot(dir / "cap") == before);
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().filename().string(), "cap");
}

TEST_F(RoundTrip, FrameIndexOutOfRange) {
  writeCapture(dir / "cap", kW, kH, makeFrames(kW, kH, 2), nullptr);
  const Capture c = loadCapture(dir / "cap");
  EXPECT_THROW(loadGBuffer(c, 2), std::out_of_range);
  EXPECT_THROW(loadGBuffer(c, -1), std::out_of_range);
  EXPECT_THROW(loadReference(c, 5), std::out_of_range);
}

}  // namespace
}  // namespace aor::test
