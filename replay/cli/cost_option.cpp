#include "cli/cost_option.h"

#include <map>

namespace aor::cli {

void addCostOption(CLI::App& command, CostMeasure& cost, const std::string& help) {
  command.add_option("--cost", cost, help)
      ->transform(CLI::CheckedTransformer(std::map<std::string, CostMeasure>{
          {"time", CostMeasure::Time}, {"instructions", CostMeasure::Instructions}, {"cycles", CostMeasure::Cycles}}))
      ->default_str("time");
}

}  // namespace aor::cli
