// The sweep's data handling and the SVG plots, without a GPU: grid expansion, Pareto flags, CSV.
#include <gtest/gtest.h>

#include "capture/input_error.h"
#include "report/svg_plot.h"
#include "report/sweep.h"

namespace aor {
namespace {

SweepRow row(const std::string& name, double ms, double rmse) {
  SweepRow r;
  r.config.name = name;
  r.totalMs = ms;
  r.rmse = rmse;
  return r;
}

}  // namespace

TEST(Sweep, PresetsTimesTheGridInOrder) {
  AoSettings base;
  base.radius = 2.5f;
  auto configs = expandSweep(base, {"low", "ultra"}, {"thin=0,1", "technique=gtao,reference"});
  ASSERT_EQ(configs.size(), 8u);
  EXPECT_EQ(configs[0].name, "low thin=0 technique=gtao");
  EXPECT_EQ(configs[7].name, "ultra thin=1 technique=reference");
  EXPECT_EQ(configs[7].settings.slices, 9);
  EXPECT_EQ(configs[7].settings.thin, 1.0f);
  EXPECT_EQ(configs[7].settings.technique, AoTechnique::Reference);
  EXPECT_EQ(configs[7].settings.temporal, 0.0f) << "the reference is never denoised";
  EXPECT_EQ(configs[2].settings.radius, 2.5f) << "base settings carry over";
}

TEST(Sweep, BadPresetsAndGridsAreInputErrors) {
  AoSettings base;
  EXPECT_THROW(expandSweep(base, {"extreme"}, {}), InputError);
  EXPECT_THROW(expandSweep(base, {"low"}, {"slices"}), InputError);
  EXPECT_THROW(expandSweep(base, {"low"}, {"slices=2,,3"}), InputError);
  EXPECT_THROW(expandSweep(base, {"low"}, {"slices=99"}), InputError);
  EXPECT_THROW(expandSweep(base, {"low"}, {"technique=magic"}), InputError);
}

TEST(Sweep, ParetoRowsAreTheOnesNothingBeats) {
  std::vector<SweepRow> rows = {row("a", 1.0, 0.10), row("b", 2.0, 0.05), row("c", 3.0, 0.07),  // c: slower and worse than b
                                row("d", 2.0, 0.05), row("e", 0.5, 0.20), row("f", 4.0, 0.01)};
  markPareto(rows);
  std::vector<bool> expected = {true, true, false, true, true, true};  // b and d tie: neither beats the other
  for (size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i].pareto, expected[i]) << rows[i].config.name;
}

TEST(Sweep, CsvHasOneLinePerRowAndTheUnionOfPasses) {
  auto a = row("low", 1.5, 0.1), b = row("high, thin", 3.0, 0.05);
  a.passMs = {{"gtao", 1.0}, {"spatial", 0.5}};
  b.passMs = {{"gtao", 2.5}, {"temporal", 0.5}};
  b.pareto = true;
  auto csv = sweepCsv({a, b});
  EXPECT_NE(csv.find(",gtao_ms,spatial_ms,temporal_ms,total_ms,rmse,ssim,pareto\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\"high, thin\",gtao"), std::string::npos) << "names with commas are quoted";
  EXPECT_NE(csv.find(",2.500000,0.000000,0.500000,3.000000,0.050000,0.000000,1\n"), std::string::npos) << csv;
}

TEST(SvgPlot, IsDeterministicEscapedAndMarksHighlightedPoints) {
  PlotSeries s{"A & B"};
  s.x = {1, 2, 4};
  s.y = {0.3, 0.2, 0.1};
  s.labels = {"low", "<mid>", "high"};
  s.highlighted = {true, false, true};
  PlotOptions o;
  o.title = "error vs ms";
  o.logX = true;
  auto svg = svgPlot({s}, o);
  EXPECT_EQ(svg, svgPlot({s}, o));
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("A &amp; B"), std::string::npos);
  EXPECT_NE(svg.find("&lt;mid&gt;"), std::string::npos);
  EXPECT_NE(svg.find("Pareto-optimal"), std::string::npos);
  // Two emphasised points (r=7) and one plain marker (r=4), plus the legend's sample marker.
  auto count = [&](const std::string& needle) {
    size_t n = 0;
    for (size_t p = svg.find(needle); p != std::string::npos; p = svg.find(needle, p + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("r=\"7\""), 2u);
  EXPECT_EQ(count("r=\"4\""), 1u);
  EXPECT_NE(svg.find("(log scale)"), std::string::npos);
  // Empty and degenerate data still give a valid document.
  auto empty = svgPlot({}, o);
  EXPECT_NE(empty.find("</svg>"), std::string::npos);
  PlotSeries single{"one"};
  single.x = {3};
  single.y = {0.5};
  EXPECT_NE(svgPlot({single}, PlotOptions{}).find("<circle"), std::string::npos);
}

}  // namespace aor
