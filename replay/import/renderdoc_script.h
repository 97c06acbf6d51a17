#pragma once
// Runs renderdoc_dump.py, which the binary embeds, on one .rdc: it replays the capture with
// RenderDoc's Python module and dumps the event's depth, normals and matrices as raw data.
#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/subprocess.h"

namespace aor {

struct DumpRequest {
  std::filesystem::path capture;
  std::filesystem::path workDir;  // receives dump.json, depth.bin, normals.bin; must exist
  std::string renderdocPython;    // folder of a RenderDoc build's renderdoc.so; empty: the installed module
  std::optional<int> event;
  std::optional<std::string> passName;
  std::string depth = "auto";
  std::string normals = "none";
  std::string view, projection, viewProjection;  // the script reads view and projection, or view_projection
  bool arrayRows = false;
  int sample = 0;
  bool noSelfCheck = false;  // the script then skips the post-vertex-shader dump
};

// dump.json's contents: what the script found and, for bad input, "error" {field, message}.
// Throws InputError when no Python can be run, std::runtime_error when the script itself failed
// (crashed, timed out, wrote no dump).
nlohmann::json runRenderDocDump(const DumpRequest& request);

// Runs an embedded script of RenderDoc's (`text`, written to WORK_DIR/NAME) with the Python below
// and `arguments` after it, its output in WORK_DIR/script.out and script.err; a user's
// AOREPLAY_PYTHON is checked to be a Python 3 first. Throws InputError when no Python can run it.
ProcessResult runRenderDocScript(std::string_view text, const std::string& name, const std::vector<std::string>& arguments,
                                 const std::map<std::string, std::string>& environment,
                                 const std::filesystem::path& workDir, std::chrono::seconds timeLimit);

// The Python that runs the script: $AOREPLAY_PYTHON, else Debian's /usr/bin/python3 (the one
// python3-renderdoc is built for), else python3 on PATH.
std::string renderDocPythonInterpreter();

}  // namespace aor
