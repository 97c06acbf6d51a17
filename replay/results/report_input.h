#pragma once
// What `aoreplay record` takes from a report.json: the series it belongs to and its timings.
#include <filesystem>
#include <string>

#include "report/compare.h"

namespace aor::results {

// A series is one thing timed in one place: the same capture content, technique and settings,
// frames and timing mode, on the same device and driver, by the same tool version. Runs of one
// series are comparable; anything else starts a new series.
struct SeriesKey {
  std::string captureName;  // for people; not part of the fingerprint (a renamed copy is the same capture)
  std::string captureSha256;
  std::string technique;
  std::string settings;  // report.json's settings, as compact JSON with sorted keys
  std::string frames;    // run.frames, as JSON
  std::string timingMode;
  std::string device, driver;
  std::string toolVersion;
  // What the values measure: "time" (ms), or a count under callgrind ("instructions", "cycles")
  // with the report's cost.key (device, driver, CPU model, valgrind, caches): counts compare only
  // within one key, so another runner's CPU starts a series of its own.
  std::string measure = "time";
  std::string costKey;
  bool counted() const { return measure != "time"; }
  // SHA-256 of every field above but the capture's name, as one canonical JSON object (the
  // measure and cost key only for counts, so timed series keep the fingerprints they had).
  std::string fingerprint() const;
  // "capture technique on device": what tables and plots call it.
  std::string label() const;
};

struct ReportInput {
  std::string source;        // the path as given
  std::string reportSha256;  // of the file's bytes: the run's identity (recording it twice stores it once)
  SeriesKey series;
  TimingSamples passes;  // every pass and the total, as compare reads them (counts: per frame)
};

// Throws InputError naming the file and field (a report from before report.json had
// capture.content_sha256 and tool_version is refused: run it again with this aoreplay).
ReportInput readReportInput(const std::filesystem::path& path);

}  // namespace aor::results
