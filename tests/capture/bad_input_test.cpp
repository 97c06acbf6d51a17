// The bad-input corpus: each case starts from a valid capture written by writeCapture, breaks one
// thing, and expects an aor::InputError whose message names the file, the frame and the field or
// channel. The control test shows the unbroken capture loads, so every error comes from the break.
#include <algorithm>

#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <glm/gtc/matrix_transform.hpp>

#include "test_support.h"

namespace aor::test {
namespace {

constexpr int kW = 8, kH = 6;

class BadInput : public TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    cap = dir / "cap";
    // 2 frames, normals, a reference on both; frame 1 has a reversed infinite projection.
    writeCapture(cap, kW, kH, makeFrames(kW, kH, 2, true, false, 1), {{"ao_radius", 0.5}});
    doc = readJson(cap / "capture.json");
  }
  void save() { writeJson(cap / "capture.json", doc); }
  void saveText(const std::string& text) { writeBytes(cap / "capture.json", text); }
  Capture load() { return loadCapture(cap); }
  nlohmann::json& frame(int i) { return doc["frames"][i]; }
  void setMatrix(int i, const char* key, const glm::mat4& m) {
    auto a = nlohmann::json::array();
    for (int k = 0; k < 16; ++k) a.push_back(m[k / 4][k % 4]);
    frame(i)[key] = a;
  }
  glm::mat4 projection(int i) {
    glm::mat4 m;
    for (int k = 0; k < 16; ++k) m[k / 4][k % 4] = frame(i)["projection"][k].get<float>();
    return m;
  }
  fs::path cap;
  nlohmann::json doc;
};

const std::string kJson = "cap/capture.json";

TEST_F(BadInput, ControlTheUnbrokenCaptureLoads) {
  const Capture c = load();
  EXPECT_EQ(c.frames.size(), 2u);
  save();  // re-serialised by the test helper: still valid
  EXPECT_EQ(load().frames.size(), 2u);
}

// ---- capture.json as a file ----------------------------------------------------------------------

TEST_F(BadInput, CaptureFolderMissing) {
  EXPECT_INPUT_ERROR(loadCapture(dir / "nowhere"), "nowhere", "does not exist");
}

TEST_F(BadInput, CaptureJsonMissing) {
  fs::remove(cap / "capture.json");
  EXPECT_INPUT_ERROR(load(), kJson, "does not exist");
}

TEST_F(BadInput, MalformedJsonNamesThePosition) {
  saveText("{\n  \"format\": \"aoreplay-capture\",\n  \"version\": 1,,\n}\n");
  EXPECT_INPUT_ERROR(load(), kJson, "malformed JSON", "line 3, column");
}

TEST_F(BadInput, EmptyFile) {
  saveText("");
  EXPECT_INPUT_ERROR(load(), kJson, "malformed JSON");
}

TEST_F(BadInput, NumberTooLargeForADouble) {
  std::string text = doc.dump(2);
  const std::string first = "\"projection\": [\n";
  const auto at = text.find(first);
  ASSERT_NE(at, std::string::npos);
  const auto end = text.find(',', at);
  text.replace(at + first.size(), end - at - first.size(), "1e999");
  saveText(text);
  EXPECT_INPUT_ERROR(load(), kJson, "malformed JSON", "1e999", "line ");
}

TEST_F(BadInput, TopLevelNotAnObject) {
  saveText("[1, 2, 3]");
  EXPECT_INPUT_ERROR(load(), kJson, "top level must be a JSON object");
}

TEST_F(BadInput, DuplicateKey) {
  std::string text = doc.dump(2);
  text.insert(text.find('{') + 1, "\n  \"width\": 9,");
  saveText(text);
  EXPECT_INPUT_ERROR(load(), kJson, "field \"width\"", "twice");
}

// ---- top-level fields ------------------------------------------------------------------------------

