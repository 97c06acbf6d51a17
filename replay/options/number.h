#pragma once
// Whole numbers and decimals given on a command line, checked strictly: the whole text must be
// the number (no sign other than '-', no spaces, nothing after it) and it must lie in [min, max].
// Anything else throws InputError naming `option` and the text, so a typo exits 2 with a message
// instead of std::stoi's "stoi" (or a silent prefix: stoi("12abc") is 12).
#include <string>
#include <string_view>

namespace aor {

int parseInt(std::string_view text, const std::string& option, int min, int max);
long long parseLong(std::string_view text, const std::string& option, long long min, long long max);
double parseNumber(std::string_view text, const std::string& option, double min, double max);

}  // namespace aor
