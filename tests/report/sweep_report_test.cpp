// The sweep's data handling and the SVG plots, without a GPU: grid expansion, Pareto flags, CSV.
#include <gtest/gtest.h>

#include "core/input_error.h"
#include "report/svg_plot.h"
#include "report/sweep.h"
#include "techniques/registry.h"

namespace aor {
namespace {

SweepRow row(const std::string& name, double ms, double rmse) {
  SweepRow r{{name, Settings()}};
  r.config.name = name;
  r.totalMs = ms;
  r.rmse = rmse;
  return r;
}

}  // namespace

// What `sweep` resolves with a capture, without one: the technique's defaults, the preset, the assignments.
Settings resolveWithoutCapture(const Technique& t, std::string_view preset, const std::vector<std::string>& assignments) {
  Settings s(t);
  if (!preset.empty()) s.applyPreset(preset);
  for (const auto& a : assignments) s.assign(a);
  return s;
}

SweepPlan expand(std::vector<std::string> presets, std::vector<std::string> grid, std::vector<std::string> set = {}) {
  return expandSweep({std::move(presets), std::move(grid), std::move(set)}, resolveWithoutCapture);
}

TEST(Sweep, EachTechniqueRunsItsPresetsTimesTheGridInOrder) {
  auto plan = expand({"low", "ultra"}, {"thin=0,1", "technique=gtao,reference"}, {"radius=2.5"});
  // gtao: 2 presets x 2 thin values; reference: no presets, so once per thin value.
  ASSERT_EQ(plan.configs.size(), 6u);
  EXPECT_EQ(plan.configs[0].name, "low technique=gtao thin=0");
  EXPECT_EQ(plan.configs[3].name, "ultra technique=gtao thin=1");
  EXPECT_EQ(plan.configs[3].settings.i("slices"), 9);
  EXPECT_EQ(plan.configs[3].settings.f("thin"), 1.0f);
  EXPECT_EQ(plan.configs[5].name, "technique=reference thin=1");
  EXPECT_EQ(plan.configs[5].settings.technique().name, "reference");
  EXPECT_FALSE(plan.configs[5].settings.has("temporal")) << "the reference has no denoiser to switch off";
  EXPECT_EQ(plan.configs[4].settings.f("radius"), 2.5f) << "--set applies to every technique that has the key";
  EXPECT_EQ(plan.configs[1].settings.f("radius"), 2.5f);
}

TEST(Sweep, KeysApplyWhereDeclaredAndPresetsATechniqueLacksAreSkippedWithANote) {
  // half_res is gtao's alone: the reference is not expanded along it, and no error is raised.
  auto plan = expand({"high", "extreme"}, {"technique=gtao,reference", "half_res=0,1"});
  ASSERT_EQ(plan.configs.size(), 3u);
  EXPECT_EQ(plan.configs[0].name, "high technique=gtao half_res=0");
  EXPECT_EQ(plan.configs[2].name, "technique=reference");
  ASSERT_EQ(plan.notes.size(), 1u);
  EXPECT_NE(plan.notes[0].find("gtao has no preset 'extreme'"), std::string::npos) << plan.notes[0];
  // Without --presets every preset of the technique runs.
  EXPECT_EQ(expand({}, {}).configs.size(), gtaoTechnique().presets.size());
}

TEST(Sweep, BadPresetsKeysAndGridsAreInputErrors) {
  EXPECT_TRUE(expand({"extreme"}, {}).configs.empty());  // the command refuses an empty sweep (exit 2)
  EXPECT_THROW(expand({"low"}, {"slices"}), InputError);
  EXPECT_THROW(expand({"low"}, {"slices=2,,3"}), InputError);
  EXPECT_THROW(expand({"low"}, {"slices=99"}), InputError);
  EXPECT_THROW(expand({"low"}, {"technique=magic"}), InputError);
  EXPECT_THROW(expand({"low"}, {"technique=reference", "slices=2"}), InputError) << "no technique of the sweep has slices";
  EXPECT_THROW(expand({"low"}, {}, {"typo=1"}), InputError);
}

TEST(Sweep, ParetoRowsAreTheOnesNothingBeats) {
  std::vector<SweepRow> rows = {row("a", 1.0, 0.10), row("b", 2.0, 0.05), row("c", 3.0, 0.07),  // c: slower and worse than b
                                row("d", 2.0, 0.05), row("e", 0.5, 0.20), row("f", 4.0, 0.01)};
  markPareto(rows);
  std::vector<bool> expected = {true, true, false, true, true, true};  // b and d tie: neither beats the other
  for (size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i].pareto, expected[i]) << rows[i].config.name;
}

