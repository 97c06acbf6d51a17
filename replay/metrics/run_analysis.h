#pragma once
// Everything a run measures about its outputs besides time: error against the reference
// (error_metrics.h) and temporal stability (temporal_metrics.h). The run layer feeds every frame in
// order; report.json holds frameJson()/summaryJson().
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "metrics/analyzed_frame.h"
#include "metrics/error_metrics.h"

namespace aor {

class ErrorAnalysis;
class TemporalAnalysis;

class RunAnalysis {
 public:
  // Error against references of `referenceKind` (with FLIP when asked), and temporal stability
  // unless `temporal` is false.
  explicit RunAnalysis(const std::string& referenceKind = kRayTracedReference, bool withFlip = false, bool temporal = true);
  ~RunAnalysis();
  RunAnalysis(RunAnalysis&&) noexcept;
  RunAnalysis& operator=(RunAnalysis&&) noexcept;
  void addFrame(const AnalyzedFrame& frame);
  nlohmann::json frameJson(int index) const;  // metrics of one frame (object; empty if none)
  nlohmann::json summaryJson() const;         // over all frames

 private:
  std::unique_ptr<ErrorAnalysis> errors_;
  std::unique_ptr<TemporalAnalysis> temporal_;
};

}  // namespace aor