TEST_F(BadInput, WrongFormat) {
  doc["format"] = "aoreplay-capture-v2";
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"format\"", "aoreplay-capture-v2");
}

TEST_F(BadInput, MissingFormat) {
  doc.erase("format");
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"format\"", "missing");
}

TEST_F(BadInput, WrongVersion) {
  doc["version"] = 2;
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"version\"", "version 2 is not supported", "supported versions: 1");
}

TEST_F(BadInput, VersionNotAnInteger) {
  doc["version"] = "1";
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"version\"", "string \"1\"");
  doc["version"] = 1.0;
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"version\"", "number 1.0");
}

TEST_F(BadInput, MissingTopLevelField) {
  doc.erase("height");
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"height\"", "missing");
}

TEST_F(BadInput, UnknownTopLevelField) {
  doc["widht"] = 8;
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"widht\"", "unknown field", "did you mean \"width\"");
}

TEST_F(BadInput, WidthAsString) {
  doc["width"] = "8";
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"width\"", "positive integer", "string \"8\"");
}

TEST_F(BadInput, WidthNotPositiveOrFractional) {
  doc["width"] = 0;
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"width\"", "positive integer");
  doc["width"] = -8;
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"width\"", "positive integer");
  doc["width"] = 8.5;
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"width\"", "positive integer", "8.5");
}

TEST_F(BadInput, WidthTooLarge) {
  doc["width"] = 100000;
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"width\"", "100000", "16384");
}

TEST_F(BadInput, PixelCountTooLarge) {
  doc["width"] = 16384;
  doc["height"] = 8192;
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"height\"", "16384x8192", "67108864");
}

TEST_F(BadInput, SceneMustBeAnObject) {
  doc["scene"] = nlohmann::json::array({1, 2});
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"scene\"", "expected an object");
}

TEST_F(BadInput, SceneIsFreeForm) {
  doc["scene"] = {{"ao_radius", 0.25}, {"whatever", {{"nested", {1, "two", nullptr}}}}};
  save();
  EXPECT_EQ(load().scene, doc["scene"]);
}

TEST_F(BadInput, FramesWrongType) {
  doc["frames"] = nlohmann::json::object();
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"frames\"", "an object");
}

TEST_F(BadInput, FramesEmpty) {
  doc["frames"] = nlohmann::json::array();
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "field \"frames\"", "empty");
}

// ---- frame fields --------------------------------------------------------------------------------

TEST_F(BadInput, FrameNotAnObject) {
  frame(1) = 3;
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 1", "field \"frames\"", "number 3");
}

TEST_F(BadInput, MissingFrameField) {
  frame(1).erase("projection");
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 1", "field \"projection\"", "missing");
  doc = readJson(cap / "capture.json");
  doc["frames"][1] = readJson(cap / "capture.json")["frames"][0];
  frame(0).erase("gbuffer");
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 0", "field \"gbuffer\"", "missing");
}

TEST_F(BadInput, UnknownFrameFieldLikeATypo) {
  frame(1)["refrence"] = frame(1)["reference"];
  frame(1).erase("reference");
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 1", "field \"refrence\"", "unknown field", "did you mean \"reference\"");
}

TEST_F(BadInput, CutAsNumber) {
  frame(1)["cut"] = 1;
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 1", "field \"cut\"", "true or false", "number 1");
}

TEST_F(BadInput, GbufferAsNumber) {
  frame(0)["gbuffer"] = 5;
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 0", "field \"gbuffer\"", "expected a string");
}

TEST_F(BadInput, ReferenceAsNull) {
  frame(1)["reference"] = nullptr;
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 1", "field \"reference\"", "null");
}

TEST_F(BadInput, ViewNot16Numbers) {
  frame(1)["view"].erase(15);
  save();
  EXPECT_INPUT_ERROR(load(), "cap/capture.json: frame 1: field \"view\": expected 16 numbers, got 15");
}

