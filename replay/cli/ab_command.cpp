// `aoreplay ab CAPTURE --rounds N`: is B slower than A? Runs `run CAPTURE ARGS` as fresh processes
// of the A and B binaries (both this one by default), in ABBA order so that drift over the
// experiment (a machine warming up, load coming and going) falls on both sides alike, keeps every
// run's report.json under DIR/a/ and DIR/b/, and judges them as `compare DIR/a DIR/b` does.
#include <unistd.h>
#include <wordexp.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>

#include <fmt/format.h>

#include "capture/capture.h"
#include "core/input_error.h"
#include "cli/commands.h"
#include "cost/callgrind_counter.h"
#include "cli/compare_command.h"
#include "report/html/compare_page.h"
#include "cli/handlers.h"
#include "cli/number_options.h"
#include "core/subprocess.h"
#include "core/output_directory.h"

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
  std::string cost = "time";  // passed to every run as --cost
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
  for (const auto& word : out) {
    if (word == "--out" || word.starts_with("--out="))
      throw InputError("", std::nullopt, flag, "sets --out; ab chooses every run's output folder (DIR/a/NN, DIR/b/NN)");
    if (word == "--cost" || word.starts_with("--cost="))
      throw InputError("", std::nullopt, flag, "sets --cost; ab's own --cost applies to both sides (one measure a comparison)");
  }
  return out;
}

std::string resolveBinary(const std::string& given, const std::string& flag) {
  if (given.empty()) return fs::read_symlink("/proc/self/exe").string();
  std::error_code ec;
  if (!fs::is_regular_file(given, ec) || access(given.c_str(), X_OK) != 0)
    throw InputError(given, std::nullopt, flag, "is not an executable file");
  return fs::absolute(given).string();
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
std::string totalOf(const fs::path& report, const std::string& cost) {
  try {
    std::ifstream in(report);
    auto json = nlohmann::json::parse(in);
    if (cost != "time") return fmt::format(", total {:.0f} {}", json.at(cost + "_total").get<double>(), cost);
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
    if (args.cost != "time") argv.insert(argv.end(), {"--cost", args.cost});  // binaries older than --cost take time runs
    fmt::print(stderr, "ab: run {}/{} (round {}/{}): {} ...", i + 1, order.size(), i / 4 + 1, args.rounds, name);
    std::fflush(stderr);
    auto start = std::chrono::steady_clock::now();
    const ProcessResult run = runProcess(argv, {}, log, log, std::chrono::seconds(args.runTimeout));
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!run.started) throw std::runtime_error(fmt::format("cannot start {}: {}", argv[0], run.startError));
    const int status = run.signal ? 128 + run.signal : run.exitCode;
    if (run.timedOut) {
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
    fmt::print(stderr, " {:.1f} s{}\n", seconds, totalOf(runOut / "report.json", args.cost));
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
                        {"cost", args.cost},
                        {"a", {{"binary", sides[0].binary}, {"args", sides[0].args}}},
                        {"b", {{"binary", sides[1].binary}, {"args", sides[1].args}}},
                        {"runs", runs}, {"exit_status", status}};
  writeFileAtomically(out.staging() / "ab.json", record.dump(2) + "\n");
  out.commit();
  fmt::print("outputs: {}/ (a/NN, b/NN: one run each; compare.json; compare.html; ab.json; logs/)\n", out.finalPath().string());
  return status;
}

std::vector<std::string> costMeasureNames() {
  std::vector<std::string> names;
  for (CostMeasure m : kCostMeasures) names.push_back(costMeasureName(m));
  return names;
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
  cmd->add_option("--cost", args->cost,
                  "time, or instructions or cycles: every run counted under callgrind on lavapipe (run --cost), "
                  "judged exactly; one round then suffices")
      ->check(CLI::IsMember(costMeasureNames()))
      ->capture_default_str();
  addCompareFlags(*cmd, args->flags);
  handlers()["ab"] = [args] { return abCommand(*args); };
}

}  // namespace aor::cli
