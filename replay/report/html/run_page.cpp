#include "report/html/run_page.h"

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/stats.h"
#include "report/html/charts.h"
#include "report/html/graph_svg.h"
#include "report/html/html_page.h"
#include "report/svg_plot.h"

namespace aor::html {
namespace {

using json = nlohmann::json;

std::string text(const json& value) { return value.is_string() ? value.get<std::string>() : value.dump(); }

// "gpu_ms" for a timed run, else the counted measure ("instructions", "cycles").
std::string measureOf(const json& report) {
  return report.contains("cost") ? report["cost"].value("measure", "gpu_ms") : std::string("gpu_ms");
}

// A pass's figures for the tables and bars: over frames x repetitions for time, over frames for counts.
struct PassFigures {
  double median = 0, min = 0, max = 0;
  size_t count = 0;
};

PassFigures figuresOf(const json& pass, const std::string& measure) {
  if (measure == "gpu_ms") {
    const json& ms = pass["gpu_ms"];
    return {ms["median"].get<double>(), ms["min"].get<double>(), ms["max"].get<double>(), ms["count"].get<size_t>()};
  }
  const Summary s = summarize(pass[measure]["per_frame"].get<std::vector<double>>());
  return {s.median, s.min, s.max, s.count};
}

std::pair<std::string, std::string> costFact(const json& r) {
  const std::string measure = measureOf(r);
  if (measure == "gpu_ms")
    return {"GPU total (median per frame)", fmt::format("{:.4g} ms (compute passes; host copies add {:.4g} ms)",
                                                        r["gpu_ms_total_median"].get<double>(),
                                                        r["gpu_ms_host_copies_median"].get<double>())};
  return {measure + " (counted)", fmt::format("{:.0f} over the frames (compute passes; host copies add {:.0f}); {}",
                                              r[measure + "_total"].get<double>(),
                                              r[measure + "_host_copies_total"].get<double>(), text(r["cost"]["key"]))};
}

std::string overviewHtml(const RunPage& page) {
  const json& r = page.report;
  const json& c = r["capture"];
  auto frames = r["run"]["frames"];
  std::vector<std::pair<std::string, std::string>> facts = {
      {"device", fmt::format("{} (driver {}, Vulkan {})", text(r["device"]["name"]), text(r["device"]["driver"]),
                             text(r["device"]["api_version"]))},
      {"capture", fmt::format("{} ({}x{}, {} frames) at {}", text(c["name"]), c["width"].get<int>(), c["height"].get<int>(),
                              c["frames"].get<int>(), text(c["path"]))},
      {"frames replayed", fmt::format("{}:{} (half-open)", frames[0].get<int>(), frames[1].get<int>())},
      {"technique", text(r["settings"].value("technique", json("?")))},
      {"settings", r["settings"].dump()},
      {"timing", fmt::format("{}, repeat {}, warm-up {}", text(r["timing"]["mode"]), r["run"]["repeat"].get<int>(),
                             r["run"]["warmup"].get<int>())},
      costFact(r),
      {"validation", r.contains("validation") ? r["validation"].dump() : "off"},
  };
  std::string html = factList(facts);
  for (const auto& line : page.summaryLines) html += "<p class=\"metric-line\">" + escape(line) + "</p>\n";
  return html;
}

std::string passTimesHtml(const json& report) {
  std::vector<Bar> bars;
  const std::string measure = measureOf(report);
  for (const auto& p : report["passes"]) {
    const PassFigures f = figuresOf(p, measure);
    bars.push_back({text(p["name"]), f.median, f.min, f.max});
  }
  if (measure != "gpu_ms")
    return barChartSvg(bars, measure + " per frame (counted under callgrind): bar = median, whiskers = min to max over frames");
  return barChartSvg(bars, "GPU time per frame (ms): bar = median, whiskers = min to max over frames x repetitions");
}

// The frames where history was reset (not the resets of every frame of a run that keeps no
// history, whose reason is `noHistoryReason`), with the reason.
void markResets(const json& frames, const std::string& noHistoryReason, PlotOptions& options) {
  for (const auto& f : frames)
    if (f.value("history", "") == "reset" && (noHistoryReason.empty() || f.value("reset_reason", "") != noHistoryReason)) {
      options.verticalMarkers.push_back(f["index"].get<double>());
      options.verticalMarkerLabels.push_back("reset: " + f.value("reset_reason", "?"));
    }
}

PlotSeries perFrame(const json& frames, const std::string& name, auto valueOf) {
  PlotSeries s{name};
  for (const auto& f : frames)
    if (auto v = valueOf(f)) {
      s.x.push_back(f["index"].get<double>());
      s.y.push_back(*v);
      s.tooltips.push_back(fmt::format("frame {}: {} = {:.5g}", f["index"].get<int>(), name, *v));
    }
  return s;
}

std::optional<double> numberAt(const json& j, std::initializer_list<const char*> path) {
  const json* node = &j;
  for (const char* key : path) {
    if (!node->is_object() || !node->contains(key)) return std::nullopt;
    node = &(*node)[key];
  }
  return node->is_number() ? std::optional<double>(node->get<double>()) : std::nullopt;
}

std::string frameTimesHtml(const json& report, const std::string& noHistoryReason) {
  const std::string measure = measureOf(report);
  const bool counted = measure != "gpu_ms";
  const std::string frameKey = counted ? measure : "gpu_ms_median";
  std::vector<PlotSeries> series;
  for (const auto& p : report["passes"]) {
    std::string name = text(p["name"]);
    series.push_back(perFrame(report["frames"], name, [&](const json& f) { return numberAt(f, {frameKey.c_str(), name.c_str()}); }));
  }
  PlotOptions options;
  options.title = counted ? measure + " per pass and frame (counted)" : "GPU time per pass and frame (median over repetitions)";
  options.xLabel = "frame (index in the capture)";
  options.yLabel = counted ? measure : "GPU time (ms)";
  options.width = 1000;
  options.height = 420;
  markResets(report["frames"], noHistoryReason, options);
  return svgPlot(series, options);
}

std::string metricsOverTimeHtml(const json& report, const std::string& noHistoryReason) {
  const json& frames = report["frames"];
  std::vector<PlotSeries> series;
  auto add = [&](const std::string& name, std::initializer_list<const char*> path) {
    auto s = perFrame(frames, name, [&](const json& f) { return numberAt(f, path); });
    if (!s.x.empty()) series.push_back(std::move(s));
  };
  add("RMSE vs reference", {"metrics", "error", "rmse"});
  add("halo-band RMSE (behind nearer silhouettes)", {"metrics", "error", "halo_band", "rmse"});
  auto dissimilarity = perFrame(frames, "1 - SSIM vs reference", [](const json& f) -> std::optional<double> {
    auto ssim = numberAt(f, {"metrics", "error", "ssim"});
    return ssim ? std::optional<double>(1.0 - *ssim) : std::nullopt;
  });
  if (!dissimilarity.x.empty()) series.push_back(std::move(dissimilarity));
  add("warping error (squared, previous output reprojected)", {"metrics", "temporal", "warping_error"});
  add("derivative error |dO - dR|", {"metrics", "temporal", "derivative_error"});
  add("abs error |O - R|", {"metrics", "temporal", "abs_error"});
  if (series.empty()) return "<p class=\"note\">No per-frame error or temporal metric (one frame, or nothing to compare with).</p>\n";
  PlotOptions options;
  options.title = "error and temporal stability per frame";
  options.xLabel = "frame (index in the capture); dashed: history reset, with its reason";
  options.yLabel = "error (visibility, 0-1; log scale)";
  options.logY = true;
  options.width = 1000;
  options.height = 460;
  markResets(frames, noHistoryReason, options);
  return svgPlot(series, options);
}

std::string passesHtml(const json& report) {
  const std::string measure = measureOf(report);
  const bool counted = measure != "gpu_ms";
  Table run{"passes-run",
            counted ? std::vector<std::string>{"pass", "median " + measure + " a frame", "min", "max", "frames"}
                    : std::vector<std::string>{"pass", "median ms", "min ms", "max ms", "timed runs"},
            {}, true};
  auto number = [counted](double v) { return counted ? fmt::format("{:.0f}", v) : fmt::format("{:.4f}", v); };
  for (const auto& p : report["passes"]) {
    const PassFigures f = figuresOf(p, measure);
    run.rows.push_back({escape(text(p["name"])), number(f.median), number(f.min), number(f.max), std::to_string(f.count)});
  }
  Table culled{"passes-culled", {"culled pass", "reason"}, {}, false};
  for (const auto& c : report["culled_passes"]) culled.rows.push_back({escape(text(c["name"])), escape(text(c["reason"]))});
  std::string html = "<h3>run</h3>\n" + run.html() + "<h3>culled</h3>\n";
  return html + (culled.rows.empty() ? "<p class=\"note\">No pass was culled.</p>\n" : culled.html());
}

std::string graphHtml(std::string dot) {
  // A pass chain is far longer than the page is wide: drawn top to bottom, its labels stay legible.
  if (auto lr = dot.find("rankdir=LR"); lr != std::string::npos) dot.replace(lr, 10, "rankdir=TB");
  std::string svg = graphSvg(dot);
  if (!svg.empty()) return "<div class=\"graph\">" + svg + "</div>\n<p class=\"note\">Dashed grey: culled passes.</p>\n";
  if (dot.empty()) return "<p class=\"note\">(no graph recorded)</p>\n";
  const size_t passes = passNodes(dot);
  if (passes <= kMaxDrawnPasses)  // Graphviz could not lay it out
    return "<pre class=\"graph\">" + escape(dot) + "</pre>\n";
  return fmt::format("<p class=\"note\">{} passes: more than the {} Graphviz lays out here (its layout time grows "
                     "explosively with long chains), so drawn as a list in execution order, dashed grey when culled; each "
                     "arc is a resource (hover for its name) from the pass that writes it to a pass that reads it. "
                     "<code>aoreplay graph --dot FILE</code> writes the DOT text for Graphviz.</p>\n",
                     passes, kMaxDrawnPasses) +
         "<div class=\"graph\">" + passListSvg(dot) + "</div>\n<details><summary>DOT text</summary><pre class=\"graph\">" +
         escape(dot) + "</pre></details>\n";
}

std::string bytesText(double bytes) {
  if (bytes >= 1 << 20) return fmt::format("{:.2f} MiB", bytes / double(1 << 20));
  if (bytes >= 1 << 10) return fmt::format("{:.1f} KiB", bytes / double(1 << 10));
  return fmt::format("{:.0f} B", bytes);
}

std::string memoryHtml(const json& memory) {
  std::vector<Bar> bars;
  Table table{"memory-table", {"resource", "type", "size", "format", "bytes", "allocated", "first pass", "last pass", "memory slot", "shares memory with"}, {}, true};
  for (const auto& r : memory["resources"]) {
    double bytes = r.value("bytes", 0.0);
    bool allocated = r.value("allocated", false);
    if (allocated) bars.push_back({text(r["name"]), bytes / double(1 << 10), bytes / double(1 << 10), bytes / double(1 << 10)});
    std::string size = r.contains("width") ? fmt::format("{}x{}", r["width"].get<int>(), r["height"].get<int>()) : "";
    std::vector<std::string> aliases;
    for (const auto& a : r.value("aliases", json::array())) aliases.push_back(text(a));
    table.rows.push_back({escape(text(r["name"])), escape(r.value("type", "")), size, escape(r.value("format", "")),
                          fmt::format("<td data-value=\"{}\">{}</td>", bytes, bytesText(bytes)), allocated ? "yes" : "no (unused)",
                          escape(r.value("first_pass", "")), escape(r.value("last_pass", "")),
                          r.contains("memory_slot") ? std::to_string(r["memory_slot"].get<int>()) : "",
                          escape(fmt::format("{}", fmt::join(aliases, ", ")))});
  }
  std::string html = fmt::format("<p>Peak GPU memory of the graph's resources: <b>{}</b> (aliasing included; {} without it).</p>\n",
                                 bytesText(memory.value("peak_gpu_bytes", 0.0)), bytesText(memory.value("unaliased_gpu_bytes", 0.0)));
  if (!bars.empty()) html += barChartSvg(bars, "memory per allocated resource (KiB)");
  return html + table.html();
}

}  // namespace

std::string runPageHtml(const RunPage& page) {
  const json& r = page.report;
  Page html(fmt::format("aoreplay run: {} with {}", text(r["capture"]["name"]), text(r["settings"].value("technique", json("?")))));
  html.section("overview", "Run", overviewHtml(page));
  html.section("pass-times", "GPU time per pass", passTimesHtml(r));
  html.section("frame-times", "GPU time per frame", frameTimesHtml(r, page.noHistoryReason));
  html.section("images", "Frames: AO, reference, error, flicker", frameImagesHtml(page.frames));
  html.section("metrics-over-time", "Error and temporal stability over time", metricsOverTimeHtml(r, page.noHistoryReason));
  html.section("passes", "Passes run and culled", passesHtml(r));
  html.section("graph", "Render graph (last frame)", graphHtml(graph::toDot(page.graph.declared, page.graph.compiled)));
  html.section("memory", "Memory per resource", memoryHtml(r["memory"]));
  return html.html();
}

}  // namespace aor::html
