#include "metrics/temporal_metrics.h"

namespace aor {

// Placeholder until the temporal metrics land: records nothing.
void TemporalAnalysis::addFrame(const AnalyzedFrame&) {}
nlohmann::json TemporalAnalysis::frameJson(int) const { return nullptr; }
nlohmann::json TemporalAnalysis::summaryJson() const { return nullptr; }

}  // namespace aor
