// `aoreplay technique-header FILE.json PASS`: prints the aoreplay.glsl the replay generates for one
// pass of a user technique, so its shaders can be compiled offline (glslangValidator, an editor's
// GLSL checker) against exactly what the replay declares.
#include <memory>

#include <fmt/format.h>

#include "cli/commands.h"
#include "cli/handlers.h"
#include "techniques/user/user_technique.h"

namespace aor::cli {

void registerTechniqueHeaderCommand(CLI::App& app) {
  auto file = std::make_shared<std::string>();
  auto pass = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("technique-header",
                                 "print the generated aoreplay.glsl of one pass of a user technique (user_techniques/FORMAT.md)");
  cmd->add_option("file", *file, "the technique's technique.json")->required();
  cmd->add_option("pass", *pass, "the pass's name")->required();
  handlers()["technique-header"] = [file, pass] {
    fmt::print("{}", userTechniqueHeader(*file, *pass));
    return kExitOk;
  };
}

}  // namespace aor::cli
