#pragma once
// A library of captures (captures/library.sh writes one): a folder whose subfolders are captures.
// `tune` and `sweep` take one wherever they take captures.
#include <string>
#include <vector>

namespace aor {

// The capture folders the arguments name: a folder holding capture.json is one; a folder without
// one is a library, every subfolder holding capture.json in name order (none: InputError naming
// it). Anything else is passed on for loadCapture to name.
std::vector<std::string> captureFoldersOf(const std::vector<std::string>& arguments);
// Whether `argument` is a library (a folder without capture.json).
bool isCaptureLibrary(const std::string& argument);

}  // namespace aor
