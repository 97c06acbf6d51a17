#pragma once
// report.html of `aoreplay run`: everything report.json says, drawn (docs/outputs.md, "Reports a person reads"):
// device, capture, technique and settings; per-pass GPU time (median bars with min-max whiskers)
// and per frame; selected frames' AO beside the reference with the error heat map and the change
// from the previous frame; error and temporal metrics over time with history resets marked and
// labelled; the passes run and culled (with the reason); the graph; memory per resource.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "graph/render_graph.h"
#include "report/html/frame_images.h"

namespace aor::html {

struct RunPage {
  const nlohmann::json& report;    // as written to report.json
  std::vector<FrameImages> frames;  // framesToShow()'s frames
  const graph::GraphSnapshot& graph;  // the run's last frame, drawn
  std::vector<std::string> summaryLines;  // the terminal's error and temporal lines
  std::string noHistoryReason;  // ReplayResult::noHistoryReason: such resets are not marked
};

std::string runPageHtml(const RunPage& page);

}  // namespace aor::html
