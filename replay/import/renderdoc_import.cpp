#include "import/renderdoc_import.h"

#include <stdlib.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "capture/capture.h"
#include "capture/input_error.h"
#include "import/import_problem.h"
#include "import/renderdoc_camera.h"
#include "import/renderdoc_script.h"
#include "import/texel_decoding.h"
#include "report/output_directory.h"

namespace aor {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Digit runs compare as numbers, everything else byte by byte.
bool naturalLess(const std::string& a, const std::string& b) {
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      size_t ie = i, je = j;
      while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie]))) ++ie;
      while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je]))) ++je;
      const std::string da = a.substr(i, ie - i), db = b.substr(j, je - j);
      const std::string ta = da.substr(std::min(da.find_first_not_of('0'), da.size()));
      const std::string tb = db.substr(std::min(db.find_first_not_of('0'), db.size()));
      if (ta.size() != tb.size()) return ta.size() < tb.size();
      if (ta != tb) return ta < tb;
      i = ie, j = je;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i, ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

// A private folder for the script's dumps, removed at the end whatever happens.
class WorkFolder {
 public:
  WorkFolder() {
    std::string pattern = (fs::temp_directory_path() / "aoreplay-import-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder in " + pattern);
    path_ = pattern;
  }
  ~WorkFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  WorkFolder(const WorkFolder&) = delete;
  WorkFolder& operator=(const WorkFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

struct ImportedFrame {
  CaptureFrameData data;
  json scene;  // what was chosen, for capture.json
};

TexelImage readTexels(const json& entry, const fs::path& folder) {
  TexelImage image;
  image.width = entry.at("width");
  image.height = entry.at("height");
  image.format = entry.at("format").at("name");
  image.bgra = entry.at("format").at("bgra");
  std::ifstream in(folder / entry.at("file").get<std::string>(), std::ios::binary);
  image.bytes.assign(std::istreambuf_iterator<char>(in), {});
  return image;
}

std::vector<float> crop(const std::vector<float>& values, int width, int components, const ViewportRect& r) {
  std::vector<float> out;
  out.reserve(size_t(r.width) * size_t(r.height) * size_t(components));
  for (int y = r.y; y < r.y + r.height; ++y) {
    const auto row = values.begin() + (ptrdiff_t(y) * width + r.x) * components;
    out.insert(out.end(), row, row + ptrdiff_t(r.width) * components);
  }
  return out;
}

std::string resourceText(const json& entry) {
  return fmt::format("{} (id {}), {} {}x{}", entry.at("resource").get<std::string>(), entry.at("id").get<int>(),
                     entry.at("format").at("name").get<std::string>(), entry.at("width").get<int>(),
                     entry.at("height").get<int>());
}

std::string matrixText(const json& m) {
  return fmt::format("{}.{} ({} shader, {})", m.at("block").get<std::string>(), m.at("member").get<std::string>(),
                     m.at("stage").get<std::string>(), m.at("declared_row_major").get<bool>() ? "row-major" : "column-major");
}

glm::mat4 matrixOf(const json& m) {
  std::array<float, 16> rows{};
  for (size_t i = 0; i < 16; ++i) rows[i] = m.at("rows").at(i).get<float>();  // doubles of floats: exact
  return matrixFromRows(rows);
}

void printEvent(const json& dump, const fs::path& file, int index, std::FILE* log) {
  const json& e = dump.at("event");
  std::string passes;
  for (const auto& p : e.at("passes")) passes += (passes.empty() ? " in " : " > ") + p.get<std::string>();
  fmt::print(log, "frame {}: {} (RenderDoc {}, {})\n  event {} {}{}: {}\n", index, file.string(),
             dump.at("made_with").get<std::string>(), dump.at("api").get<std::string>(), e.at("id").get<int>(),
             e.at("name").get<std::string>(), passes, e.at("why").get<std::string>());
}

// The depth of the draw's viewport, as floats; `rect` receives the viewport.
std::vector<float> importDepth(const json& dump, const fs::path& folder, ViewportRect& rect, json& scene,
                               std::FILE* log) {
  const json& d = dump.at("depth");
  const json& v = dump.at("viewport");
  const TexelImage texels = readTexels(d, folder);
  const std::vector<float> depth = decodeDepth(texels);
  rect = viewportRect(v.at("x"), v.at("y"), v.at("width"), v.at("height"), v.at("min_depth"), v.at("max_depth"),
                      texels.width, texels.height);
  const bool whole = rect.x == 0 && rect.y == 0 && rect.width == texels.width && rect.height == texels.height;
  fmt::print(log, "  depth: {}; viewport {}x{} at ({}, {}){}\n", resourceText(d), rect.width, rect.height, rect.x,
             rect.y, whole ? "" : ", cropped to it");
  scene["depth"] = {{"resource", d.at("resource")}, {"id", d.at("id")}, {"format", d.at("format").at("name")},
                    {"mip", d.at("mip")}, {"layer", d.at("layer")}};
  scene["viewport"] = {{"x", rect.x}, {"y", rect.y}, {"width", rect.width}, {"height", rect.height},
                       {"flips_y", rect.flipsY}};
  return whole ? depth : crop(depth, texels.width, 1, rect);
}

std::vector<float> importNormals(const json& dump, const fs::path& folder, const ViewportRect& rect,
                                 const RenderDocImportOptions& o, json& scene, std::FILE* log) {
  const json& n = dump.at("normals");
  if (n.is_null()) {
    fmt::print(log, "  normals: none (reconstructed from depth on replay)\n");
    scene["normals"] = nullptr;
    return {};
  }
  const TexelImage texels = readTexels(n, folder);
  const json& d = dump.at("depth");
  if (texels.width != d.at("width").get<int>() || texels.height != d.at("height").get<int>())
    throw ImportProblem("--normals", fmt::format("{} is {}x{}, the depth target {}x{}: they must be the same size",
                                                 n.at("resource").get<std::string>(), texels.width, texels.height,
                                                 d.at("width").get<int>(), d.at("height").get<int>()));
  fmt::print(log, "  normals: {}, {} space\n", resourceText(n), o.normalsSpace);
  scene["normals"] = {{"resource", n.at("resource")}, {"id", n.at("id")}, {"format", n.at("format").at("name")},
                      {"space", o.normalsSpace}};
  return crop(decodeNormals(texels), texels.width, 3, rect);
}

ImportedCamera importMatrices(const json& dump, const ViewportRect& rect, json& scene, std::FILE* log) {
  const json& v = dump.at("view");
  const json& p = dump.at("projection");
  const std::string viewName = v.at("block").get<std::string>() + "." + v.at("member").get<std::string>();
  const std::string projectionName = p.at("block").get<std::string>() + "." + p.at("member").get<std::string>();
  if (viewName == projectionName)
    throw ImportProblem("--projection", fmt::format("--view and --projection both name {}: a combined matrix is not "
                                                    "supported; the import needs the world -> view matrix and the "
                                                    "view -> clip projection as separate members, and the blocks at "
                                                    "this event hold: {}",
                                                    viewName, dump.at("blocks").get<std::string>()));
  const glm::mat4 view = matrixOf(v), projection = matrixOf(p);
  checkProjectionMatrix(projection, projectionName);
  checkViewMatrix(view, viewName);
  ImportedCamera camera = importCamera(view, projection, rect.flipsY);
  fmt::print(log, "  view: {}\n  projection: {}: {}\n", matrixText(v), matrixText(p),
             describeProjection(camera.projection));
  for (const std::string& a : camera.adjustments) fmt::print(log, "  adjusted: {}\n", a);
  scene["view"] = matrixText(v);
  scene["projection"] = matrixText(p);
  scene["camera"] = describeProjection(camera.projection);
  scene["adjustments"] = camera.adjustments;
  return camera;
}

ImportedFrame importFrame(const json& dump, const fs::path& file, int index, const fs::path& folder,
                          const RenderDocImportOptions& o, std::FILE* log) {
  ImportedFrame f;
  json& s = f.scene;
  s["file"] = file.filename().string();
  if (dump.contains("made_with")) s["made_with"] = dump["made_with"];
  if (dump.contains("event")) {
    printEvent(dump, file, index, log);
    s["api"] = dump.at("api");
    s["event"] = dump["event"]["id"];
    s["event_name"] = dump["event"]["name"];
    s["passes"] = dump["event"]["passes"];
    s["event_chosen"] = dump["event"]["why"];
  }
  ViewportRect rect;
  if (dump.contains("depth")) f.data.gbuffer.depth = importDepth(dump, folder, rect, s, log);
  if (dump.contains("error")) {
    const json& e = dump["error"];
    throw ImportProblem(e.at("field"), e.at("message"));
  }
  f.data.gbuffer.width = rect.width;
  f.data.gbuffer.height = rect.height;
  f.data.gbuffer.normals = importNormals(dump, folder, rect, o, s, log);
  const ImportedCamera camera = importMatrices(dump, rect, s, log);
  if (o.normalsSpace == "view") viewNormalsToWorld(f.data.gbuffer.normals, matrixOf(dump.at("view")));
  f.data.view = camera.view;
  f.data.projection = camera.projection;
  return f;
}

DumpRequest dumpRequest(const RenderDocImportOptions& o, const fs::path& file, const fs::path& folder) {
  DumpRequest r;
  r.capture = file;
  r.workDir = folder;
  r.renderdocPython = o.renderdocPython;
  r.event = o.event;
  r.passName = o.passName;
  r.depth = o.depth;
  r.normals = o.normals;
  r.view = o.view;
  r.projection = o.projection;
  return r;
}

}  // namespace

std::vector<fs::path> renderDocInputs(const RenderDocImportOptions& o) {
  std::vector<fs::path> files = o.files;
  if (o.framesFromDir) {
    std::error_code ec;
    if (!fs::is_directory(*o.framesFromDir, ec))
      throw InputError(o.framesFromDir->string(), std::nullopt, "--frames-from-dir", "is not a folder");
    for (const auto& entry : fs::directory_iterator(*o.framesFromDir, ec))
      if (entry.path().extension() == ".rdc") files.push_back(entry.path());
    if (files.size() == o.files.size())
      throw InputError(o.framesFromDir->string(), std::nullopt, "--frames-from-dir", "holds no .rdc file");
  }
  if (files.empty())
    throw InputError("", std::nullopt, "FILE.rdc", "no capture given (name .rdc files or --frames-from-dir DIR)");
  for (const fs::path& f : files) {
    std::error_code ec;
    if (!fs::is_regular_file(f, ec)) throw InputError(f.string(), std::nullopt, "", "does not exist or is not a file");
  }
  std::stable_sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return naturalLess(a.filename().string(), b.filename().string());
  });
  return files;
}

