#pragma once
// Runs renderdoc_dump.py, which the binary embeds, on one .rdc: it replays the capture with
// RenderDoc's Python module and dumps the event's depth, normals and matrices as raw data.
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

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

// The Python that runs the script: $AOREPLAY_PYTHON, else Debian's /usr/bin/python3 (the one
// python3-renderdoc is built for), else python3 on PATH.
std::string renderDocPythonInterpreter();

}  // namespace aor
