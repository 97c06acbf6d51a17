#include "metrics/error_metrics.h"

namespace aor {

// Placeholder until the error metrics land: records nothing.
void ErrorAnalysis::addFrame(const AnalyzedFrame&) {}
nlohmann::json ErrorAnalysis::frameJson(int) const { return nullptr; }
nlohmann::json ErrorAnalysis::summaryJson() const { return nullptr; }

}  // namespace aor