TEST_F(BadInput, ViewNotAnArray) {
  frame(0)["view"] = "identity";
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 0", "field \"view\"", "string \"identity\"");
}

TEST_F(BadInput, MatrixElementNotANumber) {
  frame(1)["projection"][4] = "0";
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 1", "field \"projection\"", "element 4 is not a number");
}

TEST_F(BadInput, MatrixElementNotFiniteAsFloat) {
  frame(0)["projection"][5] = 1e39;  // a finite double, infinite as a float
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 0", "field \"projection\"", "element 5", "not finite");
}

TEST_F(BadInput, SingularView) {
  glm::mat4 v = makeView(1);
  v[2] = glm::vec4(0.0f);  // flattens z
  setMatrix(1, "view", v);
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 1", "field \"view\"", "view is singular");
}

TEST_F(BadInput, ViewFarFromTheOriginIsNotSingular) {
  // Invertibility is judged relative to scale: a rotation with a huge translation is fine.
  glm::mat4 v = glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0, 1, 0));
  v[3] = glm::vec4(1e6f, -2e5f, 3e6f, 1.0f);
  setMatrix(1, "view", v);
  save();
  EXPECT_NO_THROW(load());
}

TEST_F(BadInput, OrthographicProjection) {
  setMatrix(0, "projection", glm::orthoRH_ZO(-4.0f, 4.0f, -3.0f, 3.0f, 0.1f, 50.0f));
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 0", "field \"projection\"",
                     "projection is not a perspective projection (P[2][3] must be -1", "orthographic");
}

TEST_F(BadInput, ProjectionWithOffAxisTerm) {
  glm::mat4 p = projection(0);
  p[0][1] = 0.5f;
  setMatrix(0, "projection", p);
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 0", "field \"projection\"", "not a perspective projection",
                     "P[0][1] must be 0");
}

TEST_F(BadInput, SingularProjection) {
  glm::mat4 p = projection(1);
  p[3][2] = 0.0f;
  setMatrix(1, "projection", p);
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 1", "field \"projection\"", "projection is singular", "P[3][2]");
  p = projection(0);
  p[1][1] = 0.0f;
  setMatrix(0, "projection", p);
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 0", "field \"projection\"", "projection is singular", "P[1][1]");
}

TEST_F(BadInput, ProjectionVariantsThatAreAccepted) {
  // Standard finite (frame 0), reversed infinite with jitter and y flip (frame 1, from
  // makeFrames), standard infinite and reversed finite.
  setMatrix(0, "projection", glm::infinitePerspectiveRH(glm::radians(70.0f), 4.0f / 3.0f, 0.1f));
  glm::mat4 reversed = glm::perspective(glm::radians(50.0f), 4.0f / 3.0f, 100.0f, 0.1f);  // near/far swapped
  setMatrix(1, "projection", reversed);
  save();
  const Capture c = load();
  EXPECT_LT(c.frames[0].projection[3][2], 0.0f);  // standard
  EXPECT_GT(c.frames[1].projection[3][2], 0.0f);  // reversed
}

// ---- paths -------------------------------------------------------------------------------------------

TEST_F(BadInput, AbsolutePath) {
  frame(1)["gbuffer"] = (cap / "frames/0001.exr").string();  // exists, but absolute
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 1", "field \"gbuffer\"", "absolute path");
}

TEST_F(BadInput, DotDotEscapesTheFolder) {
  fs::copy_file(cap / "frames/0000.exr", dir / "outside.exr");
  frame(0)["gbuffer"] = "../outside.exr";
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 0", "field \"gbuffer\"", "leaves the capture folder");
  frame(0)["gbuffer"] = "frames/../../outside.exr";
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 0", "field \"gbuffer\"", "leaves the capture folder");
}

TEST_F(BadInput, DotDotInsideTheFolderIsFine) {
  frame(0)["gbuffer"] = "frames/../frames/./0000.exr";
  save();
  EXPECT_EQ(load().frames[0].gbuffer, cap / "frames/0000.exr");
}

