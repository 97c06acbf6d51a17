// Issue 20: every JSON file aoreplay reads is bounded (core/json_input.h) and capture loading is
// linear in the number of frames. Each input here once crashed, hung or was accepted wrongly.
#include <sys/stat.h>

#include <glm/gtc/matrix_transform.hpp>

#include "core/json_input.h"
#include "test_support.h"

namespace aor::test {
namespace {

using json = nlohmann::json;
const JsonLimits kSmall{1 << 20, 1000, 128};

std::string nestedArrays(int depth) { return std::string(size_t(depth), '[') + "1" + std::string(size_t(depth), ']'); }

json parse(const std::string& text, const JsonLimits& limits = kSmall) { return parseBoundedJson(text, limits, "in.json"); }

TEST(JsonInput, NestingUpToTheLimitParsesOneLevelMoreIsRefused) {
  EXPECT_EQ(parse(nestedArrays(128)).dump().size(), 2u * 128 + 1);
  EXPECT_INPUT_ERROR(parse(nestedArrays(129)), "in.json", "nested deeper than 128 levels");
  // The same limit on the slow path (taken for the message of malformed JSON).
  EXPECT_EQ(detail::parseBoundedJsonSlowly(nestedArrays(128), kSmall, "in.json").dump().size(), 2u * 128 + 1);
  EXPECT_INPUT_ERROR(detail::parseBoundedJsonSlowly(nestedArrays(129), kSmall, "in.json"), "nested deeper than 128");
}

TEST(JsonInput, SixtyThousandLevelsAreRefusedNotAStackOverflow) {
  std::string deep;
  for (int i = 0; i < 60000; ++i) deep += "{\"a\":";
  deep += "1" + std::string(60000, '}');
  EXPECT_INPUT_ERROR(parse(deep), "in.json", "field \"a.a.a.a", "nested deeper than 128 levels");
  // Malformed as well: the slow path stops at the limit too, long before the error at the end.
  EXPECT_INPUT_ERROR(parse(deep.substr(0, deep.size() - 1)), "nested deeper than 128 levels");
}

TEST(JsonInput, DuplicateKeysAnywhereAreErrorsNamingThePath) {
  EXPECT_INPUT_ERROR(parse(R"({"a": [{}, {"b": {"c": 1, "c": 2}}]})"), "field \"a[1].b.c\"", "appears twice");
  EXPECT_INPUT_ERROR(parse(R"({"max": {"x": 1}, "max": {"x": 2}})"), "field \"max\"", "appears twice");
  // Malformed JSON after the duplicate: the slow path reports the duplicate just the same.
  EXPECT_INPUT_ERROR(parse(R"({"a": 1, "a": 2, )"), "field \"a\"", "appears twice");
}

TEST(JsonInput, ArraysLongerThanTheLimitAreRefusedNamingTheArray) {
  std::string elements = "0";
  for (int i = 1; i < 1000; ++i) elements += ",0";
  EXPECT_EQ(parse("{\"frames\": [" + elements + "]}")["frames"].size(), 1000u);
  EXPECT_INPUT_ERROR(parse("{\"frames\": [" + elements + ",0]}"), "field \"frames\"", "more than 1000 elements");
  EXPECT_INPUT_ERROR(parse("{\"frames\": [" + elements + ",0,]}"), "field \"frames\"", "more than 1000 elements");
}

TEST(JsonInput, MalformedJsonNamesLineAndColumnAndQuotesAtMostAHundredCharacters) {
  EXPECT_INPUT_ERROR(parse("{\n  \"a\": [1,,2]\n}"), "in.json", "malformed JSON", "line 2, column");
  const std::string huge = "[\"" + std::string(200000, 'x') + "\x01\"]";  // a control character ends it
  const std::string message = expectInputError([&] { parse(huge); }, {"malformed JSON", "last read: ", " bytes)"});
  EXPECT_LT(message.size(), 400u) << message;
  EXPECT_INPUT_ERROR(parse("[1e999]"), "malformed JSON", "line 1, column 2", "1e999", "numbers must be finite");
}

TEST(JsonInput, BothPathsGiveTheSameDocument) {
  // Inputs simdjson refuses and nlohmann accepts (a BOM, an integer past 64 bits) are parsed by
  // nlohmann; the others by simdjson. Either way the document is nlohmann's.
  for (const std::string text : {"\xef\xbb\xbf[1]", "[18446744073709551616]", "[-0, 0, 1.5, -7, 1e-400]",
                                 R"({"k": "\u00e9\ud83d\ude00", "z": [true, false, null]})"}) {
    EXPECT_EQ(parse(text), json::parse(text)) << text;
    EXPECT_EQ(detail::parseBoundedJsonSlowly(text, kSmall, "x"), json::parse(text)) << text;
  }
  for (const std::string text : {R"(["\udc00"])", R"(["\ud800"])", "[NaN]", "[1] x", ""})
    EXPECT_INPUT_ERROR(parse(text), "in.json", "malformed JSON");
}

class JsonFile : public TempDirTest {};

TEST_F(JsonFile, OnlyRegularFilesAreReadAndAFifoDoesNotBlock) {
  const auto fifo = dir / "fifo.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_INPUT_ERROR(readBoundedJson(fifo, kSmall), "fifo.json", "not a regular file");
  EXPECT_INPUT_ERROR(readBoundedJson("/dev/zero", kSmall), "/dev/zero", "not a regular file");
  EXPECT_INPUT_ERROR(readBoundedJson(dir, kSmall), "is a folder");
  EXPECT_INPUT_ERROR(readBoundedJson(dir / "missing.json", kSmall), "missing.json", "cannot open");
}

TEST_F(JsonFile, AFileOverTheSizeLimitIsRefusedBeforeItIsRead) {
  writeBytes(dir / "big.json", "[" + std::string(2000, ' ') + "1]");
  EXPECT_INPUT_ERROR(readBoundedJson(dir / "big.json", JsonLimits{1000, 10, 8}), "big.json", "2003 bytes",
                     "limit of 1000 bytes");
  EXPECT_EQ(readBoundedJson(dir / "big.json", JsonLimits{2003, 10, 8}), json::array({1}));
}

TEST(QuoteForMessage, CutsLongTextAtACharacterBoundary) {
  EXPECT_EQ(quoteForMessage("short"), "\"short\"");
  EXPECT_EQ(quoteForMessage(std::string(150, 'a'), 100), "\"" + std::string(100, 'a') + "\"... (150 bytes)");
  // "é" is two bytes: a cut after byte 3 of "aaé..." would split it.
  EXPECT_EQ(quoteForMessage("aa\xc3\xa9zzzz", 3), "\"aa\"... (8 bytes)");
}

TEST(InputErrorMessage, FieldAndProblemAreNeverEchoedWhole) {
  const InputError e("f.json", std::nullopt, std::string(1 << 20, 'k'), std::string(1 << 20, 'p'));
  EXPECT_LT(std::string(e.what()).size(), 1300u);
  EXPECT_NE(std::string(e.what()).find("(1048576 bytes)"), std::string::npos);
}

// ---- capture.json ---------------------------------------------------------------------------------------

class CaptureJsonBounds : public TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    cap = dir / "cap";
    writeCapture(cap, 8, 6, makeFrames(8, 6, 2), {{"ao_radius", 0.5}});
    doc = readJson(cap / "capture.json");
  }
  void save() { writeJson(cap / "capture.json", doc); }
  fs::path cap;
  json doc;
};

