// What a person sees (issue 25): the terminal's error and temporal lines and its list of outputs,
// report.html / sweep.html / compare.html (self-contained), --version, --device aliases, defaults
// in --help, JUnit XML from run --expect and compare, and progress lines off a terminal.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gpu_test_support.h"

namespace aor::test {
namespace {
namespace fs = std::filesystem;

fs::path shipped(const char* name) { return fs::path(AOR_SOURCE_DIR) / "captures" / name; }

size_t count(const std::string& text, const std::string& needle) {
  size_t n = 0;
  for (size_t p = text.find(needle); p != std::string::npos; p = text.find(needle, p + 1)) ++n;
  return n;
}

// Nothing on the page is fetched: no external script, style, image or link.
void expectSelfContained(const std::string& html) {
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);
  EXPECT_EQ(html.find("href=\"http"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("<script src"), std::string::npos);
  EXPECT_EQ(html.find("url(http"), std::string::npos);
}

int xmllint(const fs::path& file) { return std::system(fmt::format("xmllint --noout '{}'", file.string()).c_str()); }

TEST(ReportCli, RunOnTheShippedCapturePrintsErrorTemporalAndEveryOutput) {
  fs::path out = scratchDir("report-run") / "boxes";
  auto r = runAoreplay(fmt::format("run {} --frames 0:6 --device lavapipe --out {}", shipped("boxes-orbit").string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex(R"(error vs ray-traced reference, 6 frame\(s\): RMSE 0\.\d+, SSIM 0\.\d+, PSNR \d+\.\d+ dB)")))
      << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex(R"(temporal: warping error [0-9.e-]+ mean \(max [0-9.e-]+ at frame \d+\); )"))) << r.output;
  EXPECT_NE(r.output.find("response "), std::string::npos) << r.output;
  // Every file written is listed, the SVGs and report.html included.
  for (const char* listed : {"report.html", "report.json", "trace.json", "temporal.svg", "temporal_response.svg",
                             "ao/ (12 file(s): NNNN.exr, NNNN.png)"})
    EXPECT_NE(r.output.find(listed), std::string::npos) << listed << "\n" << r.output;
  for (const char* file : {"report.html", "temporal.svg", "temporal_response.svg"}) EXPECT_TRUE(fs::exists(out / file)) << file;

  std::string html = readText(out / "report.html");
  for (const char* id : {"overview", "pass-times", "frame-times", "images", "metrics-over-time", "passes", "graph", "memory"})
    EXPECT_NE(html.find(fmt::format("<section id=\"{}\">", id)), std::string::npos) << id;
  expectSelfContained(html);
  // Frames 1, 3 and 5: AO, reference, heat map and flicker each, as PNG data.
  EXPECT_EQ(count(html, "src=\"data:image/png;base64,"), 12u);
  EXPECT_NE(html.find("class=\"colour-scale\""), std::string::npos);
  EXPECT_NE(html.find("<svg width=\""), std::string::npos) << "the render graph, laid out by Graphviz";
  EXPECT_NE(html.find("culled"), std::string::npos);
  EXPECT_NE(html.find(">reset: first frame</text>"), std::string::npos) << "resets are marked and labelled";
}

TEST(ReportCli, ReportHtmlIsDeterministic) {
  auto capture = generatedCapture("boxes", "orbit", 64, 36, 3);
  fs::path dir = scratchDir("report-determinism");
  for (const char* name : {"a", "b"})
    ASSERT_EQ(runAoreplay(fmt::format("run {} --out {}", capture.string(), (dir / name).string())).exitCode, 0);
  // Timings differ between runs; images, graph and memory do not.
  auto images = [&](const char* name) {
    std::string html = readText(dir / name / "report.html");
    size_t begin = html.find("<section id=\"images\">"), end = html.find("</section>", begin);
    return html.substr(begin, end - begin);
  };
  EXPECT_EQ(images("a"), images("b"));
}

TEST(ReportCli, VersionNamesTheBuildLoaderAndDriver) {
  auto r = runAoreplay("--version");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex(R"(^aoreplay \d+\.\d+ \(git [0-9a-f]{7,})"))) << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex(R"(Vulkan loader: 1\.\d+\.\d+)"))) << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex(R"(driver llvmpipe Mesa \d+)"))) << r.output;
}

TEST(ReportCli, DeviceMatchesAliasesDeviceAndDriverNames) {
  auto capture = generatedCapture("boxes", "orbit", 64, 36, 3);
  for (const char* device : {"lavapipe", "cpu", "llvmpipe", "LLVMPIPE"}) {
    auto r = runAoreplay(fmt::format("run {} --frames 0:1 --no-images --device {} --out {}", capture.string(), device,
                                     (scratchDir(std::string("device-") + device) / "out").string()));
    EXPECT_EQ(r.exitCode, 0) << device << "\n" << r.output;
    EXPECT_NE(r.output.find("device: llvmpipe"), std::string::npos) << r.output;
  }
  auto missing = runAoreplay(fmt::format("run {} --frames 0:1 --device no-such-gpu --out {}", capture.string(),
                                         (scratchDir("device-missing") / "out").string()));
  EXPECT_EQ(missing.exitCode, 3) << missing.output;
  EXPECT_NE(missing.output.find("aliases: lavapipe, cpu"), std::string::npos) << missing.output;
}

