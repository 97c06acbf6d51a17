#include "report/output_directory.h"

#include <unistd.h>

#include <fmt/format.h>

namespace aor {

namespace fs = std::filesystem;

OutputDirectory::OutputDirectory(fs::path finalPath) : final_(fs::absolute(std::move(finalPath)).lexically_normal()) {
  if (final_.filename().empty()) final_ = final_.parent_path();
  staging_ = final_.parent_path() / fmt::format(".{}.tmp-{}", final_.filename().string(), getpid());
  fs::remove_all(staging_);
  fs::create_directories(staging_);
}

OutputDirectory::~OutputDirectory() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
}

void OutputDirectory::commit() {
  fs::remove_all(final_);
  fs::rename(staging_, final_);
  committed_ = true;
}

}  // namespace aor
