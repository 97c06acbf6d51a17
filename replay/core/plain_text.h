#pragma once
// One rule for text that comes in (command-line values, names and docs in files) and goes out to a
// terminal, to XML and HTML, or into generated GLSL: control characters are refused where the
// text comes in when nothing legitimate holds them (a command-line value, a parameter's doc, a
// pass name), and escaped on the way out everywhere else, so no input adds a line to a shader,
// moves the terminal's cursor or makes XML invalid.
#include <optional>
#include <string>
#include <string_view>

namespace aor {

// The first control character (C0 with tab and newline, DEL, C1) as "\x0a at byte 3"; nullopt when none.
std::optional<std::string> controlCharacterIn(std::string_view text);

// `text`, read from `file`'s `field`; InputError when it holds a control character.
std::string withoutControlCharacters(std::string text, const std::string& file, const std::string& field);

// `text` with each control character's bytes turned into spaces (one line that moves no cursor:
// InputError's messages).
std::string controlCharactersBlanked(std::string text);

// `text` with every control character, and every byte that is not part of valid UTF-8, written as
// \xNN. `keepLines`: newline and tab are kept (text bound for XML, where they are valid).
std::string printable(std::string_view text, bool keepLines = false);

}  // namespace aor
