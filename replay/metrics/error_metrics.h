#pragma once
// Error of the AO output against a reference visibility (issue "Ground truth"): sky masked.
#include <map>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "metrics/analyzed_frame.h"

namespace aor {

class ErrorAnalysis {
 public:
  void addFrame(const AnalyzedFrame& frame);
  nlohmann::json frameJson(int index) const;  // null when the frame had no reference
  nlohmann::json summaryJson() const;         // null when no frame had one

 private:
  std::map<int, nlohmann::json> frames_;
};

}  // namespace aor
