#include "cli/commands.h"

#include <functional>
#include <map>
#include <string>

#include <fmt/format.h>

#include "core/plain_text.h"
#include "cli/handlers.h"

namespace aor::cli {

std::map<std::string, std::function<int()>>& handlers() {
  static std::map<std::string, std::function<int()>> h;
  return h;
}

void checkEveryValue(CLI::App& app) {
  const CLI::Validator plain(
      [](std::string& value) -> std::string {
        if (value.empty()) return "is empty";
        if (auto at = controlCharacterIn(value)) return fmt::format("{} holds a control character ({})", printable(value), *at);
        return {};
      },
      "");
  for (CLI::App* command : app.get_subcommands(nullptr)) {
    for (CLI::Option* option : command->get_options())
      if (option->get_type_size_max() != 0) option->check(plain);
    checkEveryValue(*command);
  }
}

int runSelected(CLI::App& app) {
  for (auto* sub : app.get_subcommands()) return handlers().at(sub->get_name())();
  return kExitBadInput;
}

}  // namespace aor::cli
