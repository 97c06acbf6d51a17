#include "import/renderdoc_script.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "core/input_error.h"
#include "import/private_display.h"
#include "core/subprocess.h"

namespace aor {

extern const std::string_view kRenderDocDumpScript;  // renderdoc_dump.py, embedded at build time

namespace {

namespace fs = std::filesystem;

// Replaying a small frame takes about a second; a capture RenderDoc loops on is bad input.
constexpr std::chrono::seconds kDumpTimeLimit{300};

std::string readWhole(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> scriptArguments(const DumpRequest& r) {
  std::vector<std::string> args = {r.capture.string(), "--out", r.workDir.string(), "--depth", r.depth, "--normals", r.normals};
  if (r.viewProjection.empty()) args.insert(args.end(), {"--view", r.view, "--projection", r.projection});
  else args.insert(args.end(), {"--view-projection", r.viewProjection});
  if (r.arrayRows) args.push_back("--array-rows");
  if (r.sample != 0) args.insert(args.end(), {"--sample", std::to_string(r.sample)});
  if (!r.renderdocPython.empty()) args.insert(args.end(), {"--renderdoc-python", r.renderdocPython});
  if (r.event) args.insert(args.end(), {"--event", std::to_string(*r.event)});
  if (r.passName) args.insert(args.end(), {"--pass", *r.passName});
  if (r.noSelfCheck) args.push_back("--no-self-check");
  return args;
}

// A user's AOREPLAY_PYTHON must be a Python 3 before the script is blamed for anything: probed
// once per run (a wrong one was exit 1, "the dump script failed").
void checkChosenPython(const fs::path& workDir) {
  const char* chosen = std::getenv("AOREPLAY_PYTHON");
  if (!chosen || !*chosen) return;
  static bool checked = false;
  if (checked) return;
  const fs::path out = workDir / "python.out", err = workDir / "python.err";
  const ProcessResult p = runProcess({chosen, "-c", "import sys; print(sys.version_info[0])"}, {}, out, err,
                                     std::chrono::seconds(30));
  if (!p.started || p.exitCode != 0 || readWhole(out).rfind("3", 0) != 0)
    throw InputError(chosen, std::nullopt, "AOREPLAY_PYTHON",
                     fmt::format("is not a Python 3 that runs ({}): unset it to use Debian's /usr/bin/python3",
                                 !p.started ? p.startError : p.exitCode != 0 ? fmt::format("exit {}", p.exitCode)
                                                                              : "it printed " + outputTail(out, 1)));
  checked = true;
}

}  // namespace

std::string renderDocPythonInterpreter() {
  if (const char* chosen = std::getenv("AOREPLAY_PYTHON"); chosen && *chosen) return chosen;
  if (::access("/usr/bin/python3", X_OK) == 0) return "/usr/bin/python3";
  return "python3";
}

ProcessResult runRenderDocScript(std::string_view text, const std::string& name, const std::vector<std::string>& arguments,
                                 const std::map<std::string, std::string>& environment, const fs::path& workDir,
                                 std::chrono::seconds timeLimit) {
  checkChosenPython(workDir);
  const fs::path script = workDir / name;
  std::ofstream(script, std::ios::binary).write(text.data(), std::streamsize(text.size()));
  std::vector<std::string> argv = {renderDocPythonInterpreter(), script.string()};
  argv.insert(argv.end(), arguments.begin(), arguments.end());
  const ProcessResult p = runProcess(argv, environment, workDir / "script.out", workDir / "script.err", timeLimit);
  if (!p.started)
    throw InputError(renderDocPythonInterpreter(), std::nullopt, "",
                     fmt::format("cannot run Python ({}): the RenderDoc import needs Debian's python3 and "
                                 "python3-renderdoc (apt-get install python3 python3-renderdoc), or AOREPLAY_PYTHON "
                                 "naming a Python 3",
                                 p.startError));
  return p;
}

namespace {

bool unset(const char* name) {
  const char* value = std::getenv(name);
  return !value || !*value;
}

nlohmann::json runDumpScript(const DumpRequest& r, const std::map<std::string, std::string>& environment,
                             bool noDisplay) {
  std::vector<std::string> arguments = scriptArguments(r);
  if (noDisplay) arguments.push_back("--no-display");
  const fs::path err = r.workDir / "script.err";
  const ProcessResult p =
      runRenderDocScript(kRenderDocDumpScript, "renderdoc_dump.py", arguments, environment, r.workDir, kDumpTimeLimit);
  if (p.timedOut)
    throw InputError(r.capture.string(), std::nullopt, "",
                     fmt::format("RenderDoc did not finish replaying it within {} s", kDumpTimeLimit.count()));
  if (p.signal)
    throw InputError(r.capture.string(), std::nullopt, "",
                     fmt::format("RenderDoc crashed replaying it (signal {}); its last output: {}", p.signal,
                                 outputTail(err)));
  if (p.exitCode != 0 || !fs::exists(r.workDir / "dump.json"))
    throw std::runtime_error(fmt::format("the RenderDoc dump script ({}) failed on {} (exit {}): {}",
                                         renderDocPythonInterpreter(), r.capture.string(), p.exitCode,
                                         outputTail(err)));
  try {
    return nlohmann::json::parse(readWhole(r.workDir / "dump.json"));
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(fmt::format("the RenderDoc dump script wrote malformed JSON: {}", e.what()));
  }
}

}  // namespace

nlohmann::json runRenderDocDump(const DumpRequest& r) {
  std::map<std::string, std::string> environment;
  if (!r.renderdocPython.empty()) {  // a RenderDoc build's module loads its librenderdoc.so from there
    const char* old = std::getenv("LD_LIBRARY_PATH");
    environment["LD_LIBRARY_PATH"] = r.renderdocPython + (old && *old ? std::string(":") + old : "");
  }
  // RenderDoc 1.24 replays desktop OpenGL through GLX. Without a display (and without an EGL
  // platform the user chose) the script stops at a GL capture, and it runs again on a private one.
  const bool noDisplay = unset("DISPLAY") && unset("EGL_PLATFORM");
  nlohmann::json dump = runDumpScript(r, environment, noDisplay);
  if (!dump.value("needs_display", false)) return dump;
  const PrivateDisplay display(r.capture, r.workDir / "xvfb.log");
  environment["DISPLAY"] = display.name();
  dump = runDumpScript(r, environment, false);
  dump["replayed_on"] = "a private X display (Xvfb " + display.name() + ")";
  return dump;
}

}  // namespace aor
