#include "techniques/user/shader_compiler.h"

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include <fmt/format.h>
#include <shaderc/shaderc.hpp>
#include <spirv-tools/libspirv.hpp>

#include "core/sha256.h"
#include "core/input_error.h"
#include "embedded_shaders.h"
#include "core/json_input.h"
#include "techniques/user/user_header.h"
#include "vk/shader_reflection.h"

#ifndef AOR_SHADERC_VERSION
#define AOR_SHADERC_VERSION "unknown"
#endif

namespace aor {
namespace fs = std::filesystem;
namespace {

constexpr const char* kHeaderName = "aoreplay.glsl";
constexpr uint64_t kMaxSourceBytes = 4u << 20;
constexpr size_t kMaxIncludeDepth = 32;
// A budget over one shader's whole expansion: an include that fans out (a file including the
// next one twice, 24 deep: 2^24 expansions) ran past 125 s at 3.3 GB before it.
constexpr size_t kMaxIncludes = 1000;
constexpr uint64_t kMaxIncludedBytes = 16u << 20;
constexpr const char* kCacheMagic = "aoreplay-spirv-cache 2";
// What the compile options below are, in every cache key.
constexpr const char* kCompileOptions = "glsl compute, vulkan 1.2, no optimisation";


// How messages name a file of the technique: the technique's path as given, then the file's.
std::string displayOf(const UserTechniqueSpec& spec, const std::string& relative) {
  fs::path folder = fs::path(spec.display).parent_path();
  return folder.empty() ? relative : (folder / relative).string();
}

// The sources one compile read besides the header: (absolute path, text).
using Sources = std::map<std::string, std::string>;

class Includer : public shaderc::CompileOptions::IncluderInterface {
 public:
  Includer(const UserTechniqueSpec& spec, std::string header, Sources& read) : spec_(spec), header_(std::move(header)), read_(read) {}

  shaderc_include_result* GetInclude(const char* requested, shaderc_include_type, const char*, size_t depth) override {
    auto* r = new Result;
    try {
      if (depth > kMaxIncludeDepth) throw std::runtime_error(fmt::format("#include nested deeper than {}", kMaxIncludeDepth));
      if (++includes_ > kMaxIncludes)
        throw std::runtime_error(fmt::format("more than {} #include expansions in one shader", kMaxIncludes));
      if (std::string_view(requested) == kHeaderName) {
        r->name = kHeaderName;
        r->content = header_;
      } else {
        fs::path path = resolveTechniqueFile(spec_.folder, requested, "", "#include");
        r->name = displayOf(spec_, fs::path(requested).lexically_normal().string());
        r->content = readBoundedText(path, kMaxSourceBytes, r->name);
        if ((includedBytes_ += r->content.size()) > kMaxIncludedBytes)
          throw std::runtime_error(fmt::format("more than {} MiB included into one shader", kMaxIncludedBytes >> 20));
        read_[path.string()] = r->content;
      }
    } catch (const std::exception& e) {
      r->name.clear();
      r->content = fmt::format("cannot include \"{}\": {}", requested, e.what());
    }
    r->result = {r->name.c_str(), r->name.size(), r->content.c_str(), r->content.size(), r};
    return &r->result;
  }
  void ReleaseInclude(shaderc_include_result* data) override { delete static_cast<Result*>(data->user_data); }