TEST_F(CaptureJsonBounds, DeeplyNestedSceneIsRefused) {
  std::string text = doc.dump();
  std::string deep;
  for (int i = 0; i < 60000; ++i) deep += "{\"a\":";
  deep += "1" + std::string(60000, '}');
  text.replace(text.find("\"scene\":{") + 9, 0, "\"deep\":" + deep + ",");
  writeBytes(cap / "capture.json", text);
  EXPECT_INPUT_ERROR(loadCapture(cap), "cap/capture.json", "field \"scene.deep.a.a", "nested deeper than 128 levels");
}

TEST_F(CaptureJsonBounds, AoRadiusMustBeAFloatTheRadiusSettingAccepts) {
  for (const json& bad : {json(1e300), json(1e-300), json(2e7), json(5e-7), json(-1.0), json("0.5"), json(nullptr)}) {
    doc["scene"]["ao_radius"] = bad;
    save();
    EXPECT_INPUT_ERROR(loadCapture(cap), "cap/capture.json", "field \"scene.ao_radius\"");
  }
  for (double good : {1e-6, 0.5, 1e7}) {
    doc["scene"]["ao_radius"] = good;
    save();
    EXPECT_EQ(loadCapture(cap).scene["ao_radius"].get<double>(), good);
  }
}

TEST_F(CaptureJsonBounds, MatrixElementsThatUnderflowAFloatAreRefused) {
  doc["frames"][1]["projection"][2] = 1e-300;  // P[0][2], must be 0: as a float it would be
  save();
  EXPECT_INPUT_ERROR(loadCapture(cap), "frame 1", "field \"projection\"", "element 2", "would become 0");
}

TEST_F(CaptureJsonBounds, ALongUnknownKeyIsQuotedShort) {
  std::string text = doc.dump();
  text.insert(1, "\"" + std::string(2 << 20, 'k') + "\": 1,");
  writeBytes(cap / "capture.json", text);
  const std::string message = expectInputError([&] { loadCapture(cap); }, {"unknown field", "(2097152 bytes)"});
  EXPECT_LT(message.size(), 500u) << message;
}

TEST_F(CaptureJsonBounds, FramesPastTheLimitAreRefusedAndOneFileIsCheckedOnceForAllFrames) {
  // Every frame names the same two EXR files: loading checks each file once.
  const json frame = doc["frames"][0];
  doc["frames"] = json::array();
  for (int i = 0; i < 3000; ++i) doc["frames"].push_back(frame);
  save();
  const Capture c = loadCapture(cap);
  EXPECT_EQ(c.frames.size(), 3000u);
  EXPECT_EQ(captureFiles(c).size(), 3u) << "capture.json, one G-buffer, one reference";
  // kMaxCaptureFrames + 1 small frames: refused, naming the field, before any file is opened.
  std::string text = "{\"format\": \"aoreplay-capture\", \"version\": 1, \"width\": 8, \"height\": 6, \"frames\": [";
  for (int i = 0; i <= kMaxCaptureFrames; ++i) text += i ? ",{}" : "{}";
  writeBytes(cap / "capture.json", text + "]}");
  EXPECT_INPUT_ERROR(loadCapture(cap), "cap/capture.json", "field \"frames\"", "more than 100000 elements");
}

}  // namespace
}  // namespace aor::test
