#include "core/output_directory.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <mutex>
#include <set>
#include <atomic>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/input_error.h"
#include "core/json_input.h"

#ifndef AOREPLAY_VERSION
#define AOREPLAY_VERSION "unknown"
#endif

namespace aor {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

constexpr const char* kMarker = ".aoreplay-result.json";

// ---- what each command writes ------------------------------------------------------------------

struct KindInfo {
  const char* name;      // "run"
  const char* mainFile;  // the file every result of the kind holds
  // Entries (relative, '/'-separated) an older result without the marker may hold; '#' stands
  // for one or more digits.
  std::vector<std::string> entries;
  std::function<bool(const json&)> isOurs;  // the main file, parsed, is the kind's
};

const KindInfo& kindInfo(ResultKind kind) {
  static const KindInfo run{"run", "report.json",
                            {"report.json", "report.html", "trace.json", "temporal.svg", "temporal_response.svg", "ao", "ao/#.exr",
                             "ao/#.png"},
                            [](const json& j) { return j.is_object() && j.value("tool", json()) == "aoreplay"; }};
  static const KindInfo sweep{"sweep", "sweep.json",
                              {"sweep.json", "sweep.csv", "sweep.svg", "sweep.html"},
                              [](const json& j) {
                                return j.is_object() && j.contains("rows") && j["rows"].is_array() &&
                                       j.contains("capture") && j["capture"].is_string();
                              }};
  static const KindInfo capture{"capture", "capture.json",
                                {"capture.json", "frames", "frames/#.exr", "frames/#.ref.exr"},
                                [](const json& j) { return j.is_object() && j.value("format", json()) == "aoreplay-capture"; }};
  static const KindInfo ab{"ab", "ab.json", {}, [](const json&) { return false; }};
  static const KindInfo tune{"tune", "tune.json", {}, [](const json&) { return false; }};
  switch (kind) {
    case ResultKind::Run: return run;
    case ResultKind::Sweep: return sweep;
    case ResultKind::Capture: return capture;
    case ResultKind::Ab: return ab;
    case ResultKind::Tune: return tune;
  }
  return run;
}

bool matchesPattern(std::string_view name, std::string_view pattern) {
  size_t n = 0;
  for (char p : pattern) {
    if (p != '#') {
      if (n >= name.size() || name[n] != p) return false;
      ++n;
      continue;
    }
    const size_t start = n;
    while (n < name.size() && name[n] >= '0' && name[n] <= '9') ++n;
    if (n == start) return false;
  }
  return n == name.size();
}

// ---- test-only switch ------------------------------------------------------------------------------

// AOREPLAY_TEST_KILL_AFTER=STEP (SIGKILL) and AOREPLAY_TEST_STOP_AFTER=STEP (SIGSTOP) stop the
// process right after STEP of the replacement; AOREPLAY_TEST_NO_EXCHANGE=1 takes the fallback path
// of file systems without RENAME_EXCHANGE. For the kill test (tests/cli/output_safety_test.cpp).
void reached(const char* step) {
  static const char* killAfter = std::getenv("AOREPLAY_TEST_KILL_AFTER");
  static const char* stopAfter = std::getenv("AOREPLAY_TEST_STOP_AFTER");
  if (killAfter && std::strcmp(killAfter, step) == 0) ::kill(::getpid(), SIGKILL);
  if (stopAfter && std::strcmp(stopAfter, step) == 0) ::kill(::getpid(), SIGSTOP);
}

bool exchangeDisabledForTest() {
  static const bool disabled = [] {
    const char* v = std::getenv("AOREPLAY_TEST_NO_EXCHANGE");
    return v && std::strcmp(v, "1") == 0;
  }();
  return disabled;
}

// ---- outputs in progress, for the termination handler -------------------------------------------------

std::mutex& outputsMutex() {
  static std::mutex m;
  return m;
}
std::set<OutputDirectory*>& activeDirectories() {
  static std::set<OutputDirectory*> s;
  return s;
}
std::set<fs::path>& activeTemporaryFiles() {
  static std::set<fs::path> s;
  return s;
}
std::set<fs::path>& activeScratchFolders() {
  static std::set<fs::path> s;
  return s;
}

// ---- file system helpers -------------------------------------------------------------------------------

std::string errnoText() { return std::strerror(errno); }

// Every entry below `dir` as a '/'-separated relative path (folders too), sorted. Symbolic links
// are listed, never followed.
std::vector<std::string> listTree(const fs::path& dir, std::error_code& ec) {
  std::vector<std::string> names;
  fs::recursive_directory_iterator it(dir, fs::directory_options::none, ec), end;
  for (; !ec && it != end; it.increment(ec)) names.push_back(it->path().lexically_relative(dir).generic_string());
  std::sort(names.begin(), names.end());
  return names;
}

// Removes `dir` and everything below it, one entry at a time, children first (never following
// links). Returns false, with the first error in `ec`, when something could not be removed.
bool removeTree(const fs::path& dir, std::error_code& ec) {
  auto names = listTree(dir, ec);
  if (ec) return false;
  bool first = true;
  for (auto it = names.rbegin(); it != names.rend(); ++it) {  // "ao/0001.exr" sorts after "ao"
    fs::remove(dir / *it, ec);
    if (ec) return false;
    if (first) reached("old-removed-partly");
    first = false;
  }
  fs::remove(dir, ec);
  return !ec;
}

bool sameFile(const struct stat& a, const struct stat& b) { return a.st_dev == b.st_dev && a.st_ino == b.st_ino; }

// `inner` is `outer` or lies below it (both absolute and normalised).
bool isWithin(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i)
    if (i == inner.end() || *i != *o) return false;
  return true;
}

