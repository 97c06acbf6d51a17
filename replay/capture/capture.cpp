#include "capture/capture.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "capture/exr_detail.h"
#include "capture/image_io.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace aor {
namespace {

using detail::ExrChannelKind;
using detail::ExrHeaderDetail;
using detail::kMaxImagePixels;
using detail::kMaxImageSide;

constexpr const char* kFormatName = "aoreplay-capture";
constexpr int kFormatVersion = 1;

const std::vector<std::string> kTopLevelFields = {"format", "version", "width", "height", "frames", "scene"};
const std::vector<std::string> kFrameFields = {"gbuffer", "view", "projection", "reference", "cut"};
const std::vector<std::string> kNormalChannels = {"normal.X", "normal.Y", "normal.Z"};
const std::vector<std::string> kGBufferChannels = {"depth", "depth2", "normal.X", "normal.Y", "normal.Z"};

// Where a problem is: the file as the user spelled it, and the frame when there is one.
struct Where {
  std::string file;
  std::optional<int> frame;
};

[[noreturn]] void fail(const Where& w, const std::string& field, const std::string& problem) {
  throw InputError(w.file, w.frame, field, problem);
}

std::string join(const std::vector<std::string>& items, const char* sep = ", ") {
  std::string s;
  for (const auto& item : items) {
    if (!s.empty()) s += sep;
    s += item;
  }
  return s;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string quoteJson(const std::string& s) {
  return json(s).dump(-1, ' ', false, json::error_handler_t::replace);
}

// Short description of a JSON value for "expected X, got Y" messages.
std::string describe(const json& v) {
  switch (v.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case json::value_t::string: {
      std::string s = v.get<std::string>();
      if (s.size() > 40) s = s.substr(0, 37) + "...";
      return "string " + quoteJson(s);
    }
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float: return "number " + v.dump();
    case json::value_t::array: return fmt::format("an array of {} elements", v.size());
    case json::value_t::object: return "an object";
    default: return v.type_name();
  }
}

size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

void checkKnownFields(const json& obj, const std::vector<std::string>& known, const Where& w, const char* where) {
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    const std::string& key = it.key();
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    std::string msg = "unknown field";
    std::string best;
    size_t bestDistance = 3;
    for (const auto& k : known) {
      const size_t d = lower(k) == lower(key) ? 0 : editDistance(key, k);
      if (d < bestDistance) {
        bestDistance = d;
        best = k;
      }
    }
    if (!best.empty()) msg += fmt::format(" (did you mean \"{}\"?)", best);
    msg += fmt::format("; the fields {} are: {}", where, join(known));
    fail(w, key, msg);
  }
}

// ---- JSON fields ---------------------------------------------------------------------------------

std::int64_t positiveInt(const json& obj, const char* key, const Where& w) {
  auto it = obj.find(key);
  if (it == obj.end()) fail(w, key, "missing; expected a positive integer");
  if (!it->is_number_integer()) fail(w, key, "expected a positive integer, got " + describe(*it));
  std::int64_t v = 0;
  if (it->is_number_unsigned()) {
    const auto u = it->get<std::uint64_t>();
    v = u > std::uint64_t(std::numeric_limits<std::int64_t>::max()) ? std::numeric_limits<std::int64_t>::max()
                                                                    : static_cast<std::int64_t>(u);
  } else {
    v = it->get<std::int64_t>();
  }
  if (v <= 0) fail(w, key, fmt::format("expected a positive integer, got {}", v));
  return v;
}

glm::mat4 parseMatrix(const json& frame, const char* key, const Where& w) {
  auto it = frame.find(key);
  if (it == frame.end()) fail(w, key, "missing; expected 16 numbers (a 4x4 matrix, column-major)");
  if (!it->is_array()) fail(w, key, "expected an array of 16 numbers, got " + describe(*it));
  if (it->size() != 16) fail(w, key, fmt::format("expected 16 numbers, got {}", it->size()));
  glm::mat4 m(1.0f);
  for (int i = 0; i < 16; ++i) {
    const json& e = (*it)[static_cast<size_t>(i)];
    if (!e.is_number()) fail(w, key, fmt::format("element {} is not a number: got {}", i, describe(e)));
    const double d = e.get<double>();
    if (!std::isfinite(d)) fail(w, key, fmt::format("element {} is not finite", i));
    const float f = static_cast<float>(d);
    if (!std::isfinite(f)) fail(w, key, fmt::format("element {} ({}) is not finite as a 32-bit float", i, e.dump()));
    m[i / 4][i % 4] = f;
  }
  return m;
}

void checkView(const glm::mat4& view, const Where& w) {
  const glm::dmat4 d(view);
  // |det| relative to the product of column lengths (Hadamard's bound) is 1 for any rotation and
  // independent of the units of the translation.
  double scale = 1.0;
  for (int c = 0; c < 4; ++c) scale *= glm::length(d[c]);
  const double det = glm::determinant(d);
  if (!(scale > 0.0) || !std::isfinite(det) || !(std::abs(det) > 1e-12 * scale))
    fail(w, "view", fmt::format("view is singular (not invertible): determinant {:g}", det));
  const glm::dmat4 inv = glm::inverse(d);
  const glm::mat4 invf = glm::inverse(view);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(inv[c][r]) || !std::isfinite(invf[c][r]))
        fail(w, "view", "view is singular (its inverse is not finite)");
}

