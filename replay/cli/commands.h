#pragma once
// Subcommands of aoreplay. Each register* adds its options; runSelected dispatches.
#include <CLI/CLI.hpp>

#include "technique_api/technique.h"

namespace aor::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailed = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitNoDevice = 3;

// --device's help, one text for every command that creates a device (vk/device_selection.h).
inline constexpr const char* kDeviceHelp =
    "Vulkan device: index, alias (lavapipe, cpu) or a piece of its name or driver name; default lavapipe";

// `help`: the technique whose keys the help text lists (--technique on the command line, else gtao).
void registerRunCommand(CLI::App& app, const Technique& help);
void registerCaptureCommand(CLI::App& app);
void registerGraphCommand(CLI::App& app, const Technique& help);
void registerDevicesCommand(CLI::App& app);
void registerCompareCommand(CLI::App& app);
void registerSweepCommand(CLI::App& app, const Technique& help);
void registerTechniquesCommand(CLI::App& app);
void registerTechniqueHeaderCommand(CLI::App& app);
void registerAbCommand(CLI::App& app);
void registerImportCommand(CLI::App& app);
void registerRenderDocCaptureCommand(CLI::App& app);
void registerTuneCommand(CLI::App& app);
void registerRecordCommand(CLI::App& app);
void registerTrendCommand(CLI::App& app);
void registerExportCommand(CLI::App& app);
// Every value of every option and argument of every command, refused when empty or holding a
// control character (core/plain_text.h): after all commands are registered.
void checkEveryValue(CLI::App& app);
int runSelected(CLI::App& app);

}  // namespace aor::cli
