#include "capture/library.h"

#include <algorithm>
#include <filesystem>

#include "core/input_error.h"

namespace aor {

namespace fs = std::filesystem;

bool isCaptureLibrary(const std::string& argument) {
  std::error_code ec;
  return fs::is_directory(argument, ec) && !fs::exists(fs::path(argument) / "capture.json", ec);
}

std::vector<std::string> captureFoldersOf(const std::vector<std::string>& arguments) {
  std::vector<std::string> folders;
  for (const auto& argument : arguments) {
    std::error_code ec;
    if (!isCaptureLibrary(argument)) {
      folders.push_back(argument);  // a capture, or what loadCapture will name as missing
      continue;
    }
    std::vector<std::string> library;
    for (const auto& entry : fs::directory_iterator(argument, ec))
      if (fs::exists(entry.path() / "capture.json", ec)) library.push_back(entry.path().string());
    if (library.empty())
      throw InputError(argument, std::nullopt, "", "holds neither capture.json nor capture folders (a library's are its subfolders)");
    std::sort(library.begin(), library.end());
    folders.insert(folders.end(), library.begin(), library.end());
  }
  return folders;
}

}  // namespace aor