void checkProjection(const glm::mat4& p, const Where& w) {
  const auto notPerspective = [&](int c, int r, const char* must, const char* hint = "") {
    fail(w, "projection",
         fmt::format("projection is not a perspective projection (P[{}][{}] must be {}, got {}; P[column][row], "
                     "element {} of the array){}",
                     c, r, must, p[c][r], c * 4 + r, hint));
  };
  if (p[2][3] != -1.0f) {
    const char* hint = "";
    if (p[2][3] == 0.0f && p[3][3] == 1.0f) hint = "; orthographic projections are not supported";
    if (p[2][3] == 1.0f) hint = "; left-handed projections (camera looking down +Z) are not supported";
    notPerspective(2, 3, "-1", hint);
  }
  if (p[3][3] != 0.0f) notPerspective(3, 3, "0");
  static const int zeros[][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 0}, {1, 2}, {1, 3}, {3, 0}, {3, 1}};
  for (const auto& z : zeros)
    if (p[z[0]][z[1]] != 0.0f) notPerspective(z[0], z[1], "0");
  static const int nonZeros[][2] = {{0, 0}, {1, 1}, {3, 2}};
  for (const auto& z : nonZeros)
    if (p[z[0]][z[1]] == 0.0f)
      fail(w, "projection",
           fmt::format("projection is singular (P[{}][{}], element {} of the array, is 0)", z[0], z[1],
                       z[0] * 4 + z[1]));
}

// Lexical checks of a path written in capture.json. Returns it normalised.
fs::path relativePath(const json& value, const char* key, const Where& w) {
  if (!value.is_string()) fail(w, key, "expected a string (a path relative to the capture folder), got " + describe(value));
  const std::string text = value.get<std::string>();
  if (text.empty()) fail(w, key, "path is empty");
  if (text.find('\\') != std::string::npos)
    fail(w, key, fmt::format("path {} contains a backslash; write paths with forward slashes", quoteJson(text)));
  if (text.find('\0') != std::string::npos) fail(w, key, "path contains a NUL character");
  const fs::path p(text);
  if (p.is_absolute() || p.has_root_path())
    fail(w, key, fmt::format("absolute path {} is not allowed; paths are relative to the capture folder", quoteJson(text)));
  const fs::path n = p.lexically_normal();
  if (!n.empty() && *n.begin() == "..")
    fail(w, key, fmt::format("path {} leaves the capture folder", quoteJson(text)));
  if (n.empty() || n == "." || !n.has_filename()) fail(w, key, fmt::format("path {} does not name a file", quoteJson(text)));
  return n;
}

