#pragma once
// --frames A:B, half-open, either end optional ("3:", ":4"), against a capture's frames.
#include <string>
#include <utility>

#include "capture/capture.h"

namespace aor {

// [A, B) within the capture's frames; empty text: all of them. Throws InputError (--frames).
std::pair<int, int> frameRange(const Capture& capture, const std::string& frames);

}  // namespace aor