TEST_F(BadInput, SymlinkEscapesTheFolder) {
  fs::copy_file(cap / "frames/0000.exr", dir / "outside.exr");
  fs::create_symlink(dir / "outside.exr", cap / "frames/link.exr");
  frame(0)["gbuffer"] = "frames/link.exr";
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 0", "field \"gbuffer\"", "outside the capture folder");
}

TEST_F(BadInput, BackslashPath) {
  frame(0)["gbuffer"] = "frames\\0000.exr";
  save();
  EXPECT_INPUT_ERROR(load(), kJson, "frame 0", "field \"gbuffer\"", "backslash");
}

// ---- G-buffer EXRs -------------------------------------------------------------------------------

TEST_F(BadInput, MissingGbufferExr) {
  fs::remove(cap / "frames/0001.exr");
  EXPECT_INPUT_ERROR(load(), kJson, "frame 1", "field \"gbuffer\"", "frames/0001.exr", "does not exist");
}

TEST_F(BadInput, TruncatedExrHalfItsBytes) {
  const fs::path exr = cap / "frames/0001.exr";
  truncateFile(exr, fs::file_size(exr) / 2);
  EXPECT_INPUT_ERROR(load(), "frames/0001.exr", "frame 1");
}

TEST_F(BadInput, TruncatedExrAtEveryLength) {
  // However much is cut off, loading reports it instead of crashing or accepting the file.
  const fs::path exr = cap / "frames/0001.exr";
  const std::string bytes = readBytes(exr);
  for (size_t size = 0; size < bytes.size(); size += (size < 64 ? 1 : 5)) {
    SCOPED_TRACE("truncated to " + std::to_string(size) + " of " + std::to_string(bytes.size()) + " bytes");
    writeBytes(exr, bytes.substr(0, size));
    EXPECT_INPUT_ERROR(load(), "frames/0001.exr", "frame 1");
  }
  writeBytes(exr, bytes);
  EXPECT_NO_THROW(load());
}

TEST_F(BadInput, GarbageNamedExr) {
  std::string garbage;
  for (int i = 0; i < 300; ++i) garbage.push_back(static_cast<char>(hash01(static_cast<std::uint32_t>(i)) * 256));
  writeBytes(cap / "frames/0000.exr", garbage);
  EXPECT_INPUT_ERROR(load(), "frames/0000.exr", "frame 0", "not a readable OpenEXR file");
}

// Offset of the line offset table of a small single-chunk scan-line EXR: the 8 bytes whose value
// is their own end position (the one chunk starts right after the table).
size_t findSingleChunkTable(const std::string& bytes) {
  for (size_t p = 8; p + 8 <= bytes.size(); ++p) {
    std::uint64_t v = 0;
    for (int k = 0; k < 8; ++k) v |= std::uint64_t(static_cast<unsigned char>(bytes[p + k])) << (8 * k);
    if (v == p + 8) return p;
  }
  return std::string::npos;
}

TEST_F(BadInput, ExrOffsetTablePointsPastTheEnd) {
  const fs::path exr = cap / "frames/0001.exr";
  std::string bytes = readBytes(exr);
  const size_t table = findSingleChunkTable(bytes);
  ASSERT_NE(table, std::string::npos);
  std::fill(bytes.begin() + table, bytes.begin() + table + 7, '\x7f');
  writeBytes(exr, bytes);
  EXPECT_INPUT_ERROR(load(), "frames/0001.exr", "frame 1");
}

TEST_F(BadInput, MissingDepthChannel) {
  writeExrWithChannels(cap / "frames/0001.exr", kW, kH,
                       {{"normal.X", ExrPixelType::Half}, {"normal.Y", ExrPixelType::Half}, {"normal.Z", ExrPixelType::Half}});
  EXPECT_INPUT_ERROR(load(), "frames/0001.exr", "frame 1", "channel \"depth\"", "missing");
}