// Per-frame data gathered from capture.json before any EXR is opened.
struct FrameEntry {
  fs::path gbuffer;
  std::optional<fs::path> reference;
  std::string gbufferText, referenceText;
};

// Filesystem checks of a path that passed relativePath: it must not resolve outside the folder
// (symbolic links) and must be an existing file. Returns the absolute path.
fs::path resolveInFolder(const fs::path& folderAbs, const fs::path& folderCanonical, const fs::path& rel,
                         const std::string& text, const std::string& display, const char* key, const Where& w) {
  const fs::path abs = folderAbs / rel;
  std::error_code ec;
  const fs::path canon = fs::weakly_canonical(abs, ec);
  if (ec) fail(w, key, fmt::format("cannot resolve {}: {}", quoteJson(text), ec.message()));
  const fs::path inside = canon.lexically_relative(folderCanonical);
  if (inside.empty() || inside == "." || *inside.begin() == "..")
    fail(w, key,
         fmt::format("{} resolves to {}, outside the capture folder (through a symbolic link)", quoteJson(text),
                     canon.string()));
  const auto st = fs::status(abs, ec);
  if (ec || !fs::exists(st)) fail(w, key, fmt::format("file {} does not exist (looked for {})", quoteJson(text), display));
  if (!fs::is_regular_file(st)) fail(w, key, fmt::format("{} is not a file ({})", quoteJson(text), display));
  return abs;
}

// A channel that is not one of ours but starts like one ("normal.x", "Depth", "visibilty") is
// almost certainly a misspelling that would otherwise be silently ignored. Other channels
// (e.g. "albedo.R") are ignored.
void checkMisspelledChannels(const ExrHeaderDetail& h, const std::vector<std::string>& known,
                             const std::vector<std::string>& prefixes, const Where& w) {
  for (const auto& [name, kind] : h.channels) {
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    const std::string l = lower(name);
    for (const auto& prefix : prefixes)
      if (l.rfind(prefix, 0) == 0)
        fail(w, name,
             fmt::format("unknown channel (misspelt?); the channels of this file are {} (case-sensitive)",
                         join(known)));
  }
}

void checkSize(const ExrHeaderDetail& h, int width, int height, const Where& w) {
  if (h.width != width || h.height != height)
    fail(w, "", fmt::format("image is {}x{} but capture.json says {}x{}", h.width, h.height, width, height));
}

void checkFloatChannel(ExrChannelKind kind, const std::string& name, const Where& w) {
  if (kind != ExrChannelKind::Float) fail(w, name, fmt::format("has type {}, expected FLOAT", detail::kindName(kind)));
}

// The FLOAT channel `name` that a `what` (G-buffer, reference) cannot do without.
void requireFloatChannel(const ExrHeaderDetail& h, const std::string& name, const char* what, const Where& w) {
  auto it = h.channels.find(name);
  if (it == h.channels.end())
    fail(w, name,
         fmt::format("missing; a {} needs a FLOAT channel named {} (channels present: {})", what, name,
                     detail::channelList(h)));
  checkFloatChannel(it->second, name, w);
}

struct Layout {
  bool normals = false;
  bool depth2 = false;
};

Layout checkGBufferHeader(const ExrHeaderDetail& h, int width, int height, const Where& w) {
  checkSize(h, width, height, w);
  requireFloatChannel(h, "depth", "G-buffer", w);
  std::vector<std::string> present, missing;
  for (const auto& n : kNormalChannels) (h.channels.count(n) ? present : missing).push_back(n);
  if (!present.empty() && !missing.empty())
    fail(w, missing.front(),
         fmt::format("missing, but {} {} present; normals need all of normal.X, normal.Y, normal.Z or none",
                     join(present, " and "), present.size() == 1 ? "is" : "are"));
  for (const auto& n : present)
    if (h.channels.at(n) == ExrChannelKind::Uint) fail(w, n, "has type UINT, expected HALF or FLOAT");
  Layout layout;
  layout.normals = !present.empty();
  auto depth2 = h.channels.find("depth2");
  if (depth2 != h.channels.end()) {
    checkFloatChannel(depth2->second, "depth2", w);
    layout.depth2 = true;
  }
  checkMisspelledChannels(h, kGBufferChannels, {"depth", "normal"}, w);
  return layout;
}