fs::path resolvedPath(const fs::path& p) {
  std::error_code ec;
  fs::path r = fs::weakly_canonical(fs::absolute(p), ec);
  return ec ? fs::absolute(p).lexically_normal() : r;
}

// The process id written in a lock file, for the message to the run that did not get it.
std::string lockHolder(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof(text) - 1, 0);
  if (n <= 0) return "of unknown id";
  const long pid = std::strtol(text, nullptr, 10);
  return pid > 0 ? fmt::format("{}", pid) : "of unknown id";
}

bool allDigits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

// ---- the replacement rule --------------------------------------------------------------------------------

namespace {

// Why `dir` (an existing folder) may not be replaced by a result of `kind`, or "" when it may:
// everything in it was written there by aoreplay, and every folder in it can be emptied.
std::string whyNotReplaceable(const fs::path& dir, ResultKind kind) {
  const KindInfo& info = kindInfo(kind);
  std::error_code ec;
  const auto entries = listTree(dir, ec);
  if (ec) return fmt::format("cannot be listed ({}); not replacing it", ec.message());
  if (entries.empty()) return "";
  const auto unexpected = [](const std::string& entry) {
    return fmt::format("holds {}, which aoreplay did not write there; not replacing it (nothing was changed)",
                       quoteForMessage(entry));
  };
  std::error_code markerError;
  if (fs::is_regular_file(fs::symlink_status(dir / kMarker, markerError))) {
    json marker;
    try {
      marker = readBoundedJson(dir / kMarker, JsonLimits{std::uint64_t(64) << 20, 10'000'000, 8});
    } catch (const InputError& e) {
      return fmt::format("holds a {} that cannot be read ({}); not replacing it", kMarker, e.what());
    }
    if (!marker.is_object() || marker.value("tool", json()) != "aoreplay" || !marker.contains("entries") ||
        !marker["entries"].is_array())
      return fmt::format("holds a {} that is not aoreplay's; not replacing it", kMarker);
    const json kindName = marker.value("kind", json());
    if (kindName != info.name)
      return fmt::format("holds an aoreplay {} result, not a {} result; not replacing it",
                         kindName.is_string() ? quoteForMessage(kindName.get<std::string>()) : "unknown", info.name);
    std::set<std::string> written;
    for (const auto& e : marker["entries"])
      if (e.is_string()) written.insert(e.get<std::string>());
    for (const auto& entry : entries)
      if (entry != kMarker && !written.count(entry)) return unexpected(entry);
  } else {
    // An older result, written before the marker: its main file must be ours, and everything else
    // one of the names its command writes.
    for (const auto& entry : entries) {
      const bool known = std::any_of(info.entries.begin(), info.entries.end(),
                                     [&](const std::string& pattern) { return matchesPattern(entry, pattern); });
      if (!known) return unexpected(entry);
    }
    bool ours = false;
    try {
      ours = info.isOurs(readBoundedJson(dir / info.mainFile, JsonLimits{std::uint64_t(256) << 20, 10'000'000, 128}));
    } catch (const InputError&) {
    }
    if (!ours)
      return fmt::format("has no {} and no {} written by aoreplay {}; not replacing it", kMarker, info.mainFile, info.name);
  }
  // Removing an entry needs write access to its folder: find out now, not half-way through.
  std::vector<std::string> folders = {""};
  for (const auto& entry : entries)
    if (fs::is_directory(fs::symlink_status(dir / entry, ec))) folders.push_back(entry);
  for (const auto& folder : folders)
    if (::access((dir / folder).c_str(), W_OK | X_OK) != 0)
      return fmt::format("cannot be replaced: {} is not writable, so the earlier result could not be removed",
                         folder.empty() ? std::string("the folder") : quoteForMessage(folder + "/"));
  return "";
}

}  // namespace

