#pragma once
// Output folders and files that neither a careless --out, a second run nor a kill can break
// (docs/robustness.md, "Outputs and inputs"):
//   - a folder is replaced only when everything in it is something aoreplay wrote there: a result
//     carries .aoreplay-result.json listing its entries; an older result without it qualifies when
//     its main file (report.json, sweep.json, capture.json) is aoreplay's and every entry is one
//     its command writes. Anything else is refused (InputError, exit 2) before any work, naming
//     the first unexpected entry, and nothing is moved or deleted. --out may not be, lie inside or
//     hold an input of the run;
//   - one writer per output: an flock on .NAME.lock beside it, held from the constructor to the
//     destructor; a second run is refused at once, naming the holder's process id;
//   - the result is staged in .NAME.tmp-PID and swapped in with renameat2(RENAME_EXCHANGE), or,
//     where the file system lacks it, moved aside to .NAME.old-PID and renamed in. So NAME is at
//     every moment the complete old result or the complete new one; after a kill between the two
//     renames of the fallback, the next run on NAME puts the old one back. The next run also
//     removes the staging folders of dead runs (holding the lock, it knows they are dead).
// Files (--json, --dot) are written to a temporary file and renamed over the target.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/input_error.h"

namespace aor {

// What a result folder holds; each kind knows what its command writes (output_directory.cpp).
// What a result folder holds (each command's): decides which older results without the marker may
// be replaced. Kinds newer than the marker (ab, tune) are replaced only by what their marker lists.
enum class ResultKind { Run, Sweep, Capture, Ab, Tune };

class OutputDirectory {
 public:
  // Checks finalPath, takes the lock, finishes or undoes what killed runs left, and creates the
  // staging folder. `inputs` (files or folders the run reads) must neither be finalPath nor lie
  // inside it or hold it. Throws InputError (field --out).
  OutputDirectory(std::filesystem::path finalPath, ResultKind kind, const std::vector<std::filesystem::path>& inputs = {});
  ~OutputDirectory();  // removes the staging folder unless committed, then releases the lock
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  const std::filesystem::path& staging() const { return staging_; }
  const std::filesystem::path& finalPath() const { return final_; }
  // Writes the marker and swaps the staged result in for the previous one, which is then removed.
  // Throws InputError when something aoreplay did not write appeared in finalPath meanwhile (it
  // is kept; the new result is discarded).
  void commit();

  // For the termination handler: removes what an unfinished run leaves (staging, lock).
  void abandon();

 private:
  void recoverInterruptedRuns();
  void createStaging(const std::function<InputError(const std::string&)>& fail);
  void swapIn();
  bool exchangeIn(const std::function<InputError(const std::string&)>& appeared);
  std::filesystem::path moveAsideAndIn(const std::function<InputError(const std::string&)>& appeared);
  void releaseLock();

  std::filesystem::path final_, parent_;
  std::string name_;
  ResultKind kind_;
  std::filesystem::path staging_;
  std::filesystem::path lockPath_;
  int lockFd_ = -1;
  bool committed_ = false;
};

// One file output: `text` goes to a temporary file beside `path` (".NAME.tmp-PID"), renamed over
// `path` once complete, so `path` is either untouched or the whole new file. Missing parent
// folders are created. Refused (InputError naming `path`): an existing `path` that is not a
// regular file (folder, symbolic link, FIFO, device), and one that is one of `inputs`. "-" writes
// to standard output. Temporary files of dead processes beside `path` are removed.
void writeFileAtomically(const std::filesystem::path& path, const std::string& text,
                         const std::vector<std::filesystem::path>& inputs = {});

// A private folder for a command's scratch files ("PREFIX-XXXXXX" in the temporary directory),
// removed with everything in it when the object goes, and by the termination handler below when
// a signal ends the process first (an interrupted `import renderdoc` left its folder behind).
class ScratchFolder {
 public:
  explicit ScratchFolder(const std::string& prefix);
  ~ScratchFolder();
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// Call first in main(), before any thread starts: SIGINT, SIGTERM and SIGHUP are then handled on a
// thread of their own, which removes the staging folders, locks and temporary files of the outputs
// in progress and the scratch folders (a commit under way finishes first) and then ends the process
// by the same signal.
void cleanUpOutputsOnTermination();
// While `pid` (> 0) does the command's work in a child process that holds the outputs (counted
// cost's valgrind child), those signals are passed on to it instead, and this process goes on
// until it has waited for the child; 0 ends the forwarding.
void forwardTerminationSignalsTo(int pid);

}  // namespace aor