void checkReferenceHeader(const ExrHeaderDetail& h, int width, int height, const Where& w) {
  checkSize(h, width, height, w);
  requireFloatChannel(h, "visibility", "reference", w);
  checkMisspelledChannels(h, {"visibility"}, {"visib"}, w);
}

json parseCaptureJson(const std::string& text, const Where& w) {
  // nlohmann keeps the last of duplicate keys silently; a parser callback catches them.
  std::vector<std::set<std::string>> open;
  std::optional<std::string> duplicate;
  const json::parser_callback_t callback = [&](int, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::object_start) {
      open.emplace_back();
    } else if (event == json::parse_event_t::object_end) {
      if (!open.empty()) open.pop_back();
    } else if (event == json::parse_event_t::key && !open.empty() && parsed.is_string()) {
      if (!open.back().insert(parsed.get<std::string>()).second && !duplicate) duplicate = parsed.get<std::string>();
    }
    return true;
  };
  json root;
  try {
    root = json::parse(text, callback);
  } catch (const json::exception& e) {
    std::string what = e.what();
    // Drop nlohmann's "[json.exception.parse_error.101] " tag, keep "parse error at line L, column C: ...".
    if (!what.empty() && what.front() == '[') {
      const auto close = what.find("] ");
      if (close != std::string::npos) what = what.substr(close + 2);
    }
    // A number too large for a double (1e999) is reported without a position; find the token.
    if (e.id == 406) {
      const auto q1 = what.find('\'');
      const auto q2 = what.rfind('\'');
      if (q1 != std::string::npos && q2 > q1 + 1) {
        const auto at = text.find(what.substr(q1 + 1, q2 - q1 - 1));
        if (at != std::string::npos) {
          const auto lineStart = text.rfind('\n', at);
          const size_t line = 1 + static_cast<size_t>(std::count(text.begin(), text.begin() + at, '\n'));
          const size_t column = at - (lineStart == std::string::npos ? 0 : lineStart + 1) + 1;
          what = fmt::format("at line {}, column {}: {} (numbers must be finite)", line, column, what);
        }
      }
    }
    fail(w, "", "malformed JSON: " + what);
  }
  if (duplicate) fail(w, *duplicate, "appears twice in the same object");
  return root;
}

std::string readTextFile(const fs::path& path, const Where& w) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(w, "", "cannot open: " + std::string(std::strerror(errno)));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) fail(w, "", "cannot read: " + std::string(std::strerror(errno)));
  return ss.str();
}

fs::path absoluteFolder(const fs::path& folder) {
  fs::path p = fs::absolute(folder).lexically_normal();
  if (!p.has_filename() && p.has_relative_path()) p = p.parent_path();  // trailing slash
  return p;
}

}  // namespace

// ---- loading ---------------------------------------------------------------------------------------

