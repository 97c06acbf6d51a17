#pragma once
// Subcommands of aoreplay. Each register* adds its options; runSelected dispatches.
#include <CLI/CLI.hpp>

namespace aor::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailed = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitNoDevice = 3;

void registerRunCommand(CLI::App& app);
void registerCaptureCommand(CLI::App& app);
void registerGraphCommand(CLI::App& app);
void registerDevicesCommand(CLI::App& app);
void registerCompareCommand(CLI::App& app);
void registerSweepCommand(CLI::App& app);
void registerImportCommand(CLI::App& app);
int runSelected(CLI::App& app);

}  // namespace aor::cli
