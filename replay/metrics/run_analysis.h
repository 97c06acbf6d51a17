#pragma once
// Everything a run measures about its outputs besides time: error against the reference
// (error_metrics.h) and temporal stability (temporal_metrics.h). The run command feeds every frame
// in order and puts frameJson()/summaryJson() into report.json.
#include <memory>

#include <nlohmann/json.hpp>

#include "metrics/analyzed_frame.h"

namespace aor {

class ErrorAnalysis;
class TemporalAnalysis;

class RunAnalysis {
 public:
  RunAnalysis();
  ~RunAnalysis();
  void addFrame(const AnalyzedFrame& frame);
  nlohmann::json frameJson(int index) const;  // metrics of one frame (object; empty if none)
  nlohmann::json summaryJson() const;         // over all frames

 private:
  std::unique_ptr<ErrorAnalysis> errors_;
  std::unique_ptr<TemporalAnalysis> temporal_;
};

}  // namespace aor