Capture loadCapture(const fs::path& folder) {
  if (folder.empty()) throw InputError("", std::nullopt, "", "no capture folder given (the path is empty)");
  const std::string folderDisplay = folder.string();
  {
    std::error_code ec;
    const auto st = fs::status(folder, ec);
    if (ec || !fs::exists(st)) throw InputError(folderDisplay, std::nullopt, "", "capture folder does not exist");
    if (!fs::is_directory(st))
      throw InputError(folderDisplay, std::nullopt, "", "is not a folder; a capture is a folder holding capture.json");
  }
  const fs::path jsonPath = folder / "capture.json";
  const Where top{(folder / "capture.json").lexically_normal().string(), std::nullopt};
  {
    std::error_code ec;
    const auto st = fs::status(jsonPath, ec);
    if (ec || !fs::exists(st)) fail(top, "", "file does not exist; a capture folder must contain capture.json");
    if (!fs::is_regular_file(st)) fail(top, "", "is not a regular file");
  }
  const json root = parseCaptureJson(readTextFile(jsonPath, top), top);
  if (!root.is_object()) fail(top, "", "the top level must be a JSON object, got " + describe(root));

  // format and version first: a file of another format or version gets that message, not a
  // complaint about fields it does not know.
  auto format = root.find("format");
  if (format == root.end()) fail(top, "format", fmt::format("missing; expected \"{}\"", kFormatName));
  if (!format->is_string() || format->get<std::string>() != kFormatName)
    fail(top, "format", fmt::format("expected \"{}\", got {}", kFormatName, describe(*format)));
  auto version = root.find("version");
  if (version == root.end()) fail(top, "version", fmt::format("missing; supported versions: {}", kFormatVersion));
  if (!version->is_number_integer())
    fail(top, "version",
         fmt::format("expected an integer, got {}; supported versions: {}", describe(*version), kFormatVersion));
  if (version->is_number_unsigned() ? version->get<std::uint64_t>() != std::uint64_t(kFormatVersion)
                                    : version->get<std::int64_t>() != kFormatVersion)
    fail(top, "version",
         fmt::format("version {} is not supported; supported versions: {}", version->dump(), kFormatVersion));
  checkKnownFields(root, kTopLevelFields, top, "of capture.json");

  const std::int64_t width = positiveInt(root, "width", top);
  const std::int64_t height = positiveInt(root, "height", top);
  if (width > kMaxImageSide)
    fail(top, "width", fmt::format("{} exceeds the limit of {} pixels per side", width, kMaxImageSide));
  if (height > kMaxImageSide)
    fail(top, "height", fmt::format("{} exceeds the limit of {} pixels per side", height, kMaxImageSide));
  if (width * height > kMaxImagePixels)
    fail(top, "height",
         fmt::format("{}x{} = {} pixels exceeds the limit of {} pixels (16384*16384/4)", width, height, width * height,
                     kMaxImagePixels));

  Capture capture;
  capture.width = static_cast<int>(width);
  capture.height = static_cast<int>(height);
  capture.folder = absoluteFolder(folder);
  capture.name = capture.folder.filename().string();

  if (auto scene = root.find("scene"); scene != root.end()) {
    if (!scene->is_object()) fail(top, "scene", "expected an object, got " + describe(*scene));
    capture.scene = *scene;
  }

  auto framesIt = root.find("frames");
  if (framesIt == root.end()) fail(top, "frames", "missing; expected an array of frame objects");
  if (!framesIt->is_array()) fail(top, "frames", "expected an array of frame objects, got " + describe(*framesIt));
  if (framesIt->empty()) fail(top, "frames", "the array is empty; a capture needs at least one frame");
  if (framesIt->size() > static_cast<size_t>(std::numeric_limits<int>::max()))
    fail(top, "frames", "too many frames");

  // Pass 1: everything in capture.json, so typos are reported before any EXR is opened.
  std::vector<FrameEntry> entries;
  for (size_t i = 0; i < framesIt->size(); ++i) {
    const json& f = (*framesIt)[i];
    const Where w{top.file, static_cast<int>(i)};
    if (!f.is_object()) fail(w, "frames", "expected a frame object, got " + describe(f));
    checkKnownFields(f, kFrameFields, w, "of a frame");
    FrameEntry entry;
    auto gbuffer = f.find("gbuffer");
    if (gbuffer == f.end()) fail(w, "gbuffer", "missing; expected the path of the frame's G-buffer EXR");
    entry.gbuffer = relativePath(*gbuffer, "gbuffer", w);
    entry.gbufferText = gbuffer->get<std::string>();
    if (auto ref = f.find("reference"); ref != f.end()) {
      entry.reference = relativePath(*ref, "reference", w);
      entry.referenceText = ref->get<std::string>();
    }
    CaptureFrame frame;
    if (auto cut = f.find("cut"); cut != f.end()) {
      if (!cut->is_boolean()) fail(w, "cut", "expected true or false, got " + describe(*cut));
      frame.cut = cut->get<bool>();
    }
    frame.view = parseMatrix(f, "view", w);
    frame.projection = parseMatrix(f, "projection", w);
    checkView(frame.view, w);
    checkProjection(frame.projection, w);
    capture.frames.push_back(frame);
    entries.push_back(std::move(entry));
  }

  // Pass 2: files. Paths stay inside the folder, every EXR header is checked, and the channel
  // layout of frame 0 must hold for every frame.
  std::error_code ec;
  const fs::path folderCanonical = fs::canonical(capture.folder, ec);
  if (ec) throw InputError(folderDisplay, std::nullopt, "", "cannot resolve the capture folder: " + ec.message());
  Layout first;
  for (size_t i = 0; i < entries.size(); ++i) {
    const int index = static_cast<int>(i);
    const Where w{top.file, index};
    CaptureFrame& frame = capture.frames[i];
    const FrameEntry& entry = entries[i];

    const std::string gDisplay = (folder / entry.gbuffer).lexically_normal().string();
    frame.gbuffer =
        resolveInFolder(capture.folder, folderCanonical, entry.gbuffer, entry.gbufferText, gDisplay, "gbuffer", w);
    const Where gw{gDisplay, index};
    const Layout layout = checkGBufferHeader(detail::readExrHeaderDetail(frame.gbuffer, gDisplay, index),
                                             capture.width, capture.height, gw);
    if (i == 0) {
      first = layout;
    } else {
      if (layout.normals != first.normals)
        fail(gw, "normal.X",
             fmt::format("frame {} {}; every frame must have the same channels", index,
                         layout.normals ? "has normals but frame 0 has none"
                                        : "has no normals (normal.X, normal.Y, normal.Z) but frame 0 has them"));
      if (layout.depth2 != first.depth2)
        fail(gw, "depth2",
             fmt::format("frame {} {}; every frame must have the same channels", index,
                         layout.depth2 ? "has a depth2 channel but frame 0 has none"
                                       : "has no depth2 channel but frame 0 has one"));
    }

    if (entry.reference) {
      const std::string rDisplay = (folder / *entry.reference).lexically_normal().string();
      frame.reference = resolveInFolder(capture.folder, folderCanonical, *entry.reference, entry.referenceText,
                                        rDisplay, "reference", w);
      checkReferenceHeader(detail::readExrHeaderDetail(*frame.reference, rDisplay, index), capture.width,
                           capture.height, Where{rDisplay, index});
    }
  }
  capture.hasNormals = first.normals;
  capture.hasDepth2 = first.depth2;
  return capture;
}

