#include "report/output_directory.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include <fmt/format.h>

#include "capture/input_error.h"

namespace aor {

namespace fs = std::filesystem;

namespace {

// Where a result for `path` is written before it is renamed into place: a hidden sibling, named
// after this process so two runs never share one.
fs::path stagingSibling(const fs::path& path) {
  return path.parent_path() / fmt::format(".{}.tmp-{}", path.filename().string(), getpid());
}

}  // namespace

OutputDirectory::OutputDirectory(fs::path finalPath, const std::string& marker)
    : final_(fs::absolute(std::move(finalPath)).lexically_normal()) {
  if (final_.filename().empty()) final_ = final_.parent_path();
  auto fail = [&](const std::string& problem) { return InputError(final_.string(), std::nullopt, "--out", problem); };
  std::error_code ec;
  auto status = fs::symlink_status(final_, ec);
  if (fs::exists(status)) {
    if (fs::is_symlink(status)) throw fail("is a symbolic link; not replacing it");
    if (!fs::is_directory(status)) throw fail("exists and is not a folder; not replacing it");
    if (!fs::exists(final_ / marker) && !fs::is_empty(final_, ec))
      throw fail(fmt::format("exists, is not empty and holds no {} (not an earlier result); not replacing it", marker));
  }
  staging_ = stagingSibling(final_);
  fs::remove_all(staging_, ec);
  fs::create_directories(staging_, ec);
  if (ec) throw fail(fmt::format("cannot create {}: {}", staging_.string(), ec.message()));
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

void writeFileAtomically(const fs::path& path, const std::string& text) {
  auto fail = [&](const std::string& problem) { return InputError(path.string(), std::nullopt, "", problem); };
  std::error_code ec;
  if (!path.has_filename() || fs::is_directory(path, ec)) throw fail("names a folder, not a file");
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw fail(fmt::format("cannot create the folder {}: {}", path.parent_path().string(), ec.message()));
  }
  fs::path tmp = stagingSibling(path);
  try {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw fail(fmt::format("cannot create {}: {}", tmp.string(), std::strerror(errno)));
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) throw fail(fmt::format("cannot write {}: {}", tmp.string(), std::strerror(errno)));
    fs::rename(tmp, path, ec);
    if (ec) throw fail("cannot move the new file into place: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

}  // namespace aor