TEST_F(BadInput, DepthAsHalf) {
  writeExrWithChannels(cap / "frames/0001.exr", kW, kH,
                       {{"depth", ExrPixelType::Half},
                        {"normal.X", ExrPixelType::Half},
                        {"normal.Y", ExrPixelType::Half},
                        {"normal.Z", ExrPixelType::Half}});
  EXPECT_INPUT_ERROR(load(), "frames/0001.exr", "frame 1", "channel \"depth\"", "HALF", "FLOAT");
}

TEST_F(BadInput, PartialNormals) {
  writeExrWithChannels(cap / "frames/0001.exr", kW, kH,
                       {{"depth", ExrPixelType::Float}, {"normal.X", ExrPixelType::Half}, {"normal.Y", ExrPixelType::Half}});
  EXPECT_INPUT_ERROR(load(), "frames/0001.exr", "frame 1", "channel \"normal.Z\"", "normal.X and normal.Y are present");
}

TEST_F(BadInput, Depth2AsHalf) {
  writeExrWithChannels(cap / "frames/0000.exr", kW, kH,
                       {{"depth", ExrPixelType::Float},
                        {"depth2", ExrPixelType::Half},
                        {"normal.X", ExrPixelType::Half},
                        {"normal.Y", ExrPixelType::Half},
                        {"normal.Z", ExrPixelType::Half}});
  EXPECT_INPUT_ERROR(load(), "frames/0000.exr", "frame 0", "channel \"depth2\"", "HALF");
}

TEST_F(BadInput, MisspeltChannel) {
  writeExrWithChannels(cap / "frames/0001.exr", kW, kH,
                       {{"depth", ExrPixelType::Float},
                        {"normal.x", ExrPixelType::Half},
                        {"normal.y", ExrPixelType::Half},
                        {"normal.z", ExrPixelType::Half}});
  EXPECT_INPUT_ERROR(load(), "frames/0001.exr", "frame 1", "channel \"normal.x\"", "case-sensitive");
}

TEST_F(BadInput, UnrelatedExtraChannelsAreIgnored) {
  writeExrWithChannels(cap / "frames/0001.exr", kW, kH,
                       {{"depth", ExrPixelType::Float},
                        {"normal.X", ExrPixelType::Half},
                        {"normal.Y", ExrPixelType::Half},
                        {"normal.Z", ExrPixelType::Float},
                        {"albedo.R", ExrPixelType::Half}});
  const Capture c = load();
  EXPECT_TRUE(c.hasNormals);
  EXPECT_EQ(loadGBuffer(c, 1).normals[2], 0.5f);
}

TEST_F(BadInput, SizeMismatchBetweenFrameAndCapture) {
  writeExrWithChannels(cap / "frames/0001.exr", kW + 1, kH,
                       {{"depth", ExrPixelType::Float},
                        {"normal.X", ExrPixelType::Half},
                        {"normal.Y", ExrPixelType::Half},
                        {"normal.Z", ExrPixelType::Half}});
  EXPECT_INPUT_ERROR(load(), "frames/0001.exr", "frame 1", "image is 9x6", "capture.json says 8x6");
}

TEST_F(BadInput, LayoutDiffersBetweenFrames) {
  writeExrWithChannels(cap / "frames/0001.exr", kW, kH, {{"depth", ExrPixelType::Float}});
  EXPECT_INPUT_ERROR(load(), "frames/0001.exr", "frame 1", "channel \"normal.X\"", "frame 0");
  writeExrWithChannels(cap / "frames/0001.exr", kW, kH,
                       {{"depth", ExrPixelType::Float},
                        {"depth2", ExrPixelType::Float},
                        {"normal.X", ExrPixelType::Half},
                        {"normal.Y", ExrPixelType::Half},
                        {"normal.Z", ExrPixelType::Half}});
  EXPECT_INPUT_ERROR(load(), "frames/0001.exr", "frame 1", "channel \"depth2\"", "frame 0");
}

