#pragma once

namespace aor {

// The version this aoreplay reports (report.json's tool_version, result markers).
const char* aoreplayVersion();

}  // namespace aor