void importRenderDoc(const RenderDocImportOptions& o, std::FILE* log) {
  if (o.normalsSpace != "world" && o.normalsSpace != "view")
    throw InputError("", std::nullopt, "--normals-space", "must be world or view, got " + o.normalsSpace);
  const std::vector<fs::path> files = renderDocInputs(o);
  // Refuses an --out it must not replace (or one holding an input), before any work.
  OutputDirectory out(o.out, ResultKind::Capture, files);
  WorkFolder work;
  std::vector<CaptureFrameData> frames;
  json scene = {{"source", "renderdoc"}, {"frames", json::array()}};
  for (size_t i = 0; i < files.size(); ++i) {
    const int index = int(i);
    const fs::path folder = work.path() / fmt::format("{:04}", i);
    fs::create_directories(folder);
    try {
      const json dump = runRenderDocDump(dumpRequest(o, files[i], folder));
      if (dump.contains("renderdoc")) scene["renderdoc"] = dump["renderdoc"];
      ImportedFrame f = importFrame(dump, files[i], index, folder, o, log);
      const GBuffer& first = frames.empty() ? f.data.gbuffer : frames[0].gbuffer;
      if (f.data.gbuffer.width != first.width || f.data.gbuffer.height != first.height)
        throw ImportProblem("", fmt::format("the frame is {}x{}, frame 0 is {}x{}: every frame must be the same size",
                                            f.data.gbuffer.width, f.data.gbuffer.height, first.width, first.height));
      frames.push_back(std::move(f.data));
      scene["frames"].push_back(std::move(f.scene));
    } catch (const ImportProblem& e) {
      std::fflush(log);  // what was found before the problem reads before the error message
      throw InputError(files[i].string(), index, e.field, e.what());
    } catch (const json::exception& e) {
      throw std::runtime_error(fmt::format("{}: the RenderDoc dump script's output is not as expected: {}",
                                           files[i].string(), e.what()));
    }
  }
  const GBuffer& g = frames[0].gbuffer;
  writeCaptureFiles(out.staging(), g.width, g.height, frames, scene);
  out.commit();
  fmt::print(log, "capture: {} ({} frame{}, {}x{}, {})\n", o.out.string(), frames.size(), frames.size() == 1 ? "" : "s",
             g.width, g.height, g.normals.empty() ? "depth only" : "depth and normals");
}

}  // namespace aor