namespace {

// --out may be neither an input of the run, nor inside one, nor hold one.
void checkApartFromInputs(const fs::path& out, const std::vector<fs::path>& inputs,
                          const std::function<InputError(const std::string&)>& fail) {
  const fs::path resolvedOut = resolvedPath(out);
  for (const auto& input : inputs) {
    const fs::path in = resolvedPath(input);
    if (in == resolvedOut) throw fail(fmt::format("is {}, an input of this run; choose another folder", input.string()));
    if (isWithin(in, resolvedOut))
      throw fail(fmt::format("holds {}, an input of this run; choose another folder", input.string()));
    if (isWithin(resolvedOut, in))
      throw fail(fmt::format("lies inside {}, an input of this run; choose another folder", input.string()));
  }
}

void checkIsFolderOrMissing(const fs::path& out, const std::function<InputError(const std::string&)>& fail) {
  std::error_code ec;
  const auto status = fs::symlink_status(out, ec);
  if (fs::is_symlink(status)) throw fail("is a symbolic link; not replacing it");
  if (fs::exists(status) && !fs::is_directory(status)) throw fail("exists and is not a folder; not replacing it");
}

// An exclusive flock on `lockPath`, refused at once when another process holds it. Its holder
// removes the file when done, so a lock taken on a file that is no longer at the path guards
// nothing: then the one that is there is taken. Returns the descriptor.
int acquireLock(const fs::path& lockPath, const std::function<InputError(const std::string&)>& fail) {
  for (;;) {
    const int fd = ::open(lockPath.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0) throw fail(fmt::format("cannot create the lock file {}: {}", lockPath.string(), errnoText()));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      const std::string holder = error == EWOULDBLOCK ? lockHolder(fd) : "";
      ::close(fd);
      if (error == EWOULDBLOCK)
        throw fail(fmt::format("is being written by another aoreplay run (process {}, lock {}); wait for it or "
                               "choose another folder",
                               holder, lockPath.string()));
      throw fail(fmt::format("cannot lock {}: {}", lockPath.string(), std::strerror(error)));
    }
    struct stat held {}, atPath {};
    if (::fstat(fd, &held) == 0 && ::lstat(lockPath.c_str(), &atPath) == 0 && sameFile(held, atPath)) {
      // The id is only for the message of a run that does not get the lock: failing to write it is harmless.
      const std::string pid = fmt::format("{}\n", ::getpid());
      if (::ftruncate(fd, 0) == 0) (void)!::pwrite(fd, pid.data(), pid.size(), 0);
      return fd;
    }
    ::close(fd);
  }
}

}  // namespace