namespace {
const CaptureFrame& frameAt(const Capture& capture, int frame, const char* function) {
  if (frame < 0 || static_cast<size_t>(frame) >= capture.frames.size())
    throw std::out_of_range(
        fmt::format("{}: frame {} out of range (capture has {} frames)", function, frame, capture.frames.size()));
  return capture.frames[static_cast<size_t>(frame)];
}
}  // namespace

GBuffer loadGBuffer(const Capture& capture, int frame) {
  const CaptureFrame& f = frameAt(capture, frame, "loadGBuffer");
  std::vector<std::string> names = {"depth"};
  if (capture.hasNormals) names.insert(names.end(), kNormalChannels.begin(), kNormalChannels.end());
  if (capture.hasDepth2) names.push_back("depth2");
  auto planes = detail::readExrChannelsDetail(f.gbuffer, detail::displayPath(f.gbuffer), frame, names, capture.width,
                                              capture.height);
  GBuffer g;
  g.width = capture.width;
  g.height = capture.height;
  g.depth = std::move(planes.at("depth"));
  if (capture.hasNormals) {
    const auto& x = planes.at("normal.X");
    const auto& y = planes.at("normal.Y");
    const auto& z = planes.at("normal.Z");
    g.normals.resize(x.size() * 3);
    for (size_t i = 0; i < x.size(); ++i) {
      g.normals[3 * i + 0] = x[i];
      g.normals[3 * i + 1] = y[i];
      g.normals[3 * i + 2] = z[i];
    }
  }
  if (capture.hasDepth2) g.depth2 = std::move(planes.at("depth2"));
  return g;
}

