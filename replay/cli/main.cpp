// aoreplay: replays AO captures through the render graph and reports time, error and stability.
// Exit codes: 0 success, 1 failed run (e.g. validation messages), 2 bad usage or bad input,
// 3 no usable Vulkan device.
#include <cerrno>
#include <cstdio>
#include <cstring>

#include <CLI/CLI.hpp>

#include "core/input_error.h"
#include "cli/commands.h"
#include "cost/launcher.h"
#include "cli/settings_options.h"
#include "cli/version.h"
#include "core/output_directory.h"
#include "techniques/registry.h"
#include "vk/vk_check.h"

namespace aor::cli {

// Every command's standard output checked in one place: what a script reads there (compare --json -,
// export -, the tables) must not be lost silently, so a write that failed (a full disk, a closed
// pipe) turns the exit status into 1.
int checkedStandardOutput(int status) {
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return status;
  // fprintf, not fmt::print, which throws when standard error cannot be written either.
  std::fprintf(stderr, "aoreplay: failed: cannot write standard output: %s\n", std::strerror(errno));
  return status == kExitOk ? kExitFailed : status;
}

}  // namespace aor::cli

int main(int argc, char** argv) {
  // Before any thread starts: an interrupted run removes its staging folder and lock.
  aor::cleanUpOutputsOnTermination();
  aor::rememberCommandLine(argc, argv);  // counted cost re-executes it under callgrind
  CLI::App app{"aoreplay: deterministic replay and profiling of screen-space ambient occlusion captures"};
  app.require_subcommand(1);
  app.set_version_flag("--version", [] {
    auto text = aor::cli::versionText();
    return text.substr(0, text.size() - 1);  // CLI11 ends it with a newline
  }, "version, git commit, Vulkan loader and every device's driver version; exit");
  const aor::Technique& help = aor::cli::techniqueForHelp(argc, argv, aor::defaultTechnique());
  aor::cli::registerRunCommand(app, help);
  aor::cli::registerCaptureCommand(app);
  aor::cli::registerGraphCommand(app, help);
  aor::cli::registerDevicesCommand(app);
  aor::cli::registerCompareCommand(app);
  aor::cli::registerSweepCommand(app, help);
  aor::cli::registerTechniquesCommand(app);
  aor::cli::registerTechniqueHeaderCommand(app);
  aor::cli::registerAbCommand(app);
  aor::cli::registerImportCommand(app);
  aor::cli::registerRenderDocCaptureCommand(app);
  aor::cli::registerTuneCommand(app);
  aor::cli::registerRecordCommand(app);
  aor::cli::registerTrendCommand(app);
  aor::cli::registerExportCommand(app);
  aor::cli::checkEveryValue(app);
  try {
    app.parse(argc, argv);
    return aor::cli::checkedStandardOutput(aor::cli::runSelected(app));
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return aor::cli::kExitBadInput;
  } catch (const aor::InputError& e) {
    std::fprintf(stderr, "aoreplay: error: %s\n", e.what());
    return aor::cli::kExitBadInput;
  } catch (const aor::NoDeviceError& e) {
    std::fprintf(stderr, "aoreplay: no usable Vulkan device: %s\n", e.what());
    return aor::cli::kExitNoDevice;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "aoreplay: failed: %s\n", e.what());  // fprintf: never throws, even when stderr is gone
    return aor::cli::kExitFailed;
  }
}
