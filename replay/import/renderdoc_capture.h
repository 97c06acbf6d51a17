#pragma once
// `aoreplay renderdoc-capture`: one frame of any program RenderDoc can capture (Vulkan, OpenGL
// core), written as a .rdc for `aoreplay import renderdoc`. The program is launched with RenderDoc
// injected, as RenderDoc's UI launches it, and followed through a wrapper script to the process
// that draws; renderdoc_capture.py, which the binary embeds, does the work.
#include <filesystem>
#include <string>
#include <vector>

namespace aor {

struct FrameCaptureRequest {
  std::vector<std::string> program;  // the program and its arguments
  std::filesystem::path out;         // the .rdc to write (replaced when it is an earlier capture)
  int afterFrames = 5;               // frames (at 60 a second) between registering and the trigger
  int timeoutSeconds = 60;           // for the whole attempt
  std::string afterRegister, afterTrigger;  // shell commands: once it draws, once the capture is triggered
  std::string renderdocPython;       // folder of a RenderDoc build's Python module; empty: the installed one
};

struct FrameCapture {
  int frame = 0;
  std::string api, target;  // as RenderDoc names them ("Vulkan", the process that drew)
};

// Captures one frame into request.out, whole or not at all. What the user can act on (a program
// that is not there, that RenderDoc cannot capture, with RenderDoc's reason; one that exits or
// never draws within the time; a failing command; an --out that is not a capture) is an
// InputError; a script that crashes is a std::runtime_error.
FrameCapture captureFrame(const FrameCaptureRequest& request);

}  // namespace aor