// ---- reference EXRs ------------------------------------------------------------------------------

TEST_F(BadInput, MissingReference) {
  fs::remove(cap / "frames/0001.ref.exr");
  EXPECT_INPUT_ERROR(load(), kJson, "frame 1", "field \"reference\"", "frames/0001.ref.exr", "does not exist");
}

TEST_F(BadInput, ReferenceWithoutVisibility) {
  writeExrWithChannels(cap / "frames/0000.ref.exr", kW, kH, {{"occlusion", ExrPixelType::Float}});
  EXPECT_INPUT_ERROR(load(), "frames/0000.ref.exr", "frame 0", "channel \"visibility\"", "missing", "occlusion");
}

TEST_F(BadInput, ReferenceVisibilityAsHalf) {
  writeExrWithChannels(cap / "frames/0001.ref.exr", kW, kH, {{"visibility", ExrPixelType::Half}});
  EXPECT_INPUT_ERROR(load(), "frames/0001.ref.exr", "frame 1", "channel \"visibility\"", "HALF");
}

TEST_F(BadInput, ReferenceSizeMismatch) {
  writeExrWithChannels(cap / "frames/0001.ref.exr", kW, kH - 1, {{"visibility", ExrPixelType::Float}});
  EXPECT_INPUT_ERROR(load(), "frames/0001.ref.exr", "frame 1", "image is 8x5");
}

// ---- pixel data that only fails when read ---------------------------------------------------------

TEST_F(BadInput, LoadGBufferOnTruncatedDataThrowsInputError) {
  const Capture c = load();  // valid when loaded ...
  const fs::path exr = cap / "frames/0001.exr";
  truncateFile(exr, fs::file_size(exr) - 20);  // ... then the pixel data is cut short; the header is intact
  EXPECT_NO_THROW(Imf::InputFile(exr.c_str()).header());
  EXPECT_INPUT_ERROR(loadGBuffer(c, 1), "frames/0001.exr", "frame 1");
  EXPECT_INPUT_ERROR(readExrChannels(exr, {"depth"}), "frames/0001.exr");
  EXPECT_NO_THROW(loadGBuffer(c, 0));  // the other frame is unaffected
}

TEST_F(BadInput, LoadReferenceOnTruncatedDataThrowsInputError) {
  const Capture c = load();
  const fs::path exr = cap / "frames/0000.ref.exr";
  truncateFile(exr, fs::file_size(exr) - 20);
  EXPECT_INPUT_ERROR(loadReference(c, 0), "frames/0000.ref.exr", "frame 0");
}

TEST_F(BadInput, LoadGBufferOnCorruptCompressedDataThrowsInputError) {
  // Structure intact (loadCapture accepts it), compressed bytes damaged: zlib's checksum fails.
  // Constant channels so that the chunk really is compressed (OpenEXR stores a chunk raw when
  // compression does not make it smaller, and raw bytes cannot be detected as damaged).
  const fs::path exr = cap / "frames/0001.exr";
  writeExrWithChannels(exr, kW, kH,
                       {{"depth", ExrPixelType::Float},
                        {"normal.X", ExrPixelType::Half},
                        {"normal.Y", ExrPixelType::Half},
                        {"normal.Z", ExrPixelType::Half}});
  ASSERT_LT(fs::file_size(exr), 400u) << "expected a compressed chunk";
  std::string bytes = readBytes(exr);
  std::fill(bytes.end() - 24, bytes.end(), '\x5a');
  writeBytes(exr, bytes);
  const Capture c = load();
  EXPECT_INPUT_ERROR(loadGBuffer(c, 1), "frames/0001.exr", "frame 1", "cannot read pixel data");
}

}  // namespace
}  // namespace aor::test
