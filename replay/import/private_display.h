#pragma once
// A private X server for replaying an OpenGL capture where there is no display: RenderDoc 1.24
// replays desktop GL through GLX, which needs one. Debian's Xvfb is started on a free display
// number of its own choosing (-displayfd), used for one import and stopped when this object goes;
// it also ends with aoreplay if aoreplay is killed.
#include <filesystem>
#include <string>

namespace aor {

class PrivateDisplay {
 public:
  // Throws InputError (exit 2, naming `capture` and the package) when Xvfb is not installed, and
  // std::runtime_error with Xvfb's own last words when it does not come up. Xvfb's output goes to
  // `logFile`.
  PrivateDisplay(const std::filesystem::path& capture, const std::filesystem::path& logFile);
  ~PrivateDisplay();
  PrivateDisplay(const PrivateDisplay&) = delete;
  PrivateDisplay& operator=(const PrivateDisplay&) = delete;

  // The DISPLAY value, e.g. ":99".
  const std::string& name() const { return name_; }

 private:
  int pid_ = -1;
  std::string name_;
};

}  // namespace aor
