#include "cli/cost_option.h"

#include <map>

namespace aor::cli {

void addCostOption(CLI::App& command, CostMeasure& cost, const std::string& help) {
  std::map<std::string, CostMeasure> named;
  for (CostMeasure m : kCostMeasures) named[costMeasureName(m)] = m;
  command.add_option("--cost", cost, help)->transform(CLI::CheckedTransformer(named))->default_str("time");
}

}  // namespace aor::cli
