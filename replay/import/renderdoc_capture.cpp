#include "import/renderdoc_capture.h"

#include <unistd.h>

#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/input_error.h"
#include "core/json_input.h"
#include "import/renderdoc_script.h"
#include "core/output_directory.h"

namespace aor {

extern const std::string_view kRenderDocCaptureScript;  // renderdoc_capture.py, embedded at build time

namespace {

namespace fs = std::filesystem;

// An existing --out is replaced only when it is a capture itself (RenderDoc's files begin "RDOC").
void checkOut(const fs::path& out) {
  if (out.extension() != ".rdc") throw InputError(out.string(), std::nullopt, "--out", "must name a .rdc file");
  std::error_code ec;
  const auto status = fs::symlink_status(out, ec);
  if (!fs::exists(status)) return;
  char magic[4] = {};
  std::ifstream in(out, std::ios::binary);
  if (!fs::is_regular_file(status) || !in.read(magic, 4) || std::string_view(magic, 4) != "RDOC")
    throw InputError(out.string(), std::nullopt, "--out", "exists and is not a RenderDoc capture; not replacing it");
}

std::vector<std::string> scriptArguments(const FrameCaptureRequest& r, const fs::path& partial, const fs::path& result) {
  std::vector<std::string> args = {"--out", partial.string(), "--result", result.string(), "--after-frames",
                                   std::to_string(r.afterFrames), "--timeout", std::to_string(r.timeoutSeconds)};
  if (!r.afterRegister.empty()) args.insert(args.end(), {"--after-register", r.afterRegister});
  if (!r.afterTrigger.empty()) args.insert(args.end(), {"--after-trigger", r.afterTrigger});
  if (!r.renderdocPython.empty()) args.insert(args.end(), {"--renderdoc-python", r.renderdocPython});
  args.push_back("--");
  args.insert(args.end(), r.program.begin(), r.program.end());
  return args;
}

}  // namespace

FrameCapture captureFrame(const FrameCaptureRequest& r) {
  if (r.program.empty()) throw InputError("", std::nullopt, "PROGRAM", "no program to capture (give it after --)");
  checkOut(r.out);
  ScratchFolder work("aoreplay-renderdoc-capture");
  const fs::path partial = work.path() / "frame.rdc", result = work.path() / "result.json";
  std::map<std::string, std::string> environment;
  if (!r.renderdocPython.empty()) environment["LD_LIBRARY_PATH"] = r.renderdocPython;
  const ProcessResult p = runRenderDocScript(kRenderDocCaptureScript, "renderdoc_capture.py", scriptArguments(r, partial, result),
                                             environment, work.path(), std::chrono::seconds(r.timeoutSeconds + 30));
  if (p.timedOut || !fs::exists(result))
    throw std::runtime_error(fmt::format("the RenderDoc capture script failed ({}): {}",
                                         p.timedOut ? "it hung" : p.signal ? fmt::format("signal {}", p.signal)
                                                                           : fmt::format("exit {}", p.exitCode),
                                         outputTail(work.path() / "script.err")));
  const nlohmann::json done = readBoundedJson(result, JsonLimits{}, "the capture script's result");
  if (done.contains("error"))
    throw InputError(r.program.front(), std::nullopt, done["error"].at("field").get<std::string>(),
                     done["error"].at("message").get<std::string>());
  const nlohmann::json& c = done.at("captured");
  std::error_code ec;
  fs::rename(partial, r.out, ec);
  if (ec) {  // another file system: copy, then move into place beside --out
    const fs::path beside = fs::path(r.out.string() + fmt::format(".tmp-{}", ::getpid()));
    try {
      fs::copy_file(partial, beside, fs::copy_options::overwrite_existing);
      fs::rename(beside, r.out);
    } catch (...) {
      fs::remove(beside, ec);
      throw;
    }
  }
  return {c.at("frame").get<int>(), c.at("api").get<std::string>(), c.at("target").get<std::string>()};
}

}  // namespace aor
