#include "cli/commands.h"

#include <functional>
#include <map>
#include <string>

#include "cli/handlers.h"

namespace aor::cli {

std::map<std::string, std::function<int()>>& handlers() {
  static std::map<std::string, std::function<int()>> h;
  return h;
}

int runSelected(CLI::App& app) {
  for (auto* sub : app.get_subcommands()) return handlers().at(sub->get_name())();
  return kExitBadInput;
}

}  // namespace aor::cli