 private:
  struct Result {
    std::string name, content;
    shaderc_include_result result{};
  };
  const UserTechniqueSpec& spec_;
  std::string header_;
  Sources& read_;
  size_t includes_ = 0;
  uint64_t includedBytes_ = 0;
};

[[noreturn]] void fail(const UserTechniqueSpec& spec, size_t passIndex, const std::string& problem) {
  throw InputError(spec.display, std::nullopt, fmt::format("passes[{}].shader", passIndex), problem);
}

// The first lines of a shader must be `#version N` (N >= 450) and `#include "aoreplay.glsl"`,
// blank lines and // comments aside: the header's declarations must precede the shader's.
void checkPreamble(const std::string& source, const std::string& display, const UserTechniqueSpec& spec, size_t passIndex) {
  std::istringstream in(source);
  std::string line;
  int number = 0, step = 0;
  while (step < 2 && std::getline(in, line)) {
    ++number;
    size_t start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line.compare(start, 2, "//") == 0) continue;
    std::string text = line.substr(start);
    while (!text.empty() && (text.back() == '\r' || text.back() == ' ' || text.back() == '\t')) text.pop_back();
    if (step == 0) {
      int version = 0;
      if (std::sscanf(text.c_str(), "#version %d", &version) != 1 || version < 450)
        fail(spec, passIndex, fmt::format("{}:{}: error: a shader begins with #version 450 (or higher), got {}", display, number,
                                          quoteForMessage(text, 60)));
    } else if (text != "#include \"aoreplay.glsl\"") {
      fail(spec, passIndex, fmt::format("{}:{}: error: #include \"aoreplay.glsl\" must follow #version, got {}", display, number,
                                        quoteForMessage(text, 60)));
    }
    ++step;
  }
  if (step < 2) fail(spec, passIndex, fmt::format("{}: error: a shader begins with #version 450 and #include \"aoreplay.glsl\"", display));
}

// What shaderc says, without its "N error(s) generated." summary line.
std::string compileMessage(const std::string& message) {
  std::string out;
  std::istringstream in(message);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line.find("error generated") != std::string::npos || line.find("errors generated") != std::string::npos) continue;
    out += (out.empty() ? "" : "; ") + line;
  }
  return out.empty() ? message : out;
}

// The interface of the SPIR-V must be the header's: no bindings of the shader's own, the header's workgroup.
void checkInterface(const std::vector<uint32_t>& spirv, const UserTechniqueSpec& spec, size_t passIndex, const std::string& display) {
  const UserPass& pass = spec.passes[passIndex];
  ShaderInterface iface;
  try {
    iface = reflectComputeShader(spirv, display);
  } catch (const std::runtime_error& e) {
    fail(spec, passIndex, fmt::format("{}: error: {}", display, e.what()));
  }
  size_t expected = userPassBindings(spec, pass).size();
  if (iface.bindings.size() > expected)
    fail(spec, passIndex, fmt::format("{}: error: declares binding {} ('{}') of its own; bindings come from aoreplay.glsl", display,
                                      expected, iface.bindings[expected].name));
  if (iface.localSize[0] != pass.workgroup[0] || iface.localSize[1] != pass.workgroup[1] || iface.localSize[2] != 1)
    fail(spec, passIndex, fmt::format("{}: error: declares its own workgroup size; it comes from \"workgroup\" in technique.json",
                                      display));
  if (iface.pushConstantBytes != 0) fail(spec, passIndex, fmt::format("{}: error: declares push constants; use params", display));
}

// --- The disk cache. An entry is "aoreplay-spirv-cache 2\n", "key SHA256\n" (of everything that
// produced it: compiler, options, header, shader path and text), one "include SHA256 PATH" line per
// #included file, "spirv N SHA256\n", then N words. It is read like any input (a regular file, bounded),
// and used only when its key and includes match and its SPIR-V validates: anything else (a FIFO,
// a link to a device, a torn or foreign entry) is a miss, compiled anew and replaced, so a bad
// entry is never blamed on the user's shader.
constexpr uint64_t kMaxCacheEntryBytes = 64u << 20;

std::vector<uint32_t> validSpirv(std::string_view bytes) {
  if (bytes.empty() || bytes.size() % 4 != 0) throw std::runtime_error("its SPIR-V is not a whole number of words");
  std::vector<uint32_t> code(bytes.size() / 4);
  std::memcpy(code.data(), bytes.data(), bytes.size());
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_2);
  std::string problem;
  tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t&, const char* m) {
    if (problem.empty()) problem = m;
  });
  if (!tools.Validate(code)) throw std::runtime_error("its SPIR-V does not validate: " + problem);
  return code;
}

std::vector<uint32_t> readCacheEntry(const fs::path& file, const std::string& key) {
  const std::string text = readBoundedText(file, kMaxCacheEntryBytes, "it");
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line != kCacheMagic) throw std::runtime_error("it is not an entry of this version");
  if (!std::getline(in, line) || line != "key " + key) throw std::runtime_error("it was made from other sources");
  while (std::getline(in, line) && line.rfind("include ", 0) == 0) {
    std::string hash = line.substr(8, 64), path = line.size() > 73 ? line.substr(73) : "";
    if (textSha256(readBoundedText(path, kMaxSourceBytes, path)) != hash) throw std::runtime_error("an #included file changed");
  }
  size_t words = 0;
  char hash[65] = {};
  if (std::sscanf(line.c_str(), "spirv %zu %64s", &words, hash) != 2) throw std::runtime_error("it is damaged");
  const auto offset = size_t(in.tellg());
  if (in.fail() || text.size() - offset != words * 4) throw std::runtime_error("it is damaged (wrong length)");
  const std::string_view code = std::string_view(text).substr(offset);
  if (textSha256(code) != hash) throw std::runtime_error("it is damaged (checksum)");
  return validSpirv(code);
}

