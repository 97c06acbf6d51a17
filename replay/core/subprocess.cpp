#include "core/subprocess.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <thread>

namespace aor {

namespace {

// The child: redirect, adjust the environment, exec; on failure report errno through `errorPipe`
// (closed on a successful exec, so the parent reads nothing then).
[[noreturn]] void execChild(const std::vector<std::string>& argv, const std::map<std::string, std::string>& environment,
                            const std::filesystem::path& stdoutFile, const std::filesystem::path& stderrFile,
                            int errorPipe) {
  auto openOutput = [](const std::filesystem::path& file) {
    return file.empty() ? -1 : ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  };
  const int out = openOutput(stdoutFile);
  // One file for both: shared, so neither overwrites the other.
  const int err = stderrFile == stdoutFile ? out : openOutput(stderrFile);
  const int in = ::open("/dev/null", O_RDONLY);
  if (out >= 0) ::dup2(out, STDOUT_FILENO);
  if (err >= 0) ::dup2(err, STDERR_FILENO);
  if (in >= 0) ::dup2(in, STDIN_FILENO);
  // The child ends with aoreplay (a signal that ends aoreplay would else leave it running), and
  // takes the usual signals itself: aoreplay's main thread blocks them for its signal thread, and
  // a blocked mask survives exec.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  sigset_t signals;
  sigemptyset(&signals);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&signals, s);
  ::sigprocmask(SIG_UNBLOCK, &signals, nullptr);
  for (const auto& [key, value] : environment) ::setenv(key.c_str(), value.c_str(), 1);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  ::execvp(args[0], args.data());
  const int code = errno;
  [[maybe_unused]] auto written = ::write(errorPipe, &code, sizeof code);
  ::_exit(127);
}

}  // namespace

SpawnedProcess spawnProcess(const std::vector<std::string>& argv, const std::map<std::string, std::string>& environment,
                            const std::filesystem::path& stdoutFile, const std::filesystem::path& stderrFile) {
  SpawnedProcess spawned;
  int errorPipe[2];
  if (argv.empty() || ::pipe2(errorPipe, O_CLOEXEC) != 0) {
    spawned.startError = argv.empty() ? "no program" : std::strerror(errno);
    return spawned;
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    spawned.startError = std::strerror(errno);
    ::close(errorPipe[0]);
    ::close(errorPipe[1]);
    return spawned;
  }
  if (pid == 0) execChild(argv, environment, stdoutFile, stderrFile, errorPipe[1]);
  ::close(errorPipe[1]);
  int execErrno = 0;
  const bool execFailed = ::read(errorPipe[0], &execErrno, sizeof execErrno) == sizeof execErrno;
  ::close(errorPipe[0]);
  if (execFailed) {
    ::waitpid(pid, nullptr, 0);
    spawned.startError = std::strerror(execErrno);
    spawned.startErrno = execErrno;
    return spawned;
  }
  spawned.pid = pid;
  return spawned;
}

ProcessResult waitForProcess(int pid, std::chrono::milliseconds timeLimit) {
  ProcessResult result;
  result.started = true;
  const auto deadline = std::chrono::steady_clock::now() + timeLimit;
  int status = 0;
  while (true) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) return result;
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      result.timedOut = true;
      return result;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (WIFEXITED(status)) result.exitCode = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  return result;
}

std::string outputTail(const std::filesystem::path& file, size_t lines) {
  std::vector<std::string> kept;
  std::ifstream in(file, std::ios::binary);
  for (std::string line; std::getline(in, line);)
    if (line.find_first_not_of(" \t\r") != std::string::npos) kept.push_back(line);
  if (kept.empty()) return "(nothing)";
  std::string joined;
  for (size_t i = kept.size() > lines ? kept.size() - lines : 0; i < kept.size(); ++i)
    joined += (joined.empty() ? "" : " | ") + kept[i];
  return joined;
}

ProcessResult runProcess(const std::vector<std::string>& argv, const std::map<std::string, std::string>& environment,
                         const std::filesystem::path& stdoutFile, const std::filesystem::path& stderrFile,
                         std::chrono::seconds timeLimit) {
  const SpawnedProcess spawned = spawnProcess(argv, environment, stdoutFile, stderrFile);
  if (spawned.pid < 0) return {.startError = spawned.startError};
  return waitForProcess(spawned.pid, timeLimit);
}

}  // namespace aor
