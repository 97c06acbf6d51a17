// Pieces of the HTML reports and of --junit that need no device: base64 for the embedded PNGs,
// JUnit XML of --expect, and plot labels that never overlap.
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "report/html/graph_svg.h"
#include "report/html/html_page.h"
#include "gpu_test_support.h"
#include "report/junit.h"
#include "report/run_summary.h"
#include "report/svg_plot.h"

namespace aor {
namespace {

TEST(HtmlPage, Base64MatchesRfc4648Vectors) {
  EXPECT_EQ(html::base64(""), "");
  EXPECT_EQ(html::base64("f"), "Zg==");
  EXPECT_EQ(html::base64("fo"), "Zm8=");
  EXPECT_EQ(html::base64("foo"), "Zm9v");
  EXPECT_EQ(html::base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(html::base64(std::string("\xff\x00\x80", 3)), "/wCA");
  EXPECT_EQ(html::escape("a<b & \"c\" 'd'>"), "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;");
}

TEST(Junit, OneCasePerThresholdAndOneFailureNamingMetricAndFrames) {
  std::vector<Threshold> thresholds = {{"temporal.warping_error", true, 0.002}, {"error.ssim", false, 0.5}};
  std::vector<ExpectationFailure> failures = {{thresholds[0], 3, 0.0031}, {thresholds[0], 7, 0.0042}};
  std::string xml = junitXml("aoreplay run --expect e.json", expectationCases(thresholds, failures));
  EXPECT_NE(xml.find(R"(<testsuite name="aoreplay run --expect e.json" tests="2" failures="1" errors="0" skipped="0">)"), std::string::npos) << xml;
  EXPECT_NE(xml.find(R"(name="temporal.warping_error &lt;= 0.002")"), std::string::npos) << xml;
  EXPECT_NE(xml.find(R"(name="error.ssim &gt;= 0.5")"), std::string::npos) << xml;
  size_t first = xml.find("<failure");
  ASSERT_NE(first, std::string::npos);
  EXPECT_EQ(xml.find("<failure", first + 1), std::string::npos) << "one failing threshold, one failure";
  EXPECT_NE(xml.find(R"(message="temporal.warping_error at frame 3: 0.0031 &gt; max 0.002")"), std::string::npos) << xml;
  EXPECT_NE(xml.find("temporal.warping_error at frame 7: 0.0042 &gt; max 0.002</failure>"), std::string::npos) << xml;
}

// Issue 44, class 8: XML 1.0 cannot hold most control characters even as entities; names that
// carry them (from any input) are written escaped, so the file stays valid XML.
TEST(Junit, ControlCharactersInNamesAreEscapedAndTheXmlStaysValid) {
  std::string xml = junitXml("suite\x1b[31m", {{"class\x01", "name\x0b", std::string("fails\x02\nsecond line"), false, "detail\x7f"}});
  for (unsigned char c : xml) EXPECT_TRUE(c >= 0x20 ? c != 0x7f : c == '\n') << "raw control character " << int(c);
  EXPECT_NE(xml.find(R"(<testsuite name="suite\x1b[31m")"), std::string::npos) << xml;
  EXPECT_NE(xml.find(R"(classname="class\x01" name="name\x0b")"), std::string::npos) << xml;
  EXPECT_NE(xml.find("fails\\x02\nsecond line</failure>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("detail\\x7f"), std::string::npos) << xml;
}

TEST(SvgPlot, LabelsOfCrowdedPointsDoNotOverlap) {
  PlotSeries s{"configurations"};
  s.lines = false;
  for (int i = 0; i < 12; ++i) {
    s.x.push_back(1.0 + 0.001 * i);  // all within a few pixels
    s.y.push_back(0.1 + 0.0001 * i);
    s.labels.push_back(std::to_string(i + 1));
  }
  s.x.push_back(10.0);
  s.y.push_back(1.0);
  s.labels.push_back("13");
  auto svg = svgPlot({s}, PlotOptions{});
  std::regex label(R"re(<text x="([0-9.]+)" y="([0-9.]+)" font-size="11" fill="#222"( text-anchor="end")?>([0-9]+)</text>)re");
  struct Box { double l, t, r, b; };
  std::vector<Box> boxes;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), label); it != std::sregex_iterator(); ++it) {
    double x = std::stod((*it)[1]), y = std::stod((*it)[2]);
    double width = 6.0 * double((*it)[4].length());  // below the layout's 6.4 px a character
    bool end = (*it)[3].matched;
    boxes.push_back({end ? x - width : x, y - 9, end ? x : x + width, y});
  }
  ASSERT_EQ(boxes.size(), 13u) << svg;
  for (size_t i = 0; i < boxes.size(); ++i)
    for (size_t j = i + 1; j < boxes.size(); ++j) {
      bool overlap = boxes[i].l < boxes[j].r && boxes[j].l < boxes[i].r && boxes[i].t < boxes[j].b && boxes[j].t < boxes[i].b;
      EXPECT_FALSE(overlap) << "labels " << i + 1 << " and " << j + 1;
    }
  EXPECT_NE(svg.find(R"(stroke="#999" stroke-width="0.8")"), std::string::npos) << "labels moved out get a leader line";
}

TEST(SvgPlot, ResetMarkersAreLabelledAndTheKeyListsNumberedPoints) {
  PlotSeries s{"rmse"};
  s.x = {0, 1, 2, 3};
  s.y = {0.1, 0.2, 0.1, 0.2};
  PlotOptions o;
  o.verticalMarkers = {2};
  o.verticalMarkerLabels = {"reset: cut"};
  o.key = {"1 = low", "2 = high"};
  auto svg = svgPlot({s}, o);
  EXPECT_NE(svg.find(">reset: cut</text>"), std::string::npos) << svg;
  EXPECT_NE(svg.find(">1 = low</text>"), std::string::npos) << svg;
  EXPECT_NE(svg.find(">2 = high</text>"), std::string::npos) << svg;
}

TEST(RunSummary, OutputListingNamesEveryFileAndEachFolderOfFramesOnce) {
  namespace fs = std::filesystem;
  fs::path dir = test::scratchDir("output-listing");
  for (const char* file : {"report.json", "report.html", "temporal.svg", "ao/0000.exr", "ao/0000.png", "ao/0001.exr",
                           "ao/0001.png", "debug/linear_depth/0000.exr", ".aoreplay-result.json"}) {
    fs::create_directories((dir / file).parent_path());
    std::ofstream(dir / file) << "x";
  }
  EXPECT_EQ(outputListing(dir),
            "report.html, report.json, temporal.svg, ao/ (4 file(s): NNNN.exr, NNNN.png), debug/linear_depth/ (1 file(s): NNNN.exr)");
}

}  // namespace
}  // namespace aor

namespace aor::html {
namespace {

// A chain of passes as graph::toDot writes it (pass nodes p0.., resources r0.., edges between).
std::string chainDot(int passes) {
  std::string dot = "digraph render_graph {\n  rankdir=LR;\n";
  for (int i = 0; i < passes; ++i) dot += fmt::format("  p{} [shape=box, label=\"[{}] pass{}\"];\n", i, i, i);
  for (int i = 0; i < passes; ++i) dot += fmt::format("  r{} [shape=ellipse, label=\"image{}\"];\n", i, i);
  for (int i = 0; i < passes; ++i) {
    dot += fmt::format("  p{} -> r{};\n", i, i);
    if (i + 1 < passes) dot += fmt::format("  r{} -> p{};\n", i, i + 1);
  }
  return dot + "}\n";
}

// Graphviz's dot took 112 s on 60 chained passes: above kMaxDrawnPasses Graphviz is not asked and
// the page draws the passes as a list with an arc per resource from writer to reader (linear in
// the graph); a small graph is still laid out by Graphviz.
TEST(GraphSvg, LongPassChainsAreDrawnAsAListNotLaidOut) {
  EXPECT_EQ(passNodes(chainDot(8)), 8u);
  EXPECT_NE(graphSvg(chainDot(8)).find("<svg"), std::string::npos);
  EXPECT_EQ(passNodes(chainDot(300)), 300u);
  EXPECT_TRUE(graphSvg(chainDot(300)).empty());
  const std::string svg = passListSvg(chainDot(300));
  auto count = [&](const std::string& what) {
    size_t n = 0;
    for (size_t at = svg.find(what); at != std::string::npos; at = svg.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("<rect "), 300u) << "a row per pass";
  EXPECT_EQ(count("<path "), 299u) << "an arc per resource from its writer to its reader";
  EXPECT_NE(svg.find(">[299] pass299</text>"), std::string::npos);
  // image5 is written by row 5 and read by row 6: its arc starts and ends on those rows.
  EXPECT_NE(svg.find("<path d=\"M 310 129 C 332 129, 332 151, 310 151\" fill=\"none\" stroke=\"#3b6ea5\"><title>image5</title>"),
            std::string::npos) << svg.substr(svg.find("image5") - 200, 400);
}

}  // namespace
}  // namespace aor::html