OutputDirectory::OutputDirectory(fs::path finalPath, ResultKind kind, const std::vector<fs::path>& inputs)
    : final_(fs::absolute(std::move(finalPath)).lexically_normal()), kind_(kind) {
  if (final_.filename().empty()) final_ = final_.parent_path();
  parent_ = final_.parent_path();
  name_ = final_.filename().string();
  const std::function<InputError(const std::string&)> fail = [&](const std::string& problem) {
    return InputError(final_.string(), std::nullopt, "--out", problem);
  };
  if (name_.empty() || name_ == "." || name_ == ".." || final_ == parent_) throw fail("does not name a folder");
  checkApartFromInputs(final_, inputs, fail);
  checkIsFolderOrMissing(final_, fail);
  std::error_code ec;
  fs::create_directories(parent_, ec);
  if (ec) throw fail(fmt::format("cannot create the folder {}: {}", parent_.string(), ec.message()));

  lockPath_ = parent_ / fmt::format(".{}.lock", name_);
  {
    // From creating the lock file to registering this output: a termination meanwhile waits, then
    // removes the lock file too.
    std::lock_guard<std::mutex> guard(outputsMutex());
    lockFd_ = acquireLock(lockPath_, fail);
    activeDirectories().insert(this);
  }
  reached("locked");
  try {
    recoverInterruptedRuns();
    reached("recovered");
    checkIsFolderOrMissing(final_, fail);  // again: the repair may have put a folder back
    if (fs::is_directory(fs::symlink_status(final_, ec)))
      if (std::string why = whyNotReplaceable(final_, kind_); !why.empty()) throw fail(why);
    createStaging(fail);
    reached("staged");
  } catch (...) {
    releaseLock();
    throw;
  }
}

void OutputDirectory::createStaging(const std::function<InputError(const std::string&)>& fail) {
  std::lock_guard<std::mutex> guard(outputsMutex());  // a termination sees it the moment it exists
  staging_ = parent_ / fmt::format(".{}.tmp-{}", name_, ::getpid());
  if (::mkdir(staging_.c_str(), 0777) != 0) {
    const std::string error = errnoText();
    staging_.clear();
    throw fail(fmt::format("cannot create the staging folder: {}", error));
  }
}

// Holding the lock, every .NAME.tmp-PID and .NAME.old-PID beside NAME belongs to a run that died:
// an .old- folder without NAME is a swap interrupted half-way (put it back), anything else is
// garbage (an unfinished new result, or an old one already replaced).
void OutputDirectory::recoverInterruptedRuns() {
  const std::string prefix = "." + name_ + ".";
  std::vector<fs::path> aside, staged;
  std::error_code ec;
  for (fs::directory_iterator it(parent_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string entry = it->path().filename().string();
    if (entry.rfind(prefix, 0) != 0) continue;
    const std::string rest = entry.substr(prefix.size());
    if (rest.rfind("old-", 0) == 0 && allDigits(rest.substr(4))) aside.push_back(it->path());
    if (rest.rfind("tmp-", 0) == 0 && allDigits(rest.substr(4))) staged.push_back(it->path());
  }
  std::sort(aside.begin(), aside.end());
  for (const auto& old : aside) {
    if (!fs::exists(fs::symlink_status(final_, ec))) {
      if (::rename(old.c_str(), final_.c_str()) != 0)
        throw InputError(final_.string(), std::nullopt, "--out",
                         fmt::format("cannot put back the earlier result {} that an interrupted run moved aside: {}",
                                     old.string(), errnoText()));
      fmt::print(stderr, "aoreplay: put back {} (an interrupted run had moved it aside)\n", final_.string());
      continue;
    }
    staged.push_back(old);
  }
  for (const auto& dead : staged)
    if (!removeTree(dead, ec))
      fmt::print(stderr, "aoreplay: warning: cannot remove {}, left by an interrupted run: {}\n", dead.string(),
                 ec.message());
}

void OutputDirectory::commit() {
  std::lock_guard<std::mutex> guard(outputsMutex());  // a termination waits for the swap
  std::error_code ec;
  auto names = listTree(staging_, ec);
  if (ec) throw std::runtime_error(fmt::format("cannot list {}: {}", staging_.string(), ec.message()));
  nlohmann::ordered_json marker;
  marker["tool"] = "aoreplay";
  marker["version"] = AOREPLAY_VERSION;
  marker["kind"] = kindInfo(kind_).name;
  marker["entries"] = names;
  {
    std::ofstream out(staging_ / kMarker, std::ios::binary | std::ios::trunc);
    out << marker.dump(1) << "\n";
    if (!out) throw std::runtime_error(fmt::format("cannot write {}", (staging_ / kMarker).string()));
  }
  reached("marked");
  swapIn();
  committed_ = true;
}

// A result that something else was put into during the run is kept as it is.
void OutputDirectory::swapIn() {
  const std::function<InputError(const std::string&)> appeared = [&](const std::string& why) {
    return InputError(final_.string(), std::nullopt, "--out",
                      fmt::format("changed during the run: {}; the new result was discarded", why));
  };
  std::error_code ec;
  const auto status = fs::symlink_status(final_, ec);
  if (!fs::exists(status)) {
    if (::rename(staging_.c_str(), final_.c_str()) != 0)
      throw appeared(fmt::format("cannot move the new result into place: {}", errnoText()));
    reached("moved-in");
    return;
  }
  if (!fs::is_directory(status)) throw appeared("it is no longer a folder");
  if (std::string why = whyNotReplaceable(final_, kind_); !why.empty()) throw appeared(why);

  // The previous result ends up at `old`, NAME holds the new one.
  const fs::path old = exchangeIn(appeared) ? staging_ : moveAsideAndIn(appeared);
  if (!removeTree(old, ec))
    fmt::print(stderr, "aoreplay: warning: the new result is in place, but the earlier one (now {}) could not be removed: {}\n",
               old.string(), ec.message());
  reached("old-removed");
}

// Swaps staging and NAME in one step. Returns false where the file system cannot (the caller then
// falls back to moveAsideAndIn).
bool OutputDirectory::exchangeIn(const std::function<InputError(const std::string&)>& appeared) {
  if (exchangeDisabledForTest()) return false;
  if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, final_.c_str(), RENAME_EXCHANGE) != 0) {
    if (errno == EINVAL || errno == ENOSYS || errno == ENOTSUP) return false;
    throw appeared(fmt::format("cannot swap the new result in: {}", errnoText()));
  }
  reached("exchanged");
  if (std::string why = whyNotReplaceable(staging_, kind_); !why.empty()) {  // changed since the last check
    ::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, final_.c_str(), RENAME_EXCHANGE);
    throw appeared(why);
  }
  return true;
}

