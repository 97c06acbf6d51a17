#include "capture/capture.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <atomic>
#include <exception>
#include <map>
#include <set>
#include <thread>
#include <unordered_map>
#include <stdexcept>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "capture/exr_detail.h"
#include "capture/image_io.h"
#include "core/json_input.h"
#include "core/output_directory.h"

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
// Version 1.1 adds the optional top-level "geometry"; 1 stays valid, with exactly version 1's rules.
constexpr double kFormatVersionGeometry = 1.1;
constexpr const char* kSupportedVersions = "1, 1.1";
constexpr const char* kGeometryFile = "scene.obj";  // as writeCapture names it

const std::vector<std::string> kTopLevelFields = {"format", "version", "width", "height", "frames", "scene", "geometry"};
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

std::string quoteJson(const std::string& s) { return quoteForMessage(s); }

// Short description of a JSON value for "expected X, got Y" messages.
std::string describe(const json& v) {
  switch (v.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case json::value_t::string: return "string " + quoteForMessage(v.get_ref<const std::string&>(), 40);
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
      // The distance is at least the difference in length: a long key is not compared letter by letter.
      const size_t lengthGap = key.size() > k.size() ? key.size() - k.size() : k.size() - key.size();
      if (lengthGap >= bestDistance) continue;
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

// `d` as the 32-bit float it is used as, when that float is finite and zero only if `d` is: 1e39
// would become infinity, 1e-300 zero.
std::optional<float> asFloat(double d) {
  const float f = static_cast<float>(d);
  if (!std::isfinite(d) || !std::isfinite(f) || (f == 0.0f && d != 0.0)) return std::nullopt;
  return f;
}

// scene.ao_radius becomes the default `radius` setting (a float): it must be one the setting accepts.
void checkAoRadius(const json& scene, const Where& w) {
  auto it = scene.find("ao_radius");
  if (it == scene.end()) return;
  const char* field = "scene.ao_radius";
  if (!it->is_number()) fail(w, field, "expected a number (world units), got " + describe(*it));
  const double d = it->get<double>();
  const auto f = asFloat(d);
  if (!f) fail(w, field, fmt::format("{} is not representable as a 32-bit float", it->dump()));
  if (!(d >= kMinAoRadius && d <= kMaxAoRadius))
    fail(w, field, fmt::format("{} is outside {:g}..{:g}, the range of the radius setting", it->dump(), kMinAoRadius,
                               kMaxAoRadius));
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
    const auto f = asFloat(d);
    if (!f)
      fail(w, key,
           fmt::format("element {} ({}) is not {} as a 32-bit float", i, e.dump(),
                       std::isfinite(static_cast<float>(d)) ? "representable (it would become 0)" : "finite"));
    m[i / 4][i % 4] = *f;
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
// (symbolic links) and must be an existing file. Returns the absolute path. `parentCanonical`, when given, is the canonical form of the file's
// folder: then one lstat tells whether the file itself is a link, instead of a readlink for
// every component of the path, for each of up to 2*10^5 files.
fs::path resolveInFolder(const fs::path& folderAbs, const fs::path& folderCanonical, const fs::path& rel,
                         const std::string& text, const std::string& display, const char* key, const Where& w,
                         const std::optional<fs::path>& parentCanonical = std::nullopt) {
  const fs::path abs = folderAbs / rel;
  std::error_code ec;
  struct stat link {};
  const bool plainFile = parentCanonical && ::lstat(abs.c_str(), &link) == 0 && !S_ISLNK(link.st_mode);
  const fs::path canon = plainFile ? *parentCanonical / rel.filename() : fs::weakly_canonical(abs, ec);
  if (ec) fail(w, key, fmt::format("cannot resolve {}: {}", quoteJson(text), ec.message()));
  const fs::path inside = canon.lexically_relative(folderCanonical);
  if (inside.empty() || inside == "." || *inside.begin() == "..")
    fail(w, key,
         fmt::format("{} resolves to {}, outside the capture folder (through a symbolic link)", quoteJson(text),
                     canon.string()));
  if (plainFile && S_ISREG(link.st_mode)) return abs;  // what lstat said, for a file that is no link
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

fs::path absoluteFolder(const fs::path& folder) {
  fs::path p = fs::absolute(folder).lexically_normal();
  if (!p.has_filename() && p.has_relative_path()) p = p.parent_path();  // trailing slash
  return p;
}

// One distinct file a capture names: resolved and its header checked (runFileChecks), the outcome
// kept for every frame that names it.
struct FileCheck {
  fs::path relative;
  std::string text;     // as written in capture.json
  std::string display;  // as messages show it
  bool reference = false;
  int firstFrame = 0;   // messages name the first frame that uses the file
  std::optional<fs::path> parentCanonical;  // of the file's folder, when it resolves
  fs::path absolute;
  Layout layout;
  std::exception_ptr error;
};

void runFileCheck(FileCheck& c, const Capture& capture, const fs::path& folderCanonical, const std::string& jsonFile) {
  try {
    const char* key = c.reference ? "reference" : "gbuffer";
    c.absolute = resolveInFolder(capture.folder, folderCanonical, c.relative, c.text, c.display, key,
                                 Where{jsonFile, c.firstFrame}, c.parentCanonical);
    const Where w{c.display, c.firstFrame};
    const auto header = detail::readExrHeaderDetail(c.absolute, c.display, c.firstFrame);
    if (c.reference)
      checkReferenceHeader(header, capture.width, capture.height, w);
    else
      c.layout = checkGBufferHeader(header, capture.width, capture.height, w);
  } catch (...) {
    c.error = std::current_exception();
  }
}

// A capture of 10^5 frames names up to 2*10^5 files: they are checked on up to 8 threads.
void runFileChecks(std::vector<FileCheck>& checks, const Capture& capture, const fs::path& folderCanonical,
                   const std::string& jsonFile) {
  std::map<fs::path, std::optional<fs::path>> parents;  // a capture's files lie in a few folders
  for (auto& c : checks) {
    auto [it, added] = parents.try_emplace(c.relative.parent_path());
    if (added) {
      std::error_code ec;
      fs::path canonical = fs::canonical(capture.folder / it->first, ec);
      if (!ec) it->second = std::move(canonical);
    }
    c.parentCanonical = it->second;
  }
  const size_t threads = std::min<size_t>({8, std::max(1u, std::thread::hardware_concurrency()), 1 + checks.size() / 256});
  std::atomic<size_t> next{0};
  const auto work = [&] {
    for (size_t i = next++; i < checks.size(); i = next++) runFileCheck(checks[i], capture, folderCanonical, jsonFile);
  };
  std::vector<std::thread> helpers;
  for (size_t t = 1; t < threads; ++t) helpers.emplace_back(work);
  work();
  for (auto& h : helpers) h.join();
}

}  // namespace

// ---- loading ---------------------------------------------------------------------------------------

namespace {

// The folder exists and holds a regular capture.json; returns where errors in that file point.
Where checkCaptureFolder(const fs::path& folder) {
  if (folder.empty()) throw InputError("", std::nullopt, "", "no capture folder given (the path is empty)");
  const std::string folderDisplay = folder.string();
  std::error_code ec;
  const auto st = fs::status(folder, ec);
  if (ec || !fs::exists(st)) throw InputError(folderDisplay, std::nullopt, "", "capture folder does not exist");
  if (!fs::is_directory(st))
    throw InputError(folderDisplay, std::nullopt, "", "is not a folder; a capture is a folder holding capture.json");
  const fs::path jsonPath = folder / "capture.json";
  const Where top{jsonPath.lexically_normal().string(), std::nullopt};
  const auto jsonStatus = fs::status(jsonPath, ec);
  if (ec || !fs::exists(jsonStatus)) fail(top, "", "file does not exist; a capture folder must contain capture.json");
  if (!fs::is_regular_file(jsonStatus)) fail(top, "", "is not a regular file");
  return top;
}

// format and version first: a file of another format or version gets that message, not a
// complaint about fields it does not know. Returns whether it is version 1.1 (geometry allowed).
bool checkFormatAndVersion(const json& root, const Where& top) {
  auto format = root.find("format");
  if (format == root.end()) fail(top, "format", fmt::format("missing; expected \"{}\"", kFormatName));
  if (!format->is_string() || format->get<std::string>() != kFormatName)
    fail(top, "format", fmt::format("expected \"{}\", got {}", kFormatName, describe(*format)));
  auto version = root.find("version");
  if (version == root.end()) fail(top, "version", fmt::format("missing; supported versions: {}", kSupportedVersions));
  const bool version1 = version->is_number_integer() && (version->is_number_unsigned()
                                                              ? version->get<std::uint64_t>() == std::uint64_t(kFormatVersion)
                                                              : version->get<std::int64_t>() == kFormatVersion);
  const bool version11 = version->is_number_float() && version->get<double>() == kFormatVersionGeometry;
  if (!version->is_number())
    fail(top, "version", fmt::format("expected a number, got {}; supported versions: {}", describe(*version), kSupportedVersions));
  if (version->is_number_float() && !version11)
    fail(top, "version", fmt::format("expected the integer 1 or the number 1.1, got {}; supported versions: {}",
                                     describe(*version), kSupportedVersions));
  if (!version1 && !version11)
    fail(top, "version", fmt::format("version {} is not supported; supported versions: {}", version->dump(), kSupportedVersions));
  return version11;
}

void readSize(const json& root, const Where& top, Capture& capture) {
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
  capture.width = static_cast<int>(width);
  capture.height = static_cast<int>(height);
}

const json& framesArray(const json& root, const Where& top) {
  auto framesIt = root.find("frames");
  if (framesIt == root.end()) fail(top, "frames", "missing; expected an array of frame objects");
  if (!framesIt->is_array()) fail(top, "frames", "expected an array of frame objects, got " + describe(*framesIt));
  if (framesIt->empty()) fail(top, "frames", "the array is empty; a capture needs at least one frame");
  if (framesIt->size() > size_t(kMaxCaptureFrames))  // the parser refuses longer arrays already
    fail(top, "frames", fmt::format("more than {} frames, the limit", kMaxCaptureFrames));
  return *framesIt;
}

// One frame object of capture.json: its matrices and cut into `frame`, its file names returned.
FrameEntry readFrameEntry(const json& f, const Where& w, CaptureFrame& frame) {
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
  if (auto cut = f.find("cut"); cut != f.end()) {
    if (!cut->is_boolean()) fail(w, "cut", "expected true or false, got " + describe(*cut));
    frame.cut = cut->get<bool>();
  }
  frame.view = parseMatrix(f, "view", w);
  frame.projection = parseMatrix(f, "projection", w);
  checkView(frame.view, w);
  checkProjection(frame.projection, w);
  return entry;
}

// Every frame's files, each distinct path resolved and checked once (however many frames name it)
// on a few threads: checks[] and, per frame, its G-buffer's and reference's index in it.
struct FrameFileChecks {
  std::vector<FileCheck> checks;
  std::vector<std::pair<size_t, std::optional<size_t>>> ofFrame;
};

FrameFileChecks checkFrameFiles(const fs::path& folder, const fs::path& folderCanonical, const std::vector<FrameEntry>& entries,
                                const Capture& capture, const std::string& jsonFile) {
  FrameFileChecks out;
  std::unordered_map<std::string, size_t> checkOf[2];  // [reference?] relative path -> index in checks
  out.ofFrame.reserve(entries.size());
  const auto checkFor = [&](const fs::path& rel, const std::string& text, bool reference, int frame) {
    auto [it, added] = checkOf[reference].try_emplace(rel.generic_string(), out.checks.size());
    if (added) out.checks.push_back({rel, text, (folder / rel).lexically_normal().string(), reference, frame});
    return it->second;
  };
  for (size_t i = 0; i < entries.size(); ++i) {
    const FrameEntry& entry = entries[i];
    const size_t g = checkFor(entry.gbuffer, entry.gbufferText, false, int(i));
    std::optional<size_t> r;
    if (entry.reference) r = checkFor(*entry.reference, entry.referenceText, true, int(i));
    out.ofFrame.emplace_back(g, r);
  }
  runFileChecks(out.checks, capture, folderCanonical, jsonFile);
  return out;
}

// The channel layout of frame 0 must hold for every frame.
void checkSameLayout(const Layout& layout, const Layout& first, const Where& gw, int index) {
  if (layout.normals != first.normals)
    fail(gw, "normal.X",
         fmt::format("frame {} {}; every frame must have the same channels", index,
                     layout.normals ? "has normals but frame 0 has none"
                                    : "has no normals (normal.X, normal.Y, normal.Z) but frame 0 has them"));
  if (layout.depth2 != first.depth2)
    fail(gw, "depth2",
         fmt::format("frame {} {}; every frame must have the same channels", index,
                     layout.depth2 ? "has a depth2 channel but frame 0 has none" : "has no depth2 channel but frame 0 has one"));
}

// The checks' results in frame order, as a check frame by frame would find them: the first error
// is thrown, else each frame's files and the capture's layout are set.
void applyFrameFiles(const FrameFileChecks& files, Capture& capture) {
  Layout first;
  for (size_t i = 0; i < capture.frames.size(); ++i) {
    CaptureFrame& frame = capture.frames[i];
    const FileCheck& g = files.checks[files.ofFrame[i].first];
    if (g.error) std::rethrow_exception(g.error);
    frame.gbuffer = g.absolute;
    if (i == 0) first = g.layout;
    else checkSameLayout(g.layout, first, Where{g.display, int(i)}, int(i));
    if (files.ofFrame[i].second) {
      const FileCheck& r = files.checks[*files.ofFrame[i].second];
      if (r.error) std::rethrow_exception(r.error);
      frame.reference = r.absolute;
    }
  }
  capture.hasNormals = first.normals;
  capture.hasDepth2 = first.depth2;
}

}  // namespace

Capture loadCapture(const fs::path& folder) {
  const Where top = checkCaptureFolder(folder);
  const json root = readBoundedJson(folder / "capture.json", kCaptureJsonLimits, top.file);
  if (!root.is_object()) fail(top, "", "the top level must be a JSON object, got " + describe(root));
  const bool version11 = checkFormatAndVersion(root, top);
  checkKnownFields(root, kTopLevelFields, top, "of capture.json");
  std::optional<fs::path> geometry;
  if (auto g = root.find("geometry"); g != root.end()) {
    if (!version11) fail(top, "geometry", "needs \"version\": 1.1 (version 1 captures have no geometry)");
    geometry = relativePath(*g, "geometry", top);
  }
  Capture capture;
  readSize(root, top, capture);
  capture.folder = absoluteFolder(folder);
  capture.name = capture.folder.filename().string();
  if (auto scene = root.find("scene"); scene != root.end()) {
    if (!scene->is_object()) fail(top, "scene", "expected an object, got " + describe(*scene));
    checkAoRadius(*scene, top);
    capture.scene = *scene;
  }
  // Pass 1: everything in capture.json, so typos are reported before any EXR is opened.
  const json& frames = framesArray(root, top);
  std::vector<FrameEntry> entries;
  capture.frames.resize(frames.size());
  for (size_t i = 0; i < frames.size(); ++i) entries.push_back(readFrameEntry(frames[i], Where{top.file, int(i)}, capture.frames[i]));
  // Pass 2: files. Paths stay inside the folder, every EXR header is checked.
  std::error_code ec;
  const fs::path folderCanonical = fs::canonical(capture.folder, ec);
  if (ec) throw InputError(folder.string(), std::nullopt, "", "cannot resolve the capture folder: " + ec.message());
  applyFrameFiles(checkFrameFiles(folder, folderCanonical, entries, capture, top.file), capture);
  if (geometry)
    capture.geometry = resolveInFolder(capture.folder, folderCanonical, *geometry, root.at("geometry").get<std::string>(),
                                       (folder / *geometry).lexically_normal().string(), "geometry", top);
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

std::vector<fs::path> captureFiles(const Capture& capture) {
  std::set<fs::path> files;
  for (const auto& f : capture.frames) {
    files.insert(f.gbuffer);
    if (f.reference) files.insert(*f.reference);
  }
  if (capture.geometry) files.insert(*capture.geometry);
  std::vector<fs::path> list = {capture.folder / "capture.json"};
  list.insert(list.end(), files.begin(), files.end());
  return list;
}

CaptureGeometry loadGeometry(const Capture& capture) {
  if (!capture.geometry)
    throw InputError((capture.folder / "capture.json").string(), std::nullopt, "geometry",
                     "the capture has no geometry (format 1.1's \"geometry\": an OBJ of the scene's triangles)");
  return readObjGeometry(*capture.geometry, detail::displayPath(*capture.geometry));
}

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
                  const json& scene, const CaptureGeometry* geometry) {
  validateForWrite(width, height, frames, scene);
  fs::path target = folder.lexically_normal();
  if (!target.has_filename() && target.has_relative_path()) target = target.parent_path();
  if (target.empty() || target == "." || target == ".." || !target.has_filename())
    throw std::invalid_argument("writeCapture: invalid folder " + folder.string());
  // The rules of every output folder (core/output_directory.h): only an earlier capture is
  // replaced, one writer at a time, and the folder is the old capture or the new one at any moment.
  OutputDirectory out(target, ResultKind::Capture);
  writeCaptureFiles(out.staging(), width, height, frames, scene, geometry);
  out.commit();
}

void writeCaptureFiles(const fs::path& folder, int width, int height, const std::vector<CaptureFrameData>& frames,
                       const json& scene, const CaptureGeometry* geometry) {
  validateForWrite(width, height, frames, scene);
  const fs::path& tmp = folder;
  {
    std::error_code ec;
    fs::create_directories(tmp / "frames", ec);
    if (ec) throw InputError(tmp.string(), std::nullopt, "", "cannot create folder: " + ec.message());

    nlohmann::ordered_json doc;
    doc["format"] = kFormatName;
    if (geometry)
      doc["version"] = kFormatVersionGeometry;
    else
      doc["version"] = kFormatVersion;
    doc["width"] = width;
    doc["height"] = height;
    if (geometry) {
      doc["geometry"] = kGeometryFile;
      writeTextFile(tmp / kGeometryFile, objText(*geometry, "aoreplay capture geometry: world-space triangles"));
    }
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
  }
}

}  // namespace aor