TEST(Sweep, RankingByTheHaloBandUsesItsErrorForTheFront) {
  std::vector<SweepRow> rows = {row("a", 1.0, 0.10), row("b", 2.0, 0.05)};
  rows[0].haloRmse = 0.02;  // a: faster, worse overall, better in the band
  rows[1].haloRmse = 0.08;
  markPareto(rows, SweepRank::HaloBand);
  EXPECT_TRUE(rows[0].pareto);
  EXPECT_FALSE(rows[1].pareto) << "slower and worse in the band";
  markPareto(rows, SweepRank::Rmse);
  EXPECT_TRUE(rows[1].pareto);
  SweepInfo info{"c", "d", "ray-traced"};
  info.rank = SweepRank::HaloBand;
  EXPECT_NE(sweepSvg(info, rows).find("halo-band RMSE"), std::string::npos);
}

// Several techniques: a totals table, then each technique's own passes only, no line over 120
// characters even with CACAO's long pass names.
TEST(Sweep, TablesOfSeveralTechniquesKeepEachOnesPassesAndFit120Columns) {
  auto plan = expand({}, {"technique=gtao,cacao"});
  std::vector<SweepRow> rows;
  for (const auto& config : plan.configs) {
    SweepRow r{config};
    const bool cacao = config.settings.technique().name == "cacao";
    r.passMs = cacao ? std::vector<std::pair<std::string, double>>{{"cacao_prepare_native_normals_from_input_normals", 0.25},
                                                                   {"cacao_generate_q1", 2.0}}
                     : std::vector<std::pair<std::string, double>>{{"gtao", 1.5}, {"spatial", 0.4}};
    rows.push_back(r);
  }
  ASSERT_GT(rows.size(), 8u) << "enough configurations to need more than one block of columns";
  const std::string table = sweepTable(rows);
  size_t widest = 0, start = 0;
  for (size_t end; (end = table.find('\n', start)) != std::string::npos; start = end + 1) widest = std::max(widest, end - start);
  EXPECT_LE(widest, 120u) << table;
  const size_t cacaoBlock = table.find("cacao: GPU ms per pass");
  const size_t gtaoBlock = table.find("gtao: GPU ms per pass");
  ASSERT_NE(cacaoBlock, std::string::npos) << table;
  ASSERT_NE(gtaoBlock, std::string::npos) << table;
  EXPECT_EQ(table.substr(gtaoBlock, cacaoBlock - gtaoBlock).find("cacao_generate_q1"), std::string::npos)
      << "gtao's table has none of cacao's passes";
  EXPECT_EQ(table.substr(0, gtaoBlock).find("spatial"), std::string::npos) << "the totals table has no pass column";
  EXPECT_NE(table.find("halo RMSE"), std::string::npos);
}

TEST(Sweep, CsvHasOneLinePerRowTheUnionOfKeysAndTheUnionOfPasses) {
  auto plan = expand({"low"}, {"technique=gtao,reference"});
  SweepRow a{plan.configs[0]}, b{plan.configs[1]};
  a.config.name = "low";
  b.config.name = "high, thin";
  a.totalMs = 1.5;
  a.rmse = 0.1;
  b.totalMs = 3.0;
  b.rmse = 0.05;
  a.passMs = {{"gtao", 1.0}, {"spatial", 0.5}};
  b.passMs = {{"gtao_reference", 2.5}, {"temporal", 0.5}};
  b.pareto = true;
  auto csv = sweepCsv({a, b});
  std::string header = csv.substr(0, csv.find('\n'));
  // Every gtao key, then the reference's (all of which gtao has too), then the passes.
  std::string keys;
  for (const auto& p : gtaoTechnique().parameters) keys += "," + p.key;
  EXPECT_EQ(header, "configuration,technique" + keys + ",gtao_ms,spatial_ms,gtao_reference_ms,temporal_ms,total_ms,rmse,ssim,pareto");
  EXPECT_NE(csv.find("\"high, thin\",reference"), std::string::npos) << "names with commas are quoted";
  EXPECT_NE(csv.find("\nlow,gtao,1,1,2,0.615,"), std::string::npos) << csv;
  // The reference has no slices, steps, spatial, temporal or half_res: those cells are empty.
  EXPECT_NE(csv.find(",reference,1,,,0.615,1,0,,,1,,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",0.000000,0.000000,2.500000,0.500000,3.000000,0.050000,0.000000,1\n"), std::string::npos) << csv;
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
  // Two emphasised points (r=7) and one plain marker (r=4), plus the legend's markers, drawn as the
  // points are: the series' open marker and the Pareto-optimal filled one.
  auto count = [&](const std::string& needle) {
    size_t n = 0;
    for (size_t p = svg.find(needle); p != std::string::npos; p = svg.find(needle, p + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("r=\"7\""), 3u);
  EXPECT_EQ(count("r=\"4\""), 2u);
  EXPECT_EQ(count(R"(r="7" fill="#1f77b4")"), 3u) << "the legend's Pareto marker has the points' colour";
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
