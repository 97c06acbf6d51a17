#include "metrics/run_analysis.h"

#include "metrics/error_metrics.h"
#include "metrics/temporal_metrics.h"

namespace aor {

RunAnalysis::RunAnalysis() : errors_(std::make_unique<ErrorAnalysis>()), temporal_(std::make_unique<TemporalAnalysis>()) {}
RunAnalysis::~RunAnalysis() = default;

void RunAnalysis::addFrame(const AnalyzedFrame& frame) {
  errors_->addFrame(frame);
  temporal_->addFrame(frame);
}

nlohmann::json RunAnalysis::frameJson(int index) const {
  nlohmann::json j = nlohmann::json::object();
  if (auto e = errors_->frameJson(index); !e.is_null()) j["error"] = e;
  if (auto t = temporal_->frameJson(index); !t.is_null()) j["temporal"] = t;
  return j;
}

nlohmann::json RunAnalysis::summaryJson() const {
  nlohmann::json j = nlohmann::json::object();
  if (auto e = errors_->summaryJson(); !e.is_null()) j["error"] = e;
  if (auto t = temporal_->summaryJson(); !t.is_null()) j["temporal"] = t;
  return j;
}

}  // namespace aor
