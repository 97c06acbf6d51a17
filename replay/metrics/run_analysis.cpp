#include "metrics/run_analysis.h"

#include "metrics/error_metrics.h"
#include "metrics/temporal_metrics.h"

namespace aor {

RunAnalysis::RunAnalysis(const std::string& referenceKind, bool withFlip, bool temporal)
    : errors_(std::make_unique<ErrorAnalysis>(referenceKind, withFlip)),
      temporal_(temporal ? std::make_unique<TemporalAnalysis>() : nullptr) {}
RunAnalysis::~RunAnalysis() = default;
RunAnalysis::RunAnalysis(RunAnalysis&&) noexcept = default;
RunAnalysis& RunAnalysis::operator=(RunAnalysis&&) noexcept = default;

void RunAnalysis::addFrame(const AnalyzedFrame& frame) {
  errors_->addFrame(frame);
  if (temporal_) temporal_->addFrame(frame);
}

nlohmann::json RunAnalysis::frameJson(int index) const {
  nlohmann::json j = nlohmann::json::object();
  if (auto e = errors_->frameJson(index); !e.is_null()) j["error"] = e;
  if (auto t = temporal_ ? temporal_->frameJson(index) : nullptr; !t.is_null()) j["temporal"] = t;
  return j;
}

nlohmann::json RunAnalysis::summaryJson() const {
  nlohmann::json j = nlohmann::json::object();
  if (auto e = errors_->summaryJson(); !e.is_null()) j["error"] = e;
  if (auto t = temporal_ ? temporal_->summaryJson() : nullptr; !t.is_null()) j["temporal"] = t;
  return j;
}

}  // namespace aor
