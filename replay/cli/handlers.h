#pragma once
#include <functional>
#include <map>
#include <string>

namespace aor::cli {
// Subcommand name -> what runs it; filled by the register* functions.
std::map<std::string, std::function<int()>>& handlers();
}  // namespace aor::cli