// NAME moved aside to .NAME.old-PID, staging renamed to NAME: between the two, a kill leaves no
// NAME, and the next run puts the old one back (recoverInterruptedRuns). Returns the aside.
fs::path OutputDirectory::moveAsideAndIn(const std::function<InputError(const std::string&)>& appeared) {
  const fs::path old = parent_ / fmt::format(".{}.old-{}", name_, ::getpid());
  if (::rename(final_.c_str(), old.c_str()) != 0)
    throw appeared(fmt::format("cannot move the earlier result aside: {}", errnoText()));
  reached("moved-aside");
  if (std::string why = whyNotReplaceable(old, kind_); !why.empty()) {
    ::rename(old.c_str(), final_.c_str());
    throw appeared(why);
  }
  if (::rename(staging_.c_str(), final_.c_str()) != 0) {
    const std::string error = errnoText();
    ::rename(old.c_str(), final_.c_str());
    throw appeared(fmt::format("cannot move the new result into place: {}", error));
  }
  reached("moved-in");
  return old;
}

void OutputDirectory::abandon() {
  if (!committed_ && !staging_.empty()) {
    std::error_code ignored;
    removeTree(staging_, ignored);
  }
  if (lockFd_ >= 0) {
    ::unlink(lockPath_.c_str());
    ::close(lockFd_);
    lockFd_ = -1;
  }
}

void OutputDirectory::releaseLock() {
  std::lock_guard<std::mutex> guard(outputsMutex());
  activeDirectories().erase(this);
  abandon();
  reached("unlocked");
}

OutputDirectory::~OutputDirectory() { releaseLock(); }

// ---- single files -----------------------------------------------------------------------------------