void writeCache(const fs::path& file, const std::string& key, const Sources& includes, const std::vector<uint32_t>& code) {
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  if (ec) return;  // a cache: without one every run compiles
  fs::path temporary = file;
  temporary += fmt::format(".{}.tmp", ::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) return;
    out << kCacheMagic << "\nkey " << key << "\n";
    for (const auto& [path, text] : includes) out << "include " << textSha256(text) << " " << path << "\n";
    const std::string_view bytes(reinterpret_cast<const char*>(code.data()), code.size() * 4);
    out << "spirv " << code.size() << " " << textSha256(bytes) << "\n";
    out.write(reinterpret_cast<const char*>(code.data()), std::streamsize(code.size() * 4));
    if (!out) {
      out.close();
      fs::remove(temporary, ec);
      return;
    }
  }
  fs::rename(temporary, file, ec);  // atomic, and replaces whatever was there (a FIFO, a link)
  if (ec) fs::remove(temporary, ec);
}

}  // namespace

std::string shadercVersion() {
  unsigned version = 0, revision = 0;
  shaderc_get_spv_version(&version, &revision);
  return fmt::format("shaderc {}, SPIR-V {}.{} rev {}", AOR_SHADERC_VERSION, version >> 16, (version >> 8) & 0xff, revision);
}

fs::path userShaderCacheFolder() {
  if (const char* dir = std::getenv("AOREPLAY_SHADER_CACHE"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return fs::path(xdg) / "aoreplay" / "shaders";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "aoreplay" / "shaders";
  return {};
}

CompiledUserShader compileUserPass(const UserTechniqueSpec& spec, size_t passIndex, bool countingBuild) {
  const UserPass& pass = spec.passes[passIndex];
  const std::string display = displayOf(spec, pass.shader.lexically_relative(spec.folder).string());
  const std::string source = readBoundedText(pass.shader, kMaxSourceBytes, display);
  checkPreamble(source, display, spec, passIndex);
  const std::string header = userPassHeader(spec, pass) + (countingBuild ? std::string(spirv::countOpsPrelude()) : "");

  const fs::path cacheFolder = userShaderCacheFolder();
  const std::string key = textSha256(fmt::format("{}\n{}\n{}\n{}\n{}\n{}", shadercVersion(), kCompileOptions, header.size(), header,
                                                 pass.shader.string(), source));
  const fs::path cacheFile = cacheFolder.empty() ? fs::path() : cacheFolder / (key.substr(0, 32) + ".spv");
  if (!cacheFile.empty() && fs::exists(fs::symlink_status(cacheFile))) {
    try {
      auto cached = readCacheEntry(cacheFile, key);
      checkInterface(cached, spec, passIndex, display);
      return {std::move(cached), true};
    } catch (const std::exception& e) {
      fmt::print(stderr, "note: shader cache entry {} not used ({}); compiling {} anew\n", cacheFile.string(), e.what(), display);
    }
  }

  Sources includes;
  shaderc::Compiler compiler;
  shaderc::CompileOptions options;
  options.SetTargetEnvironment(shaderc_target_env_vulkan, shaderc_env_version_vulkan_1_2);
  options.SetSourceLanguage(shaderc_source_language_glsl);
  // No SPIR-V optimisation (as the build's glslangValidator compiles the built-ins): it would drop
  // the bindings a shader never touches, and every binding of the header is bound. The driver
  // optimises anyway.
  options.SetIncluder(std::make_unique<Includer>(spec, header, includes));
  auto result = compiler.CompileGlslToSpv(source, shaderc_compute_shader, display.c_str(), options);
  if (result.GetCompilationStatus() != shaderc_compilation_status_success)
    fail(spec, passIndex, compileMessage(result.GetErrorMessage()));
  std::vector<uint32_t> code(result.cbegin(), result.cend());
  checkInterface(code, spec, passIndex, display);
  if (!cacheFile.empty()) writeCache(cacheFile, key, includes, code);
  return {std::move(code), false};
}

}  // namespace aor
