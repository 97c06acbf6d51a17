#pragma once
// Command-line values shared by `aoreplay` and `ao_bench`, which is why they live in a library
// and not in replay/cli/ (the executable's sources).
#include <string>
#include <string_view>
#include <utility>

namespace aor {

// "WxH" -> {W, H}, both positive and within int; nothing may follow H. The accepted set is what
// `aoreplay capture --size` always took (sscanf "%d%c%d%c"): lower-case 'x' right after W, and
// white space or a '+' may precede each number. Anything else ("640x360x9", "640x", "x360",
// "0x10", "-1x5", "640X360", "640 x360", "640x360 ") throws InputError naming `option` and `text`.
std::pair<int, int> parseSize(std::string_view text, const std::string& option);

}  // namespace aor