std::optional<std::vector<float>> loadReference(const Capture& capture, int frame) {
  const CaptureFrame& f = frameAt(capture, frame, "loadReference");
  if (!f.reference) return std::nullopt;
  auto planes = detail::readExrChannelsDetail(*f.reference, detail::displayPath(*f.reference), frame, {"visibility"},
                                              capture.width, capture.height);
  return std::move(planes.at("visibility"));
}

// ---- writing ---------------------------------------------------------------------------------------

namespace {

nlohmann::ordered_json matrixJson(const glm::mat4& m) {
  auto a = nlohmann::ordered_json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) a.push_back(static_cast<double>(m[c][r]));  // exact; dumps round-trip
  return a;
}

void validateForWrite(int width, int height, const std::vector<CaptureFrameData>& frames, const json& scene) {
  const auto bad = [](const std::string& what) { throw std::invalid_argument("writeCapture: " + what); };
  if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide ||
      std::int64_t(width) * height > kMaxImagePixels)
    bad(fmt::format("invalid size {}x{}", width, height));
  if (frames.empty()) bad("no frames");
  if (!scene.is_null() && !scene.is_object()) bad("scene must be an object");
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  for (size_t i = 0; i < frames.size(); ++i) {
    const auto& f = frames[i];
    const auto& g = f.gbuffer;
    if (g.width != width || g.height != height)
      bad(fmt::format("frame {}: G-buffer is {}x{}, capture is {}x{}", i, g.width, g.height, width, height));
    if (g.depth.size() != n) bad(fmt::format("frame {}: depth has {} values, expected {}", i, g.depth.size(), n));
    if (!g.normals.empty() && g.normals.size() != 3 * n)
      bad(fmt::format("frame {}: normals has {} values, expected {}", i, g.normals.size(), 3 * n));
    if (!g.depth2.empty() && g.depth2.size() != n)
      bad(fmt::format("frame {}: depth2 has {} values, expected {}", i, g.depth2.size(), n));
    if (g.normals.empty() != frames[0].gbuffer.normals.empty() || g.depth2.empty() != frames[0].gbuffer.depth2.empty())
      bad(fmt::format("frame {}: channel layout (normals, depth2) differs from frame 0", i));
    if (f.reference && f.reference->size() != n)
      bad(fmt::format("frame {}: reference has {} values, expected {}", i, f.reference->size(), n));
    try {
      const Where w{"writeCapture", static_cast<int>(i)};
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
          if (!std::isfinite(f.view[c][r]) || !std::isfinite(f.projection[c][r]))
            fail(w, "", "matrices must be finite");
      checkView(f.view, w);
      checkProjection(f.projection, w);
    } catch (const InputError& e) {
      throw std::invalid_argument(e.what());
    }
  }
}

void writeTextFile(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw InputError(path.string(), std::nullopt, "", "cannot create file: " + std::string(std::strerror(errno)));
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) throw InputError(path.string(), std::nullopt, "", "cannot write: " + std::string(std::strerror(errno)));
}

}  // namespace

