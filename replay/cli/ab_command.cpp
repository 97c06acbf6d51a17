// `aoreplay ab CAPTURE --rounds N`: is B slower than A? Runs `run CAPTURE ARGS` as fresh processes
// of the A and B binaries (both this one by default), in ABBA order so that drift over the
// experiment (a machine warming up, load coming and going) falls on both sides alike, keeps every
// run's report.json under DIR/a/ and DIR/b/, and judges them as `compare DIR/a DIR/b` does.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <wordexp.h>

#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>

#include <fmt/format.h>

#include "capture/capture.h"
#include "capture/input_error.h"
#include "cli/commands.h"
#include "cli/compare_command.h"
#include "report/html/compare_page.h"
#include "cli/handlers.h"
#include "cli/number_options.h"
#include "report/output_directory.h"

extern char** environ;

namespace aor::cli {
namespace {

namespace fs = std::filesystem;

struct AbArgs {
  std::string capture;
  int rounds = 0;
  std::string aBinary, bBinary;  // default: this binary
  std::string aArgs, bArgs;      // `aoreplay run` arguments of each side, split as the shell would
  std::string out;
  int runTimeout = 3600;  // seconds a run may take
  CompareFlags flags;
};

struct Side {
  char label;  // 'a' or 'b'
  std::string binary;
  std::vector<std::string> args;
  int runs = 0;  // started so far
};

// Splits ARGS into words as a shell would (quotes, backslashes, $VARIABLES), without running
// commands: wordexp(3) with command substitution refused.
std::vector<std::string> splitWords(const std::string& text, const std::string& flag) {
  wordexp_t words{};
  int status = wordexp(text.c_str(), &words, WRDE_NOCMD);
  if (status != 0) {
    if (status != WRDE_NOSPACE) wordfree(&words);
    const char* why = status == WRDE_BADCHAR ? "holds an unquoted | & ; < > ( ) { } or newline"
                      : status == WRDE_CMDSUB ? "asks for command substitution, which ab does not run"
                      : status == WRDE_SYNTAX ? "is not well quoted"
                                              : "cannot be split into words";
    throw InputError("", std::nullopt, flag, fmt::format("\"{}\" {}", text, why));
  }
  std::vector<std::string> out(words.we_wordv, words.we_wordv + words.we_wordc);
  wordfree(&words);
  for (const auto& word : out)
    if (word == "--out" || word.starts_with("--out="))
      throw InputError("", std::nullopt, flag, "sets --out; ab chooses every run's output folder (DIR/a/NN, DIR/b/NN)");
  return out;
}

std::string resolveBinary(const std::string& given, const std::string& flag) {
  if (given.empty()) return fs::read_symlink("/proc/self/exe").string();
  std::error_code ec;
  if (!fs::is_regular_file(given, ec) || access(given.c_str(), X_OK) != 0)
    throw InputError(given, std::nullopt, flag, "is not an executable file");
  return fs::absolute(given).string();
}

// The spawned run takes signals as any program does: aoreplay's main thread blocks them for its
// signal thread, and a blocked mask would survive the exec (a killed ab left its run going).
void defaultSignals(posix_spawnattr_t& attributes) {
  sigset_t none, usual;
  sigemptyset(&none);
  sigemptyset(&usual);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&usual, s);
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &usual);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
}

// Waits for `pid`, killing it (SIGTERM, then SIGKILL 10 s later) past `limit`.
int waitWithin(pid_t pid, std::chrono::seconds limit, bool& timedOut) {
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  for (bool termSent = false;;) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) return status;
    if (done < 0 && errno != EINTR) throw std::runtime_error(fmt::format("waiting for a run: {}", std::strerror(errno)));
    const auto elapsed = std::chrono::steady_clock::now() - start;
    if (elapsed > limit && !termSent) ::kill(pid, SIGTERM), termSent = timedOut = true;
    if (elapsed > limit + std::chrono::seconds(10)) ::kill(pid, SIGKILL);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

// Runs argv with stdin from /dev/null and stdout and stderr into `log`; returns the exit status
// (128 + the signal when it was killed by one). A run past `limit` is killed (timedOut set); a
// signal that ends ab ends the run too (report/output_directory.h, registerChildProcess).
int runProcess(const std::vector<std::string>& argv, const fs::path& log, std::chrono::seconds limit, bool& timedOut) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawnattr_t attributes;
  defaultSignals(attributes);
  std::vector<char*> raw;
  for (const auto& a : argv) raw.push_back(const_cast<char*>(a.c_str()));
  raw.push_back(nullptr);
  pid_t pid = 0;
  int error = posix_spawn(&pid, raw[0], &actions, &attributes, raw.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (error != 0) throw std::runtime_error(fmt::format("cannot start {}: {}", argv[0], std::strerror(error)));
  registerChildProcess(pid);
  const int status = waitWithin(pid, limit, timedOut);
  forgetChildProcess(pid);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string lastLines(const fs::path& file, size_t count) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::string tail;
  for (size_t i = lines.size() > count ? lines.size() - count : 0; i < lines.size(); ++i) tail += "  " + lines[i] + "\n";
  return tail;
}

// The run's total for the progress line, when its report says it.
std::string totalOf(const fs::path& report) {
  try {
    std::ifstream in(report);
    auto json = nlohmann::json::parse(in);
    return fmt::format(", total {:.3f} ms", json.at("gpu_ms_total_median").get<double>());
  } catch (const std::exception&) {
    return "";
  }
}

