#pragma once
// `aoreplay import renderdoc`: turns one frame of each RenderDoc capture (.rdc) into a frame of an
// aoreplay capture (format v1): the depth attachment, optionally a normal target, and the camera
// matrices from uniform-block members of the draw's shaders. docs/renderdoc.md.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace aor {

// Mistakes made on purpose through a hidden option, for the tests that show the self-check
// catches each: GL rows left bottom-up (Vulkan's rows flipped), GL's D24 read as Vulkan's,
// GL's clip z taken as [0, 1].
enum class ImportFault { None, RowsUnflipped, D24LowBits, ClipZAsZeroToOne };

struct RenderDocImportOptions {
  std::vector<std::filesystem::path> files;           // .rdc files, one frame each
  std::optional<std::filesystem::path> framesFromDir;  // or every .rdc in this folder
  std::filesystem::path out;                          // the capture folder to write
  std::optional<int> event;                           // default: the last draw with a depth target
  std::optional<std::string> passName;
  std::string depth = "auto";    // or a texture (RenderDoc's name, ResourceId::N or N)
  std::string normals = "none";  // or a texture
  std::string normalsSpace = "world";
  std::string view, projection;  // BLOCK.member (or BLOCK.member[I], four vec4 elements)
  std::string viewProjection;    // or one combined matrix, factored (renderdoc_camera.h)
  std::string arrayMatrix = "columns";  // BLOCK.member[I]: the four elements are its "columns" or "rows"
  int sample = 0;                // of multisampled depth (and normals), the sample imported
  std::string renderdocPython;   // folder of a RenderDoc build's Python module; empty: the installed one
  bool noSelfCheck = false;      // import without checking against the draw's vertices (recorded)
  ImportFault fault = ImportFault::None;  // tests only
};

// The .rdc files in frame order: file-name order, digit runs compared as numbers (frame9 before
// frame10). Throws InputError when there are none or a file does not exist.
std::vector<std::filesystem::path> renderDocInputs(const RenderDocImportOptions& options);

// Imports every input and writes the capture to options.out, whole or not at all (an existing
// --out must be an earlier capture or empty, checked first). What it chose is printed to `log`
// as it goes, so the choices made before an error are shown too. Bad input throws InputError.
void importRenderDoc(const RenderDocImportOptions& options, std::FILE* log);

}  // namespace aor
