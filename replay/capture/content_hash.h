#pragma once
// A capture's identity for the results store (aoreplay record): the SHA-256 of its content, so a
// capture copied to another machine or folder keeps its series, and an edited one gets a new one.
#include <string>

#include "capture/capture.h"

namespace aor {

// Lower-case hex SHA-256 over capture.json and every distinct file its frames name (G-buffers and
// references) and its geometry, in path order, each as its path relative to the capture folder, its size and its
// bytes. Throws std::runtime_error naming a file that cannot be read.
std::string captureContentSha256(const Capture& capture);

}  // namespace aor