// ABBA within each round: A B B A, then again. Whatever drifts linearly over a round costs both sides the same.
std::vector<int> abbaOrder(int rounds) {
  std::vector<int> order;
  for (int r = 0; r < rounds; ++r)
    for (int side : {0, 1, 1, 0}) order.push_back(side);
  return order;
}

int abCommand(const AbArgs& args) {
  Capture capture = loadCapture(args.capture);  // a bad capture is bad input before any run starts
  Side sides[2] = {{'a', resolveBinary(args.aBinary, "--a-binary"), splitWords(args.aArgs, "--a")},
                   {'b', resolveBinary(args.bBinary, "--b-binary"), splitWords(args.bArgs, "--b")}};
  OutputDirectory out(args.out.empty() ? fs::path("out") / (capture.name + "-ab") : fs::path(args.out), ResultKind::Ab,
                      {capture.folder});
  fs::create_directories(out.staging() / "logs");
  auto order = abbaOrder(args.rounds);
  nlohmann::json runs = nlohmann::json::array();
  for (size_t i = 0; i < order.size(); ++i) {
    Side& side = sides[order[i]];
    std::string name = fmt::format("{}/{:02d}", side.label, ++side.runs);
    fs::path runOut = out.staging() / name;
    fs::path log = out.staging() / "logs" / fmt::format("{}-{:02d}.txt", side.label, side.runs);
    std::vector<std::string> argv{side.binary, "run", args.capture};
    argv.insert(argv.end(), side.args.begin(), side.args.end());
    argv.insert(argv.end(), {"--out", runOut.string()});
    fmt::print(stderr, "ab: run {}/{} (round {}/{}): {} ...", i + 1, order.size(), i / 4 + 1, args.rounds, name);
    std::fflush(stderr);
    auto start = std::chrono::steady_clock::now();
    bool timedOut = false;
    int status = runProcess(argv, log, std::chrono::seconds(args.runTimeout), timedOut);
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (timedOut) {
      fmt::print(stderr, " killed after {} s\nab: {} ran past --run-timeout {}; the last lines of its output:\n{}ab: nothing "
                         "was kept\n",
                 args.runTimeout, name, args.runTimeout, lastLines(log, 20));
      return kExitFailed;
    }
    if (status != 0) {
      fmt::print(stderr, " exit {}\nab: {} failed; the last lines of its output:\n{}ab: nothing was kept\n", status, name,
                 lastLines(log, 20));
      return status == kExitBadInput || status == kExitNoDevice ? status : kExitFailed;
    }
    fmt::print(stderr, " {:.1f} s{}\n", seconds, totalOf(runOut / "report.json"));
    runs.push_back({{"order", i + 1}, {"side", std::string(1, side.label)}, {"out", name}, {"wall_s", seconds}});
  }
  auto side = [&](char label) {
    auto timings = loadSide(out.staging() / std::string(1, label));
    timings.source = (out.finalPath() / std::string(1, label)).string();
    return timings;
  };
  auto comparison = judgeSides(side('a'), side('b'), args.flags);
  int status = reportComparison(comparison, args.flags, {out.finalPath()});
  writeFileAtomically(out.staging() / "compare.json", comparisonJson(comparison, args.flags.options).dump(2) + "\n");
  writeFileAtomically(out.staging() / "compare.html", html::comparePageHtml(comparison, args.flags.options));
  nlohmann::json record{{"tool", "aoreplay ab"}, {"capture", args.capture}, {"rounds", args.rounds}, {"order", "ABBA"},
                        {"a", {{"binary", sides[0].binary}, {"args", sides[0].args}}},
                        {"b", {{"binary", sides[1].binary}, {"args", sides[1].args}}},
                        {"runs", runs}, {"exit_status", status}};
  writeFileAtomically(out.staging() / "ab.json", record.dump(2) + "\n");
  out.commit();
  fmt::print("outputs: {}/ (a/NN, b/NN: one run each; compare.json; compare.html; ab.json; logs/)\n", out.finalPath().string());
  return status;
}

}  // namespace

void registerAbCommand(CLI::App& app) {
  auto args = std::make_shared<AbArgs>();
  auto* cmd = app.add_subcommand("ab", "is B slower than A? fresh `run` processes in ABBA order, judged as compare DIR/a DIR/b");
  cmd->add_option("capture", args->capture, "capture folder (holding capture.json)")->required();
  cmd->add_option("--rounds", args->rounds, "rounds of A B B A (each adds two runs a side)")
      ->required()
      ->check(wholeIn(1, 10000));
  cmd->add_option("--a-binary", args->aBinary, "aoreplay binary of side A (default: this one)");
  cmd->add_option("--b-binary", args->bBinary, "aoreplay binary of side B (default: this one)");
  cmd->add_option("--a", args->aArgs, "`run` arguments of side A, one string (e.g. \"--preset ultra\")");
  cmd->add_option("--b", args->bArgs, "`run` arguments of side B, one string (e.g. \"--set slices=4\")");
  cmd->add_option("--out", args->out, "output folder (default out/<capture name>-ab/)");
  cmd->add_option("--run-timeout", args->runTimeout, "seconds one run may take; a run past it is killed and ab fails")
      ->check(wholeIn(1, 604800))
      ->capture_default_str();
  addCompareFlags(*cmd, args->flags);
  handlers()["ab"] = [args] { return abCommand(*args); };
}

}  // namespace aor::cli
