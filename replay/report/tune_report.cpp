#include "report/tune_report.h"

#include <fmt/format.h>

#include "report/svg_plot.h"

namespace aor {
namespace {

using nlohmann::json;

json valuesJson(const TuneRun& run, const std::vector<double>& values) {
  json j = json::object();
  for (size_t i = 0; i < run.dimensions.size(); ++i) j[run.dimensions[i].name] = values[i];
  return j;
}

json scoreJson(const ConfigScore& score, const std::string& objective, bool withTimes) {
  json captures = json::array();
  for (const auto& c : score.captures) {
    json j{{"capture", c.capture}, {"frames", c.frames}, {"rmse", c.rmse}, {"mse", c.mse}, {"ssim", c.ssim},
           {"objective", c.objective}};
    if (objective == "flip") j["flip"] = c.flip;
    if (withTimes) j = json{{"capture", c.capture}, {"ms", c.ms}};
    captures.push_back(j);
  }
  if (withTimes) return json{{"ms", score.ms}, {"captures", captures}};
  return json{{"objective", score.objective}, {"captures", captures}};
}

json beforeAfter(const TuneRun& run, bool withTimes) {
  auto score = [&](const ConfigScore& s) { return scoreJson(s, run.objective, withTimes); };
  json j{{"training", {{"before", score(run.trainingBefore)}, {"after", score(run.trainingAfter)}}}};
  if (!run.holdout.empty()) j["holdout"] = {{"before", score(run.holdoutBefore)}, {"after", score(run.holdoutAfter)}};
  return j;
}

}  // namespace

json tuneJson(const TuneRun& run) {
  json dims = json::array();
  for (const auto& d : run.dimensions)
    dims.push_back({{"key", d.name}, {"min", d.min}, {"max", d.max}, {"start", d.start}, {"integer", d.integer}});
  json evaluations = json::array();
  for (size_t i = 0; i < run.search.evaluations.size(); ++i) {
    const auto& e = run.search.evaluations[i];
    evaluations.push_back({{"index", i}, {"phase", e.phase}, {"values", valuesJson(run, e.values)},
                           {"objective", e.measure.objective}, {"within_budget", e.withinBudget}});
  }
  json j{{"format", "aoreplay-tune"}, {"version", 1}, {"technique", run.technique}, {"preset", run.preset},
         {"fixed", run.assignments}, {"objective", run.objective}, {"device", run.device}, {"keys", dims},
         {"training", run.training}, {"holdout", run.holdout}, {"frames", run.frames.empty() ? "all" : run.frames},
         {"grid_points", run.search.gridPointsUsed}, {"evaluations", evaluations}};
  if (run.budgetMs > 0) j["budget_ms"] = run.budgetMs;
  const auto& best = run.search.evaluations[size_t(run.search.best)];
  j["best"] = {{"index", run.search.best}, {"values", valuesJson(run, best.values)}, {"objective", best.measure.objective}};
  j["results"] = beforeAfter(run, false);
  j["settings"] = run.settingsFile;
  return j;
}

json tuneTimesJson(const TuneRun& run) {
  json evaluations = json::array();
  for (size_t i = 0; i < run.trainingScores.size(); ++i)
    evaluations.push_back({{"index", i}, {"ms", run.trainingScores[i].ms}});
  return json{{"note", "GPU times are measurements: they differ from run to run (tune.json does not)"},
              {"device", run.device}, {"evaluations", evaluations}, {"results", beforeAfter(run, true)}};
}

std::string tuneObjectiveSvg(const TuneRun& run) {
  PlotSeries all{"evaluation", {}, {}, false, true, {}, {}};
  PlotSeries best{"best so far", {}, {}, true, false, {}, {}};
  double bestSoFar = 0;
  for (size_t i = 0; i < run.search.evaluations.size(); ++i) {
    const auto& e = run.search.evaluations[i];
    all.x.push_back(double(i));
    all.y.push_back(e.measure.objective);
    if (e.withinBudget && (best.y.empty() || e.measure.objective < bestSoFar)) bestSoFar = e.measure.objective;
    if (!best.y.empty() || e.withinBudget) {
      best.x.push_back(double(i));
      best.y.push_back(bestSoFar);
    }
  }
  PlotOptions options;
  options.title = fmt::format("tune {}: {} over the evaluations (training captures)", run.technique, run.objective);
  options.xLabel = "evaluation";
  options.yLabel = run.objective + " (mean over training captures)";
  return svgPlot({all, best}, options);
}

std::string tuneErrorMsSvg(const TuneRun& run) {
  PlotSeries all{"evaluations (training mean)", {}, {}, false, true, {}, {}};
  for (const auto& s : run.trainingScores) {
    all.x.push_back(s.ms);
    all.y.push_back(s.objective);
  }
  std::vector<PlotSeries> series{all};
  auto pair = [&](const ConfigScore& before, const ConfigScore& after, const char* kind) {
    for (size_t c = 0; c < before.captures.size(); ++c) {
      PlotSeries s{fmt::format("{} {}", kind, before.captures[c].capture), {}, {}, true, true, {"before", "after"}, {}};
      s.x = {before.captures[c].ms, after.captures[c].ms};
      s.y = {before.captures[c].objective, after.captures[c].objective};
      series.push_back(s);
    }
  };
  pair(run.trainingBefore, run.trainingAfter, "training");
  pair(run.holdoutBefore, run.holdoutAfter, "hold-out");
  PlotOptions options;
  options.title = fmt::format("tune {}: {} against GPU time, before and after", run.technique, run.objective);
  options.xLabel = "GPU ms per frame (median compute total)";
  options.yLabel = run.objective;
  return svgPlot(series, options);
}

std::string tuneSummary(const TuneRun& run) {
  std::string out;
  auto rows = [&](const char* kind, const ConfigScore& before, const ConfigScore& after) {
    for (size_t c = 0; c < before.captures.size(); ++c) {
      const auto &b = before.captures[c], &a = after.captures[c];
      std::string rmse = run.objective == "rmse" ? "" : fmt::format("   rmse {:.5f} -> {:.5f}", b.rmse, a.rmse);
      out += fmt::format("  {:<9} {:<24} {} {:.5f} -> {:.5f} ({:+.1f} %){}   ssim {:.4f} -> {:.4f}\n", kind, b.capture,
                         run.objective, b.objective, a.objective, 100.0 * (a.objective / b.objective - 1.0), rmse, b.ssim,
                         a.ssim);
    }
  };
  rows("training", run.trainingBefore, run.trainingAfter);
  rows("hold-out", run.holdoutBefore, run.holdoutAfter);
  return out;
}

json crossValidationJson(const CrossValidation& cv) {
  json folds = json::array();
  for (const auto& f : cv.folds)
    folds.push_back({{"held_out", f.heldOut}, {"training", f.run.training}, {"before", f.before()}, {"after", f.after()},
                     {"change", f.change()}, {"training_before", f.run.trainingBefore.objective},
                     {"training_after", f.run.trainingAfter.objective}, {"tuned", f.run.settingsFile}});
  json j{{"margin", cv.margin}, {"folds", folds}, {"accepted", cv.accepted()},
         {"recommended", cv.accepted() ? "tuned" : "defaults"}};
  if (!cv.accepted()) j["refused_by"] = cv.folds[size_t(cv.refusedFold)].heldOut;
  return j;
}

std::string crossValidationSummary(const CrossValidation& cv, const std::string& objective) {
  std::string out;
  for (size_t i = 0; i < cv.folds.size(); ++i) {
    const auto& f = cv.folds[i];
    out += fmt::format("  fold {} (held out {}): {} {:.5f} -> {:.5f} ({:+.1f} %)\n", i + 1, f.heldOut, objective, f.before(),
                       f.after(), 100.0 * f.change());
  }
  if (cv.accepted())
    return out + fmt::format("cross-validation: every fold's held-out {} within +{:.1f} % of the defaults': the fit on "
                             "every capture is recommended (tuned.settings.json)\n",
                             objective, 100.0 * cv.margin);
  const auto& worst = cv.folds[size_t(cv.refusedFold)];
  return out + fmt::format("cross-validation: refused: fold {} (held out {}) got worse by {:+.1f} %, more than the margin "
                           "+{:.1f} %: the defaults are recommended (tuned.settings.json holds them; exit 1)\n",
                           cv.refusedFold + 1, worst.heldOut, 100.0 * worst.change(), 100.0 * cv.margin);
}

}  // namespace aor
