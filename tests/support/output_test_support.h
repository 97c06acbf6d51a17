#pragma once
// Shared by the output-safety and kill tests (issue 20): running aoreplay as a child that can be
// stopped or killed, hashes of whole folders, and what a complete result is.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

extern char** environ;

namespace aor::test {

// aoreplay ARGS with extra environment variables, output to /dev/null; returns its process id.
inline pid_t spawnAoreplay(const std::vector<std::string>& args, const std::vector<std::string>& environment = {}) {
  std::vector<std::string> argv = {AOR_EXE};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> argvPointers, envPointers;
  for (auto& a : argv) argvPointers.push_back(a.data());
  argvPointers.push_back(nullptr);
  std::vector<std::string> env(environment);
  for (char** e = environ; *e; ++e) env.emplace_back(*e);
  for (auto& e : env) envPointers.push_back(e.data());
  envPointers.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  if (posix_spawn(&pid, AOR_EXE, &actions, nullptr, argvPointers.data(), envPointers.data()) != 0) pid = -1;
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

// waitpid's status of a child that ended (or stopped, with WUNTRACED).
inline int waitFor(pid_t pid, int options = 0) {
  int status = 0;
  while (waitpid(pid, &status, options) < 0 && errno == EINTR) {
  }
  return status;
}

inline std::string fileBytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Relative path -> hash of the bytes, for every file below `dir` (folders as "/").
inline std::map<std::string, size_t> treeHashes(const std::filesystem::path& dir) {
  std::map<std::string, size_t> hashes;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    const std::string name = std::filesystem::relative(e.path(), dir).generic_string();
    hashes[name] = e.is_directory() ? 0 : std::hash<std::string>()(fileBytes(e.path()));
  }
  return hashes;
}

// Names in `parent` (not recursive), to spot staging folders and lock files left behind.
inline std::set<std::string> namesIn(const std::filesystem::path& parent) {
  std::set<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(parent)) names.insert(e.path().filename().string());
  return names;
}

// `out` holds a complete run result: the marker lists what was written, all of it is there, the
// report parses and names one image pair per replayed frame. Returns the frame count, 0 when not.
inline size_t completeRunFrames(const std::filesystem::path& out) {
  namespace fs = std::filesystem;
  try {
    const auto marker = nlohmann::json::parse(fileBytes(out / ".aoreplay-result.json"));
    for (const auto& entry : marker.at("entries"))
      if (!fs::exists(out / entry.get<std::string>())) return 0;
    const auto report = nlohmann::json::parse(fileBytes(out / "report.json"));
    if (!nlohmann::json::accept(fileBytes(out / "trace.json"))) return 0;
    const size_t frames = report.at("frames").size();
    for (size_t i = 0; i < frames; ++i) {
      const auto stem = out / "ao" / (std::string(4 - std::to_string(i).size(), '0') + std::to_string(i));
      if (!fs::exists(stem.string() + ".exr") || !fs::exists(stem.string() + ".png")) return 0;
    }
    return frames;
  } catch (const std::exception&) {
    return 0;
  }
}

}  // namespace aor::test
