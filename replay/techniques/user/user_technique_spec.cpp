#include "techniques/user/user_technique_spec.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "shared_passes/shared_passes.h"
#include "core/input_error.h"
#include "core/json_input.h"
#include "core/plain_text.h"
#include "vk/device_limits.h"

namespace aor {
namespace fs = std::filesystem;
using ordered = nlohmann::ordered_json;

namespace {

constexpr const char* kFormat = "aoreplay-technique";
constexpr int kVersion = 1;
// A run times at most 256 passes (runtime/executor.cpp); the shared front, the params upload and the
// denoisers take fewer than 56 of them. Checked before any shader is compiled.
constexpr size_t kMaxUserPasses = 200;
constexpr uint32_t kMaxWorkgroupInvocations = 1024;  // Vulkan's guaranteed minimum of maxComputeWorkGroupInvocations

// GLSL words a parameter key cannot be (it becomes a member of the `params` block).
const std::set<std::string>& glslReservedWords() {
  static const std::set<std::string> words = {
      "active", "asm", "atomic_uint", "attribute", "bool", "break", "buffer", "case", "cast", "centroid", "class",
      "coherent", "common", "const", "continue", "default", "discard", "do", "double", "else", "enum", "extern",
      "external", "false", "filter", "fixed", "flat", "float", "for", "fvec2", "fvec3", "fvec4", "goto", "half",
      "highp", "hvec2", "hvec3", "hvec4", "if", "iimage2d", "image2d", "in", "inline", "inout", "input", "int",
      "interface", "invariant", "layout", "long", "lowp", "mediump", "namespace", "noinline", "noperspective", "out",
      "output", "partition", "patch", "precise", "precision", "public", "readonly", "resource", "restrict", "return",
      "sample", "sampler", "sampler2d", "shared", "short", "sizeof", "smooth", "static", "struct", "subroutine",
      "superp", "switch", "template", "this", "true", "typedef", "uint", "uniform", "union", "unsigned", "using",
      "varying", "vec2", "vec3", "vec4", "ivec2", "ivec3", "ivec4", "uvec2", "uvec3", "uvec4", "bvec2", "bvec3",
      "bvec4", "mat2", "mat3", "mat4", "void", "volatile", "while", "writeonly", "main", "frame", "params"};
  return words;
}

const std::vector<std::string>& sharedKeys() {
  static const std::vector<std::string> keys = {kRadiusKey, shared_passes::kSpatialKey, shared_passes::kTemporalKey, "technique"};
  return keys;
}

struct Checker {
  std::string file;  // as messages name it

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw InputError(file, std::nullopt, field, problem);
  }

  static std::string describe(const ordered& v) {
    switch (v.type()) {
      case ordered::value_t::object: return "an object";
      case ordered::value_t::array: return "an array";
      case ordered::value_t::string: return "a string";
      case ordered::value_t::boolean: return "a boolean";
      case ordered::value_t::null: return "null";
      default: return "a number";
    }
  }