namespace {

// ".NAME.tmp-PID" files beside `path` whose process is gone.
void removeDeadTemporaryFiles(const fs::path& path) {
  const std::string prefix = "." + path.filename().string() + ".tmp-";
  std::error_code ec;
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string entry = it->path().filename().string();
    if (entry.rfind(prefix, 0) != 0 || !allDigits(entry.substr(prefix.size()))) continue;
    const long pid = std::strtol(entry.c_str() + prefix.size(), nullptr, 10);
    if (pid > 0 && pid != long(::getpid()) && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

}  // namespace

void writeFileAtomically(const fs::path& path, const std::string& text, const std::vector<fs::path>& inputs) {
  if (path == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    if (std::fflush(stdout) != 0) throw std::runtime_error("cannot write to standard output");
    return;
  }
  auto fail = [&](const std::string& problem) { return InputError(path.string(), std::nullopt, "", problem); };
  if (!path.has_filename()) throw fail("names a folder, not a file");
  struct stat existing {};
  if (::lstat(path.c_str(), &existing) == 0) {
    if (S_ISDIR(existing.st_mode)) throw fail("names a folder, not a file");
    if (S_ISLNK(existing.st_mode)) throw fail("is a symbolic link; only a regular file is replaced");
    if (!S_ISREG(existing.st_mode)) throw fail("is not a regular file (a FIFO, socket or device); not replacing it");
    for (const auto& input : inputs) {
      struct stat in {};
      if (::stat(input.c_str(), &in) == 0 && sameFile(in, existing))
        throw fail(fmt::format("is {}, an input of this run; not overwriting it", input.string()));
    }
  }
  std::error_code ec;
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw fail(fmt::format("cannot create the folder {}: {}", path.parent_path().string(), ec.message()));
  }
  removeDeadTemporaryFiles(path);
  const fs::path tmp = path.parent_path() / fmt::format(".{}.tmp-{}", path.filename().string(), ::getpid());
  {
    std::lock_guard<std::mutex> guard(outputsMutex());
    activeTemporaryFiles().insert(tmp);
  }
  const auto forget = [&] {
    std::lock_guard<std::mutex> guard(outputsMutex());
    activeTemporaryFiles().erase(tmp);
  };
  try {
    fs::remove(tmp, ec);
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw fail(fmt::format("cannot create {}: {}", tmp.string(), errnoText()));
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) throw fail(fmt::format("cannot write {}: {}", tmp.string(), errnoText()));
    fs::rename(tmp, path, ec);
    if (ec) throw fail("cannot move the new file into place: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    forget();
    throw;
  }
  forget();
}

// ---- scratch folders -------------------------------------------------------------------------------

ScratchFolder::ScratchFolder(const std::string& prefix) {
  std::string pattern = (fs::temp_directory_path() / (prefix + "-XXXXXX")).string();
  std::lock_guard<std::mutex> guard(outputsMutex());  // created and registered before a signal can look
  if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder in " + pattern);
  path_ = pattern;
  activeScratchFolders().insert(path_);
}

ScratchFolder::~ScratchFolder() {
  std::lock_guard<std::mutex> guard(outputsMutex());
  std::error_code ignored;
  fs::remove_all(path_, ignored);
  activeScratchFolders().erase(path_);
}

// ---- termination ------------------------------------------------------------------------------------

namespace {
std::atomic<int> gForwardTo{0};
}  // namespace

void forwardTerminationSignalsTo(int pid) { gForwardTo = pid; }

void cleanUpOutputsOnTermination() {
  static sigset_t signals;
  sigemptyset(&signals);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&signals, s);
  // Blocked here, so in every thread started later; the thread below takes them.
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::thread([] {
    int received = 0;
    // While a child does the work (forwardTerminationSignalsTo), its signals are passed on and the
    // child, which holds the outputs, decides; this process ends when it does.
    while (sigwait(&signals, &received) != 0 || gForwardTo > 0) {
      if (gForwardTo > 0 && received != 0) ::kill(gForwardTo, received);
      received = 0;
    }
    {
      std::lock_guard<std::mutex> guard(outputsMutex());
      for (OutputDirectory* d : activeDirectories()) d->abandon();
      for (const auto& tmp : activeTemporaryFiles()) ::unlink(tmp.c_str());
      std::error_code ignored;
      for (const auto& folder : activeScratchFolders()) fs::remove_all(folder, ignored);
      // Ends the process by the signal itself, so its parent sees what happened.
      ::signal(received, SIG_DFL);
      pthread_sigmask(SIG_UNBLOCK, &signals, nullptr);
      ::kill(::getpid(), received);
      ::pause();
    }
  }).detach();
}

}  // namespace aor
