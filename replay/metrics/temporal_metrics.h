#pragma once
// Temporal stability of the AO output (issue "Temporal stability"): flicker, ghosting, history.
#include <map>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "metrics/analyzed_frame.h"

namespace aor {

class TemporalAnalysis {
 public:
  void addFrame(const AnalyzedFrame& frame);
  nlohmann::json frameJson(int index) const;  // null when nothing was measured
  nlohmann::json summaryJson() const;         // null when nothing was measured

 private:
  std::map<int, nlohmann::json> frames_;
};

}  // namespace aor