void writeCapture(const fs::path& folder, int width, int height, const std::vector<CaptureFrameData>& frames,
                  const json& scene) {
  validateForWrite(width, height, frames, scene);
  fs::path target = folder.lexically_normal();
  if (!target.has_filename() && target.has_relative_path()) target = target.parent_path();
  if (target.empty() || target == "." || target == ".." || !target.has_filename())
    throw std::invalid_argument("writeCapture: invalid folder " + folder.string());
  const std::string display = target.string();

  std::error_code ec;
  const auto st = fs::symlink_status(target, ec);
  if (fs::exists(st)) {
    if (!fs::is_directory(st)) throw InputError(display, std::nullopt, "", "exists and is not a folder; not replacing it");
    // Replacing means deleting: only ever delete an earlier capture (or an empty folder).
    if (!fs::exists(target / "capture.json") && !fs::is_empty(target, ec))
      throw InputError(display, std::nullopt, "", "exists, is not empty and holds no capture.json; not replacing it");
  }
  if (target.has_parent_path()) {
    fs::create_directories(target.parent_path(), ec);
    if (ec) throw InputError(display, std::nullopt, "", "cannot create the parent folder: " + ec.message());
  }
  fs::path tmp = target;
  tmp += fmt::format(".tmp-{}", static_cast<long>(::getpid()));
  fs::remove_all(tmp, ec);
  try {
    fs::create_directories(tmp / "frames", ec);
    if (ec) throw InputError(tmp.string(), std::nullopt, "", "cannot create folder: " + ec.message());

    nlohmann::ordered_json doc;
    doc["format"] = kFormatName;
    doc["version"] = kFormatVersion;
    doc["width"] = width;
    doc["height"] = height;
    auto list = nlohmann::ordered_json::array();
    for (size_t i = 0; i < frames.size(); ++i) {
      const CaptureFrameData& f = frames[i];
      const GBuffer& g = f.gbuffer;
      const std::string gName = fmt::format("frames/{:04}.exr", i);
      std::vector<ExrChannel> channels = {{"depth", ExrPixelType::Float, g.depth.data()}};
      std::vector<float> nx, ny, nz;
      if (!g.normals.empty()) {
        const size_t n = g.depth.size();
        nx.resize(n), ny.resize(n), nz.resize(n);
        for (size_t p = 0; p < n; ++p) {
          nx[p] = g.normals[3 * p + 0];
          ny[p] = g.normals[3 * p + 1];
          nz[p] = g.normals[3 * p + 2];
        }
        channels.push_back({"normal.X", ExrPixelType::Half, nx.data()});
        channels.push_back({"normal.Y", ExrPixelType::Half, ny.data()});
        channels.push_back({"normal.Z", ExrPixelType::Half, nz.data()});
      }
      if (!g.depth2.empty()) channels.push_back({"depth2", ExrPixelType::Float, g.depth2.data()});
      writeExr(tmp / gName, width, height, channels);

      nlohmann::ordered_json entry;
      entry["gbuffer"] = gName;
      entry["view"] = matrixJson(f.view);
      entry["projection"] = matrixJson(f.projection);
      if (f.reference) {
        const std::string rName = fmt::format("frames/{:04}.ref.exr", i);
        writeExr(tmp / rName, width, height, {{"visibility", ExrPixelType::Float, f.reference->data()}});
        entry["reference"] = rName;
      }
      if (f.cut) entry["cut"] = true;
      list.push_back(std::move(entry));
    }
    doc["frames"] = std::move(list);
    // nlohmann::json objects are sorted by key, so this is deterministic too.
    doc["scene"] = nlohmann::ordered_json::parse(scene.is_null() ? std::string("{}") : scene.dump());
    writeTextFile(tmp / "capture.json", doc.dump(2) + "\n");

    if (fs::exists(fs::symlink_status(target, ec))) {
      fs::remove_all(target, ec);
      if (ec) throw InputError(display, std::nullopt, "", "cannot remove the previous capture: " + ec.message());
    }
    fs::rename(tmp, target, ec);
    if (ec) throw InputError(display, std::nullopt, "", "cannot move the new capture into place: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(tmp, ignored);
    throw;
  }
}

}  // namespace aor
