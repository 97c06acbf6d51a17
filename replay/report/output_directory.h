#pragma once
// Outputs are written under a temporary sibling folder and renamed into place only when the run
// succeeded, so a failed run never leaves anything that looks like a valid result.
#include <filesystem>
#include <string>

namespace aor {

class OutputDirectory {
 public:
  // `marker` is the file every earlier result of the same kind holds (report.json, sweep.json).
  // Committing replaces finalPath, i.e. deletes it: so an existing finalPath must be an empty
  // folder or one holding `marker`, which is checked here, before any work. Throws InputError
  // (field --out) otherwise, or when the staging folder cannot be created.
  OutputDirectory(std::filesystem::path finalPath, const std::string& marker);
  ~OutputDirectory();  // removes the staging folder unless committed
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  const std::filesystem::path& staging() const { return staging_; }
  const std::filesystem::path& finalPath() const { return final_; }
  // Replaces the previous result at finalPath, if any, with the staged one.
  void commit();

 private:
  std::filesystem::path final_;
  std::filesystem::path staging_;
  bool committed_ = false;
};

// The same for one file: missing parent folders are created, `text` goes to a temporary file
// beside `path` (".NAME.tmp-PID") and that is renamed over `path` once complete, so `path` is
// either untouched or the whole new file. Throws InputError naming `path` when it cannot be
// written (it names a folder, a parent is a regular file, ...); the temporary file never stays.
void writeFileAtomically(const std::filesystem::path& path, const std::string& text);

}  // namespace aor
