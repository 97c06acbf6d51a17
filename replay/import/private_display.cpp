#include "import/private_display.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

#include "core/input_error.h"
#include "core/subprocess.h"

namespace aor {

namespace {

// Xvfb is up in well under a second; a loaded runner gets ten.
constexpr int kStartMilliseconds = 10000;

// What Xvfb wrote on the display-number pipe before closing it ("" when it closed at once).
std::string readDisplayNumber(int fd) {
  std::string text;
  pollfd p{fd, POLLIN, 0};
  while (text.find('\n') == std::string::npos && ::poll(&p, 1, kStartMilliseconds) > 0) {
    char buffer[32];
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n <= 0) break;
    text.append(buffer, size_t(n));
  }
  return text.substr(0, text.find('\n'));
}

void stop(int pid) {
  ::kill(pid, SIGTERM);
  waitForProcess(pid, std::chrono::seconds(5));  // which kills it if SIGTERM was not enough
}

}  // namespace

PrivateDisplay::PrivateDisplay(const std::filesystem::path& capture, const std::filesystem::path& logFile) {
  int numberPipe[2];
  if (::pipe(numberPipe) != 0) throw std::runtime_error(fmt::format("pipe for Xvfb: {}", std::strerror(errno)));
  ::fcntl(numberPipe[0], F_SETFD, FD_CLOEXEC);  // only the write end goes to Xvfb
  const SpawnedProcess x = spawnProcess({"Xvfb", "-displayfd", std::to_string(numberPipe[1]), "-nolisten", "tcp",
                                         "-screen", "0", "1280x1024x24"},
                                        {}, logFile, logFile);
  ::close(numberPipe[1]);
  if (x.pid < 0) {
    ::close(numberPipe[0]);
    if (x.startErrno == ENOENT)
      throw InputError(capture.string(), std::nullopt, "",
                       "an OpenGL capture replays on an X display, DISPLAY is unset and Xvfb is not installed: "
                       "install Debian's xvfb (apt-get install xvfb) for a private display, set DISPLAY, or set "
                       "EGL_PLATFORM=surfaceless to replay through Mesa's EGL");
    throw std::runtime_error(fmt::format("cannot start Xvfb: {}", x.startError));
  }
  pid_ = x.pid;
  const std::string number = readDisplayNumber(numberPipe[0]);
  ::close(numberPipe[0]);
  if (number.empty() || number.find_first_not_of("0123456789") != std::string::npos) {
    stop(pid_);
    throw std::runtime_error(fmt::format("Xvfb did not start a display (it has {} s); its last output: {}",
                                         kStartMilliseconds / 1000, outputTail(logFile)));
  }
  name_ = ":" + number;
}

PrivateDisplay::~PrivateDisplay() { stop(pid_); }

}  // namespace aor