  // Every key of `object` must be one of `allowed`.
  void keysOnly(const ordered& object, const std::string& where, std::initializer_list<const char*> allowed) const {
    for (const auto& [key, value] : object.items()) {
      if (std::none_of(allowed.begin(), allowed.end(), [&key = key](const char* a) { return key == a; })) {
        std::vector<std::string> names(allowed.begin(), allowed.end());
        fail(where.empty() ? key : where + "." + key,
             fmt::format("unknown key {} (the keys here are {})", quoteForMessage(key), fmt::join(names, ", ")));
      }
    }
  }
  const ordered& object(const ordered& v, const std::string& field) const {
    if (!v.is_object()) fail(field, "expected an object, got " + describe(v));
    return v;
  }
  const ordered& array(const ordered& v, const std::string& field) const {
    if (!v.is_array()) fail(field, "expected an array, got " + describe(v));
    return v;
  }
  std::string string(const ordered& v, const std::string& field) const {
    if (!v.is_string()) fail(field, "expected a string, got " + describe(v));
    // A doc becomes a comment line of the generated GLSL header: a newline there would be code.
    return withoutControlCharacters(v.get<std::string>(), file, field);
  }
  double number(const ordered& v, const std::string& field) const {
    if (!v.is_number()) fail(field, "expected a number, got " + describe(v));
    double d = v.get<double>();
    if (!std::isfinite(d) || std::abs(d) > 3.0e38) fail(field, fmt::format("{} is not a finite 32-bit value", v.dump()));
    return d;
  }
  long long integer(const ordered& v, const std::string& field, long long lo, long long hi) const {
    double d = number(v, field);
    if (d != std::floor(d)) fail(field, fmt::format("expected a whole number, got {}", v.dump()));
    if (d < double(lo) || d > double(hi)) fail(field, fmt::format("{} is outside {}..{}", v.dump(), lo, hi));
    return (long long)d;
  }
  bool boolean(const ordered& v, const std::string& field) const {
    if (!v.is_boolean()) fail(field, "expected true or false, got " + describe(v));
    return v.get<bool>();
  }
  const ordered& required(const ordered& object, const char* key, const std::string& where) const {
    auto it = object.find(key);
    if (it == object.end()) fail(where.empty() ? key : where + "." + key, "missing");
    return *it;
  }
  std::string name(const ordered& v, const std::string& field, const char* what) const {
    std::string text = string(v, field);
    bool ok = !text.empty() && text.size() <= 64 && text[0] >= 'a' && text[0] <= 'z' &&
              std::all_of(text.begin(), text.end(), [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'; });
    if (!ok) fail(field, fmt::format("{} name {} must match [a-z][a-z0-9_]* (at most 64 characters)", what, quoteForMessage(text)));
    if (text.rfind("gl_", 0) == 0 || text.find("__") != std::string::npos)
      fail(field, fmt::format("{} name {} is reserved by GLSL (gl_ prefix or a double underscore)", what, quoteForMessage(text)));
    return text;
  }
};

Parameter parseParameter(const Checker& c, const std::string& key, const ordered& v, const std::string& field) {
  c.object(v, field);
  std::string type = c.string(c.required(v, "type", field), field + ".type");
  Parameter p;
  p.key = key;
  if (auto doc = v.find("doc"); doc != v.end()) p.doc = c.string(*doc, field + ".doc");
  if (type == "int" || type == "float") {
    c.keysOnly(v, field, {"type", "default", "min", "max", "doc", "tunable"});
    bool whole = type == "int";
    p.type = whole ? ParameterType::Int : ParameterType::Float;
    auto read = [&](const char* k) {
      const ordered& n = c.required(v, k, field);
      return whole ? double(c.integer(n, field + "." + k, -(1LL << 31), (1LL << 31) - 1)) : c.number(n, field + "." + k);
    };
    p.min = read("min");
    p.max = read("max");
    p.defaultValue = read("default");
    if (p.min > p.max) c.fail(field + ".min", fmt::format("min {} is above max {}", p.min, p.max));
    if (p.defaultValue < p.min || p.defaultValue > p.max)
      c.fail(field + ".default", fmt::format("default {} is outside [{}, {}]", p.defaultValue, p.min, p.max));
    if (auto t = v.find("tunable"); t != v.end()) p.tunable = c.boolean(*t, field + ".tunable");
  } else if (type == "bool") {
    c.keysOnly(v, field, {"type", "default", "doc"});
    p.type = ParameterType::Bool;
    p.min = 0;
    p.max = 1;
    p.defaultValue = c.boolean(c.required(v, "default", field), field + ".default") ? 1 : 0;
  } else if (type == "enum") {
    c.keysOnly(v, field, {"type", "default", "choices", "doc"});
    p.type = ParameterType::Enum;
    const ordered& choices = c.array(c.required(v, "choices", field), field + ".choices");
    if (choices.empty()) c.fail(field + ".choices", "needs at least one choice");
    for (size_t i = 0; i < choices.size(); ++i) {
      std::string choice = c.name(choices[i], fmt::format("{}.choices[{}]", field, i), "choice");
      if (std::find(p.choices.begin(), p.choices.end(), choice) != p.choices.end())
        c.fail(fmt::format("{}.choices[{}]", field, i), fmt::format("duplicate choice '{}'", choice));
      p.choices.push_back(choice);
    }
    std::string def = c.string(c.required(v, "default", field), field + ".default");
    auto it = std::find(p.choices.begin(), p.choices.end(), def);
    if (it == p.choices.end())
      c.fail(field + ".default", fmt::format("'{}' is not one of the choices ({})", def, fmt::join(p.choices, ", ")));
    p.defaultValue = double(it - p.choices.begin());
    p.min = 0;
    p.max = double(p.choices.size() - 1);
  } else {
    c.fail(field + ".type", fmt::format("unknown type {} (int, float, bool or enum)", quoteForMessage(type)));
  }
  return p;
}

std::vector<Parameter> parseParameters(const Checker& c, const ordered& v) {
  std::vector<Parameter> out;
  c.object(v, "parameters");
  for (const auto& [key, value] : v.items()) {
    std::string field = "parameters." + key;
    c.name(ordered(key), field, "parameter");
    if (std::find(sharedKeys().begin(), sharedKeys().end(), key) != sharedKeys().end())
      c.fail(field, fmt::format("'{}' is a shared key ({}); the run's radius reaches shaders as frame.radius",
                                key, fmt::join(sharedKeys(), ", ")));
    if (glslReservedWords().count(key)) c.fail(field, fmt::format("'{}' is a GLSL word and cannot name a member of params", key));
    out.push_back(parseParameter(c, key, value, field));
  }
  return out;
}

// A preset's value in the parameter's JSON type: numbers for int/float, true/false for bool, a
// choice's name for enum.
double presetValue(const Checker& c, const Parameter& p, const ordered& v, const std::string& field) {
  double value = 0;
  switch (p.type) {
    case ParameterType::Bool: value = c.boolean(v, field) ? 1 : 0; break;
    case ParameterType::Enum: {
      std::string s = c.string(v, field);
      auto it = std::find(p.choices.begin(), p.choices.end(), s);
      if (it == p.choices.end()) c.fail(field, fmt::format("'{}' is not one of {}", s, fmt::join(p.choices, ", ")));
      value = double(it - p.choices.begin());
      break;
    }
    case ParameterType::Int: value = double(c.integer(v, field, -(1LL << 31), (1LL << 31) - 1)); break;
    case ParameterType::Float: value = c.number(v, field); break;
  }
  if (value < p.min || value > p.max) c.fail(field, fmt::format("{} is outside [{}, {}]", v.dump(), p.min, p.max));
  return value;
}

std::vector<Preset> parsePresets(const Checker& c, const ordered& v, const std::vector<Parameter>& params) {
  std::vector<Preset> out;
  c.object(v, "presets");
  for (const auto& [name, values] : v.items()) {
    std::string field = "presets." + name;
    c.name(ordered(name), field, "preset");
    c.object(values, field);
    Preset preset{name, {}};
    for (const auto& [key, value] : values.items()) {
      auto p = std::find_if(params.begin(), params.end(), [&key = key](const Parameter& q) { return q.key == key; });
      if (p == params.end()) {
        std::vector<std::string> keys;
        for (const auto& q : params) keys.push_back(q.key);
        c.fail(field + "." + key, fmt::format("unknown parameter {} (parameters: {})", quoteForMessage(key),
                                              keys.empty() ? std::string("none") : fmt::format("{}", fmt::join(keys, ", "))));
      }
      preset.values.emplace_back(key, presetValue(c, *p, value, field + "." + key));
    }
    out.push_back(std::move(preset));
  }
  return out;
}

VkFormat imageFormat(const Checker& c, const std::string& text, const std::string& field) {
  static const std::map<std::string, VkFormat> formats = {{"r8", VK_FORMAT_R8_UNORM},
                                                          {"r16f", VK_FORMAT_R16_SFLOAT},
                                                          {"r32f", VK_FORMAT_R32_SFLOAT},
                                                          {"rgba8", VK_FORMAT_R8G8B8A8_UNORM},
                                                          {"rgba16f", VK_FORMAT_R16G16B16A16_SFLOAT}};
  auto it = formats.find(text);
  if (it == formats.end()) c.fail(field, fmt::format("unknown format {} (r8, r16f, r32f, rgba8 or rgba16f)", quoteForMessage(text)));
  return it->second;
}

UserImageWrite parseWrite(const Checker& c, const ordered& v, const std::string& field) {
  c.object(v, field);
  c.keysOnly(v, field, {"name", "format", "scale"});
  UserImageWrite w;
  w.name = c.name(c.required(v, "name", field), field + ".name", "image");
  w.formatName = c.string(c.required(v, "format", field), field + ".format");
  w.format = imageFormat(c, w.formatName, field + ".format");
  if (auto s = v.find("scale"); s != v.end()) {
    std::string scale = c.string(*s, field + ".scale");
    if (scale != "full" && scale != "half") c.fail(field + ".scale", fmt::format("{} is not full or half", quoteForMessage(scale)));
    w.half = scale == "half";
  }
  return w;
}

UserPass parsePass(const Checker& c, const ordered& v, const std::string& field, const fs::path& folder) {
  c.object(v, field);
  c.keysOnly(v, field, {"name", "shader", "reads", "writes", "workgroup"});
  UserPass pass;
  pass.name = c.name(c.required(v, "name", field), field + ".name", "pass");
  const auto& reserved = reservedPassNames();
  if (std::find(reserved.begin(), reserved.end(), pass.name) != reserved.end())
    c.fail(field + ".name", fmt::format("'{}' is the name of a shared block's pass ({})", pass.name, fmt::join(reserved, ", ")));
  pass.shaderText = c.string(c.required(v, "shader", field), field + ".shader");
  pass.shader = resolveTechniqueFile(folder, pass.shaderText, c.file, field + ".shader");
  if (auto r = v.find("reads"); r != v.end()) {
    c.array(*r, field + ".reads");
    for (size_t i = 0; i < r->size(); ++i) pass.reads.push_back(c.name((*r)[i], fmt::format("{}.reads[{}]", field, i), "image"));
  }
  const ordered& writes = c.array(c.required(v, "writes", field), field + ".writes");
  if (writes.empty()) c.fail(field + ".writes", "a pass must write at least one image");
  for (size_t i = 0; i < writes.size(); ++i) pass.writes.push_back(parseWrite(c, writes[i], fmt::format("{}.writes[{}]", field, i)));
  if (auto wg = v.find("workgroup"); wg != v.end()) {
    const std::string f = field + ".workgroup";
    c.array(*wg, f);
    if (wg->size() != 2) c.fail(f, fmt::format("expected [x, y], got {} numbers", wg->size()));
    for (int i = 0; i < 2; ++i) pass.workgroup[i] = uint32_t(c.integer((*wg)[size_t(i)], fmt::format("{}[{}]", f, i), 1, kMaxWorkgroupInvocations));
    if (pass.workgroup[0] * pass.workgroup[1] > kMaxWorkgroupInvocations)
      c.fail(f, fmt::format("{} x {} invocations exceed {}", pass.workgroup[0], pass.workgroup[1], kMaxWorkgroupInvocations));
  }
  return pass;
}

// Names are unique, reads name a built-in or an earlier pass's write, every write is read or is
// the output, and the output is a full-scale write.
void checkGraph(const Checker& c, const UserTechniqueSpec& spec) {
  const auto& builtins = userBuiltinInputs();
  std::map<std::string, std::string> writtenBy;  // image -> field of its write
  std::set<std::string> passNames, read;
  for (size_t p = 0; p < spec.passes.size(); ++p) {
    const UserPass& pass = spec.passes[p];
    std::string field = fmt::format("passes[{}]", p);
    if (!passNames.insert(pass.name).second) c.fail(field + ".name", fmt::format("duplicate pass name '{}'", pass.name));
    std::set<std::string> ownReads;
    for (size_t r = 0; r < pass.reads.size(); ++r) {
      const std::string& name = pass.reads[r];
      std::string rf = fmt::format("{}.reads[{}]", field, r);
      if (!ownReads.insert(name).second) c.fail(rf, fmt::format("'{}' is read twice by this pass", name));
      bool builtin = std::find(builtins.begin(), builtins.end(), name) != builtins.end();
      if (!builtin && !writtenBy.count(name)) {
        std::vector<std::string> known(builtins);
        for (const auto& [image, where] : writtenBy) known.push_back(image);
        c.fail(rf, fmt::format("'{}' is neither a built-in input nor written by an earlier pass (readable here: {})", name,
                               fmt::join(known, ", ")));
      }
      read.insert(name);
    }
    for (size_t w = 0; w < pass.writes.size(); ++w) {
      const auto& write = pass.writes[w];
      std::string wf = fmt::format("{}.writes[{}].name", field, w);
      if (std::find(builtins.begin(), builtins.end(), write.name) != builtins.end())
        c.fail(wf, fmt::format("'{}' is a built-in input's name", write.name));
      if (writtenBy.count(write.name)) c.fail(wf, fmt::format("'{}' is already written by {}", write.name, writtenBy[write.name]));
      writtenBy[write.name] = wf;
    }
  }
  const UserImageWrite* output = spec.write(spec.output);
  if (!output) c.fail("output", fmt::format("'{}' is not written by any pass", spec.output));
  if (output->half) c.fail("output", fmt::format("'{}' is a half-scale write; the output must be full scale", spec.output));
  if (spec.denoise == UserDenoise::Seed000 && output->format != VK_FORMAT_R16_SFLOAT)
    c.fail("output", fmt::format("with \"denoise\": \"seed000\" the output must be r16f ('{}' is {})", spec.output, output->formatName));
  for (const auto& [image, where] : writtenBy)
    if (image != spec.output && !read.count(image))
      c.fail(where, fmt::format("'{}' is written but no pass reads it and it is not the output", image));
}

UserTechniqueSpec parseSpec(const Checker& c, const ordered& doc, UserTechniqueSpec spec) {
  c.object(doc, "");
  c.keysOnly(doc, "", {"format", "version", "name", "parameters", "presets", "default_preset", "passes", "output", "denoise"});
  if (c.string(c.required(doc, "format", ""), "format") != kFormat)
    c.fail("format", fmt::format("expected \"{}\", got {}", kFormat, doc["format"].dump()));
  if (c.integer(c.required(doc, "version", ""), "version", 0, 1 << 30) != kVersion)
    c.fail("version", fmt::format("version {} is not supported (this aoreplay reads version {})", doc["version"].dump(), kVersion));
  spec.name = c.name(c.required(doc, "name", ""), "name", "technique");
  if (auto p = doc.find("parameters"); p != doc.end()) spec.parameters = parseParameters(c, *p);
  if (spec.parameters.size() * 4 > kMaxUpdateBufferBytes)
    c.fail("parameters", fmt::format("{} parameters make a params block of {} bytes; at most {} ({} bytes, the most vkCmdUpdateBuffer writes)",
                                     spec.parameters.size(), spec.parameters.size() * 4, kMaxUpdateBufferBytes / 4, kMaxUpdateBufferBytes));
  if (auto p = doc.find("presets"); p != doc.end()) spec.presets = parsePresets(c, *p, spec.parameters);
  if (auto d = doc.find("default_preset"); d != doc.end()) {
    spec.defaultPreset = c.string(*d, "default_preset");
    if (std::none_of(spec.presets.begin(), spec.presets.end(), [&](const Preset& p) { return p.name == spec.defaultPreset; }))
      c.fail("default_preset", fmt::format("'{}' is not one of the presets", spec.defaultPreset));
  }
  const ordered& passes = c.array(c.required(doc, "passes", ""), "passes");
  if (passes.empty()) c.fail("passes", "a technique needs at least one pass");
  if (passes.size() > kMaxUserPasses)
    c.fail("passes", fmt::format("{} passes; a technique has at most {} (a run times every pass, and the shared passes need "
                                 "timestamp slots too)", passes.size(), kMaxUserPasses));
  for (size_t i = 0; i < passes.size(); ++i) spec.passes.push_back(parsePass(c, passes[i], fmt::format("passes[{}]", i), spec.folder));
  spec.output = c.name(c.required(doc, "output", ""), "output", "image");
  if (auto d = doc.find("denoise"); d != doc.end()) {
    std::string denoise = c.string(*d, "denoise");
    if (denoise != "none" && denoise != "seed000") c.fail("denoise", fmt::format("{} is not none or seed000", quoteForMessage(denoise)));
    spec.denoise = denoise == "seed000" ? UserDenoise::Seed000 : UserDenoise::None;
  }
  checkGraph(c, spec);
  return spec;
}

}  // namespace

const UserPass* UserTechniqueSpec::pass(std::string_view n) const {
  for (const auto& p : passes)
    if (p.name == n) return &p;
  return nullptr;
}

const UserImageWrite* UserTechniqueSpec::write(std::string_view image) const {
  for (const auto& p : passes)
    for (const auto& w : p.writes)
      if (w.name == image) return &w;
  return nullptr;
}

const std::vector<std::string>& userBuiltinInputs() {
  static const std::vector<std::string> names = {"depth", "linear_depth", "view_normals", "history"};
  return names;
}

const std::vector<std::string>& reservedPassNames() {
  static const std::vector<std::string> names = {"upload",          "readback", "linear_depth", "linearize_depth",
                                                 "reconstruct_normals", "view_normals", "spatial_columns", "spatial",
                                                 "temporal",        "upsample", "fill",         "constants",
                                                 "history_copy",    "history_fill"};
  return names;
}

fs::path resolveTechniqueFile(const fs::path& folder, const std::string& text, const std::string& file, const std::string& field) {
  Checker c{file};
  if (text.empty()) c.fail(field, "path is empty");
  if (text.find('\\') != std::string::npos)
    c.fail(field, fmt::format("path {} contains a backslash; write paths with forward slashes", quoteForMessage(text)));
  if (text.find('\0') != std::string::npos) c.fail(field, "path contains a NUL character");
  const fs::path p(text);
  if (p.is_absolute() || p.has_root_path())
    c.fail(field, fmt::format("absolute path {} is not allowed; paths are relative to the technique's folder", quoteForMessage(text)));
  const fs::path n = p.lexically_normal();
  if (!n.empty() && *n.begin() == "..") c.fail(field, fmt::format("path {} leaves the technique's folder", quoteForMessage(text)));
  if (n.empty() || n == "." || !n.has_filename()) c.fail(field, fmt::format("path {} does not name a file", quoteForMessage(text)));
  std::error_code ec;
  const fs::path abs = folder / n;
  const fs::path canon = fs::weakly_canonical(abs, ec);
  const fs::path folderCanonical = fs::weakly_canonical(folder, ec);
  if (ec) c.fail(field, fmt::format("cannot resolve {}: {}", quoteForMessage(text), ec.message()));
  const fs::path inside = canon.lexically_relative(folderCanonical);
  if (inside.empty() || inside == "." || *inside.begin() == "..")
    c.fail(field, fmt::format("{} resolves to {}, outside the technique's folder (through a symbolic link)", quoteForMessage(text),
                              canon.string()));
  const auto st = fs::status(abs, ec);
  if (ec || !fs::exists(st)) c.fail(field, fmt::format("file {} does not exist (looked for {})", quoteForMessage(text), abs.string()));
  if (!fs::is_regular_file(st)) c.fail(field, fmt::format("{} is not a file", quoteForMessage(text)));
  return abs;
}

UserTechniqueSpec loadUserTechniqueSpec(const fs::path& path, const std::string& display) {
  JsonLimits limits;
  limits.maxBytes = 1 << 20;
  // The bounded reader's checks (a regular file, its size, depth, duplicate keys: what
  // readBoundedJson does), then the same text in key order, which parameters and presets keep.
  std::string text = readBoundedText(path, limits.maxBytes, display);
  parseBoundedJson(text, limits, display);
  UserTechniqueSpec spec;
  spec.file = fs::absolute(path).lexically_normal();
  spec.folder = spec.file.parent_path();
  spec.display = display;
  return parseSpec(Checker{display}, ordered::parse(text), std::move(spec));
}

}  // namespace aor