TEST(ReportCli, HelpShowsEveryDefaultAndEveryKey) {
  auto run = runAoreplay("run --help");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  for (const char* option : {"--repeat", "--warmup", "--preload-budget", "--jump-angle", "--jump-distance", "--technique"})
    EXPECT_TRUE(std::regex_search(run.output, std::regex(std::string(option) + R"([^\n]*=[0-9a-z])"))) << option << "\n" << run.output;
  auto compare = runAoreplay("compare --help");
  for (const char* option : {"--alpha", "--min-effect", "--min-effect-ms", "--spread-multiple"})
    EXPECT_TRUE(std::regex_search(compare.output, std::regex(std::string(option) + R"( [^\n]*=[0-9])"))) << option << "\n" << compare.output;
  auto capture = runAoreplay("capture --help");
  EXPECT_TRUE(std::regex_search(capture.output, std::regex(R"(--reference-spp[^\n]*=[0-9])"))) << capture.output;
  // Every key of every technique, with its default, from the table the parser reads.
  auto list = runAoreplay("techniques --json");
  ASSERT_EQ(list.exitCode, 0) << list.output;
  auto techniques = nlohmann::json::parse(list.output)["techniques"];
  ASSERT_FALSE(techniques.empty());
  for (const auto& t : techniques) {
    std::string name = t["name"].get<std::string>();
    auto help = runAoreplay(fmt::format("run --technique {} --help", name));
    for (const auto& key : t["parameters"]) {
      std::string k = key["key"].get<std::string>();
      EXPECT_TRUE(std::regex_search(help.output, std::regex("\n  " + k + " +[^\n]*default"))) << name << " " << k << "\n" << help.output;
    }
  }
}

TEST(ReportCli, ExpectWithOneFailingThresholdWritesJunitWithOneFailure) {
  auto capture = generatedCapture("boxes", "orbit", 64, 36, 3);
  fs::path dir = scratchDir("report-junit");
  {
    std::ofstream expect(dir / "expect.json");
    expect << R"({"max": {"temporal.warping_error": 1e-12, "gpu_ms.gtao": 1e9}})";
  }
  auto r = runAoreplay(fmt::format("run {} --no-images --out {} --expect {} --junit {}", capture.string(), (dir / "out").string(),
                                   (dir / "expect.json").string(), (dir / "junit.xml").string()));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  std::string xml = readText(dir / "junit.xml");
  EXPECT_NE(xml.find(R"(tests="2" failures="1")"), std::string::npos) << xml;
  EXPECT_EQ(count(xml, "<failure "), 1u) << xml;
  EXPECT_TRUE(std::regex_search(xml, std::regex(R"(<failure message="temporal.warping_error at frame \d+: )"))) << xml;
  EXPECT_EQ(xmllint(dir / "junit.xml"), 0) << "xmllint (Debian libxml2-utils) rejects:\n" << xml;
  auto lonely = runAoreplay(fmt::format("run {} --no-images --out {} --junit {}", capture.string(), (dir / "out2").string(),
                                        (dir / "j2.xml").string()));
  EXPECT_EQ(lonely.exitCode, 2) << "--junit needs --expect\n" << lonely.output;
}

TEST(ReportCli, CompareWritesJunitAndHtml) {
  auto capture = generatedCapture("boxes", "orbit", 64, 36, 3);
  fs::path dir = scratchDir("report-compare");
  for (const char* side : {"a", "b"})
    ASSERT_EQ(runAoreplay(fmt::format("run {} --no-images --repeat 3 --out {}", capture.string(), (dir / side).string())).exitCode, 0);
  auto r = runAoreplay(fmt::format("compare {} {} --junit {} --html {}", (dir / "a" / "report.json").string(),
                                   (dir / "b" / "report.json").string(), (dir / "compare.xml").string(), (dir / "compare.html").string()));
  ASSERT_TRUE(r.exitCode == 0 || r.exitCode == 1) << r.output;
  std::string xml = readText(dir / "compare.xml");
  EXPECT_EQ(xmllint(dir / "compare.xml"), 0) << xml;
  EXPECT_NE(xml.find(R"(<testcase classname="aoreplay.compare" name="total">)"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<skipped"), std::string::npos) << "host copies are shown, not judged\n" << xml;
  EXPECT_EQ(count(xml, "<failure ") > 0, r.exitCode == 1) << xml;
  std::string html = readText(dir / "compare.html");
  expectSelfContained(html);
  for (const char* id : {"overview", "verdicts-section", "distributions"})
    EXPECT_NE(html.find(fmt::format("<section id=\"{}\">", id)), std::string::npos) << id;
  EXPECT_NE(html.find("class=\"strip\""), std::string::npos);
}

TEST(ReportCli, SweepWritesHtmlWithNumberedConfigurations) {
  auto capture = generatedCapture("sphere", "orbit", 48, 32, 2);
  fs::path out = scratchDir("report-sweep") / "result";
  auto r = runAoreplay(fmt::format("sweep {} --presets low,high --repeat 1 --out {}", capture.string(), out.string()));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("sweep.html"), std::string::npos) << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex(R"(\[2/2\] high \(1/2 configurations, [0-9.]+ s, about [0-9.]+ s left\))"))) << r.output;
  std::string html = readText(out / "sweep.html");
  expectSelfContained(html);
  EXPECT_NE(html.find("<table id=\"configurations\" class=\"sortable\">"), std::string::npos);
  EXPECT_NE(html.find(">1 = low</text>"), std::string::npos);
  EXPECT_NE(html.find("<title>2: high, "), std::string::npos) << "hover names the configuration";
}

TEST(ReportCli, CaptureOffATerminalPrintsProgressLinesWithTimeLeft) {
  fs::path out = scratchDir("report-progress") / "cap";
  auto r = runAoreplay(fmt::format("capture plane --out {} --size 32x18 --frames 3 --reference-spp 4", out.string()),
                       "AOREPLAY_PROGRESS_SECONDS=0");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex(R"(capture: 1/3 frames, [0-9.]+ s, about [0-9.]+ s left)"))) << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex(R"(capture: 3/3 frames, [0-9.]+ s, done)"))) << r.output;
}

}  // namespace
}  // namespace aor::test
