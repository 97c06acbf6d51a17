// `aoreplay renderdoc-capture --out FILE.rdc -- PROGRAM [ARGS...]`: one frame of a program that
// knows nothing of RenderDoc, for `aoreplay import renderdoc` (replay/import/renderdoc_capture.h).
#include <memory>

#include <fmt/format.h>

#include "cli/commands.h"
#include "cli/handlers.h"
#include "cli/number_options.h"
#include "import/renderdoc_capture.h"

namespace aor::cli {

void registerRenderDocCaptureCommand(CLI::App& app) {
  auto request = std::make_shared<FrameCaptureRequest>();
  auto* cmd = app.add_subcommand("renderdoc-capture",
                                 "capture one frame of a Vulkan or OpenGL-core program with RenderDoc (for import renderdoc)");
  cmd->add_option("program", request->program, "the program and its arguments, after --")->required();
  cmd->add_option("--out", request->out, "the .rdc to write")->required();
  cmd->add_option("--after-frames", request->afterFrames, "frames to let it draw once it uses a graphics API, before the trigger")
      ->check(wholeIn(0, 100000))
      ->capture_default_str();
  cmd->add_option("--timeout", request->timeoutSeconds, "seconds for the whole attempt")
      ->check(wholeIn(1, 86400))
      ->capture_default_str();
  cmd->add_option("--after-register", request->afterRegister,
                  "shell command run once it uses a graphics API (e.g. xdotool key space to start a demo)");
  cmd->add_option("--after-trigger", request->afterTrigger,
                  "shell command run once the capture is triggered (make it draw a frame: resize its window, press a key)");
  cmd->add_option("--renderdoc-python", request->renderdocPython,
                  "folder holding renderdoc.so of a RenderDoc build (default: Debian's python3-renderdoc)");
  handlers()["renderdoc-capture"] = [request] {
    const FrameCapture c = captureFrame(*request);
    fmt::print("captured frame {} of {} ({}, drawn by {}) into {}\n", c.frame, request->program.front(), c.api, c.target,
               request->out.string());
    return kExitOk;
  };
}

}  // namespace aor::cli
