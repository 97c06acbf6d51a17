#include "import/renderdoc_import.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iterator>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "capture/capture.h"
#include "core/input_error.h"
#include "import/api_conventions.h"
#include "import/import_problem.h"
#include "import/renderdoc_camera.h"
#include "import/renderdoc_script.h"
#include "import/self_check.h"
#include "import/texel_decoding.h"
#include "core/output_directory.h"

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

struct ImportedFrame {
  CaptureFrameData data;
  json scene;  // what was chosen, for capture.json
};

// What was read of the frame on the way, for the self-check.
struct FrameFacts {
  ApiConventions conventions;  // as RenderDoc reports them: the self-check's reference
  ApiConventions applied;      // what the import followed: the same, but for a test-only fault
  RawViewport viewport;
  ViewportRect rect;
  double depthQuantum = 0.0;
  glm::mat4 appProjection{1.0f};
  glm::mat4 appView{1.0f};  // the application's world -> view (factored when combined)
  glm::dvec2 samplePosition{0.5, 0.5};  // where the imported sample lies in its pixel, rows as the capture's
  std::vector<glm::vec4> corners;  // the draw's post-vertex-shader clip positions, when the self-check can run
};

// Where the imported sample of a multisampled depth target lies in its pixel: the standard
// locations, turned with GL's rows; a count without a standard table is refused (the self-check
// would compare the wrong points).
std::string sampleText(const json& d, FrameFacts& facts) {
  const int samples = d.value("samples", 1), sample = d.value("sample", 0);
  if (samples <= 1) return "";
  const auto position = standardSamplePosition(samples, sample);
  if (!position)
    throw ImportProblem("--sample", fmt::format("{} has {} samples, a count without standard sample locations",
                                                d.at("resource").get<std::string>(), samples));
  facts.samplePosition = {position->x, facts.applied.rowsBottomUp ? 1.0 - position->y : position->y};
  return fmt::format("; {} samples, sample {} (at {:g}, {:g} in its pixel)", samples, sample, position->x, position->y);
}

// The captured API's conventions, as the dump script read them from the draw's state.
ApiConventions conventionsOf(const json& dump) {
  const json& c = dump.at("conventions");
  ApiConventions conventions;
  conventions.api = c.at("api");
  if (conventions.api != "Vulkan" && conventions.api != "OpenGL")
    throw ImportProblem("", fmt::format("{} captures are not supported (Vulkan and OpenGL are)", conventions.api));
  conventions.clipZMinusOneToOne = c.at("clip_z") == "-1..1";
  conventions.clipOriginUpperLeft = c.at("clip_y_at_row_0") == "+1";
  conventions.rowsBottomUp = c.at("rows") == "bottom-up";
  conventions.depthRangeMin = c.at("depth_range").at(0).get<double>();
  conventions.depthRangeMax = c.at("depth_range").at(1).get<double>();
  return conventions;
}

ApiConventions withFault(ApiConventions c, ImportFault fault) {
  if (fault == ImportFault::ClipZAsZeroToOne) c.clipZMinusOneToOne = false;
  if (fault == ImportFault::RowsUnflipped) c.rowsBottomUp = !c.rowsBottomUp;
  return c;
}

// The image's rows in reverse order: GL's bottom-up rows to the capture's top-down ones.
std::vector<float> flipRows(const std::vector<float>& values, int width, int height, int components) {
  const size_t row = size_t(width) * size_t(components);
  std::vector<float> out(values.size());
  for (int y = 0; y < height; ++y)
    std::copy_n(values.begin() + ptrdiff_t(size_t(y) * row), row, out.begin() + ptrdiff_t(size_t(height - 1 - y) * row));
  return out;
}

TexelImage readTexels(const json& entry, const fs::path& folder) {
  TexelImage image;
  image.width = entry.at("width");
  image.height = entry.at("height");
  image.format = entry.at("format").at("name");
  image.bgra = entry.at("format").at("bgra");
  image.samples = entry.value("samples", 1);
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

// The viewport's pixels, top row first.
std::vector<float> cropToCapture(const std::vector<float>& values, int width, int components, const ViewportRect& r,
                                 const ApiConventions& c) {
  const std::vector<float> cropped = crop(values, width, components, r);
  return c.rowsBottomUp ? flipRows(cropped, r.width, r.height, components) : cropped;
}

std::string resourceText(const json& entry) {
  return fmt::format("{} (id {}), {} {}x{}", entry.at("resource").get<std::string>(), entry.at("id").get<uint64_t>(),
                     entry.at("format").at("name").get<std::string>(), entry.at("width").get<int>(),
                     entry.at("height").get<int>());
}

std::string matrixName(const json& m) { return m.at("block").get<std::string>() + "." + m.at("member").get<std::string>(); }

std::string matrixText(const json& m) {
  const std::string layout = m.contains("array_read_as") ? "four vec4 read as " + m["array_read_as"].get<std::string>()
                             : m.at("declared_row_major").get<bool>() ? "row-major"
                                                                      : "column-major";
  return fmt::format("{} ({} shader, {}{})", matrixName(m), m.at("stage").get<std::string>(), layout,
                     m.at("push_constant").get<bool>() ? ", " + m.at("buffer").get<std::string>() : std::string());
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
  const std::string where = dump.contains("replayed_on") ? ", replayed on " + dump["replayed_on"].get<std::string>() : "";
  fmt::print(log, "frame {}: {} (RenderDoc {}, {}{})\n  event {} {}{}: {}\n", index, file.string(),
             dump.at("made_with").get<std::string>(), dump.at("api").get<std::string>(), where, e.at("id").get<int>(),
             e.at("name").get<std::string>(), passes, e.at("why").get<std::string>());
}

// The depth of the draw's viewport, as floats, top row first; `facts` receives the viewport.
std::vector<float> importDepth(const json& dump, const fs::path& folder, const RenderDocImportOptions& o,
                               FrameFacts& facts, json& scene, std::FILE* log) {
  const json& d = dump.at("depth");
  const json& v = dump.at("viewport");
  const json& range = dump.at("conventions").at("depth_range");
  facts.conventions = conventionsOf(dump);
  facts.applied = withFault(facts.conventions, o.fault);
  const TexelImage texels = readTexels(d, folder);
  const DepthDecodeFault fault = o.fault == ImportFault::D24LowBits ? DepthDecodeFault::Unorm24LowBits
                                                                    : DepthDecodeFault::None;
  const std::vector<float> depth = decodeDepth(texels, facts.applied.api, fault);
  facts.depthQuantum = depthFormatStep(texels.format);
  facts.viewport = {v.at("x"), v.at("y"), v.at("width"), v.at("height")};
  ViewportRect& rect = facts.rect;
  rect = viewportRect(v.at("x"), v.at("y"), v.at("width"), v.at("height"), range.at(0), range.at(1), texels.width,
                      texels.height);
  const bool whole = rect.x == 0 && rect.y == 0 && rect.width == texels.width && rect.height == texels.height;
  const std::string sample = sampleText(d, facts);
  fmt::print(log, "  depth: {}; viewport {}x{} at ({}, {}){}{}{}\n", resourceText(d), rect.width, rect.height, rect.x,
             rect.y, whole ? "" : ", cropped to it", facts.applied.rowsBottomUp ? "; rows bottom-up, flipped" : "", sample);
  scene["depth"] = {{"resource", d.at("resource")}, {"id", d.at("id")}, {"format", d.at("format").at("name")},
                    {"mip", d.at("mip")}, {"layer", d.at("layer")}};
  if (d.value("samples", 1) > 1) {
    scene["depth"]["samples"] = d.at("samples");
    scene["depth"]["sample"] = d.at("sample");
  }
  scene["viewport"] = {{"x", rect.x}, {"y", rect.y}, {"width", rect.width}, {"height", rect.height},
                       {"flips_y", rect.flipsY}};
  scene["rows_flipped"] = facts.applied.rowsBottomUp;
  return cropToCapture(depth, texels.width, 1, rect, facts.applied);
}

std::vector<float> importNormals(const json& dump, const fs::path& folder, const FrameFacts& facts,
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
  return cropToCapture(decodeNormals(texels), texels.width, 3, facts.rect, facts.applied);
}

// Whether NDC y = +1 lands on the capture's top row (the format wants -1 there): then the
// projection's y is negated.
bool captureTopIsClipYUp(const FrameFacts& f) {
  const double top = f.applied.rowsBottomUp ? f.rect.y + f.rect.height : f.rect.y;
  const double ndc = 2.0 * (top - double(f.viewport.y)) / double(f.viewport.height) - 1.0;
  return (f.applied.clipOriginUpperLeft ? -ndc : ndc) > 0.0;
}

// The application's view and projection: read apart, or factored from the one combined matrix.
std::pair<glm::mat4, glm::mat4> appMatrices(const json& dump, json& scene, std::FILE* log) {
  if (dump.contains("view_projection")) {
    const json& vp = dump.at("view_projection");
    const FactoredViewProjection f = factorViewProjection(matrixOf(vp), matrixName(vp));
    fmt::print(log, "  view-projection: {}: factored into a perspective projection and a rigid view (residual {:.2g}, "
                    "axes {:.2g} degrees from perpendicular); a rigid model folded into it makes world the object's frame\n",
               matrixText(vp), f.residual, f.skewDegrees);
    scene["view_projection"] = matrixText(vp);
    scene["factoring"] = {{"residual", f.residual}, {"skew_degrees", f.skewDegrees}};
    return {f.view, f.projection};
  }
  const json& v = dump.at("view");
  const json& p = dump.at("projection");
  const std::string viewName = matrixName(v), projectionName = matrixName(p);
  if (viewName == projectionName)
    throw ImportProblem("--projection", fmt::format("--view and --projection both name {}: a combined matrix is "
                                                    "given as --view-projection {} (it is factored into the two); the "
                                                    "blocks at this event hold: {}",
                                                    viewName, viewName, dump.at("blocks").get<std::string>()));
  const glm::mat4 view = matrixOf(v), projection = matrixOf(p);
  checkProjectionMatrix(projection, projectionName);
  checkViewMatrix(view, viewName);
  fmt::print(log, "  view: {}\n  projection: {}\n", matrixText(v), matrixText(p));
  scene["view"] = matrixText(v);
  scene["projection"] = matrixText(p);
  return {view, projection};
}

std::vector<glm::vec4> readCorners(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
  std::vector<glm::vec4> corners(bytes.size() / sizeof(glm::vec4));
  std::memcpy(corners.data(), bytes.data(), corners.size() * sizeof(glm::vec4));
  return corners;
}

// GL projections brought to Vulkan often keep their [-1, 1] depth row and remap clip z in the
// vertex shader (gl_Position.z = (gl_Position.z + gl_Position.w) / 2, as Warzone 2100 does). The
// draw's own vertices tell: the depth row misses their clip z, and the row so remapped meets it.
// Then the projection the draw effectively used, else nullopt.
std::optional<glm::mat4> remappedInVertexShader(const FrameFacts& facts, const glm::mat4& projection) {
  if (facts.applied.clipZMinusOneToOne || facts.corners.empty()) return std::nullopt;
  ApiConventions gl;
  gl.clipZMinusOneToOne = true;
  const glm::mat4 remapped = projectionToWindowDepth(gl, projection);
  if (depthRowResidual(facts.corners, projection) > kSelfCheckMaxDepthRowResidual &&
      depthRowResidual(facts.corners, remapped) <= kSelfCheckMaxDepthRowResidual)
    return remapped;
  return std::nullopt;
}

ImportedCamera importMatrices(const json& dump, FrameFacts& facts, json& scene, std::FILE* log) {
  auto [view, projection] = appMatrices(dump, scene, log);
  const std::optional<glm::mat4> remapped = remappedInVertexShader(facts, projection);
  if (remapped) projection = *remapped;
  facts.appProjection = projection;
  facts.appView = view;
  ImportedCamera camera =
      importCamera(view, projectionToWindowDepth(facts.applied, projection), captureTopIsClipYUp(facts));
  const ApiConventions& c = facts.applied;
  if (c.depthRangeMin != 0.0 || c.depthRangeMax != 1.0)
    camera.adjustments.insert(camera.adjustments.begin(),
                              fmt::format("viewport depth range [{:g}, {:g}]: folded into the projection's depth row",
                                          c.depthRangeMin, c.depthRangeMax));
  if (c.clipZMinusOneToOne)
    camera.adjustments.insert(camera.adjustments.begin(), "clip z in [-1, 1]: projection's depth row mapped to [0, 1]");
  if (remapped)
    camera.adjustments.insert(camera.adjustments.begin(),
                              "the vertex shader maps clip z from [-1, 1] to [0, 1] itself (the draw's vertices say so): "
                              "the projection's depth row is mapped the same way");
  const std::string described = describeProjection(camera.projection, c.depthRangeMin, c.depthRangeMax);
  fmt::print(log, "  camera: {}\n", described);
  for (const std::string& a : camera.adjustments) fmt::print(log, "  adjusted: {}\n", a);
  scene["camera"] = described;
  scene["adjustments"] = camera.adjustments;
  return camera;
}


void printSelfCheck(const SelfCheckResult& r, double seconds, std::FILE* log) {
  fmt::print(log,
             "  self-check: {} vertices ({} on screen), clip z from w within {:.2g}; {} points in {} triangles: {} "
             "match the imported depth, {} hidden by nearer surfaces, {} disagree ({:.2f} s)\n",
             r.vertices, r.verticesOnScreen, r.depthRowResidual, r.points, r.triangles, r.matched, r.hidden,
             r.disagreed, seconds);
}

// No time in it: the same .rdc imports to the same bytes.
json selfCheckJson(const SelfCheckResult& r) {
  return {{"vertices", r.vertices},       {"vertices_on_screen", r.verticesOnScreen},
          {"depth_row_residual", r.depthRowResidual}, {"triangles", r.triangles},
          {"points", r.points},           {"matched", r.matched},
          {"hidden", r.hidden},           {"disagreed", r.disagreed},
          {"worst_difference", r.worstDifference}};
}

void failSelfCheck(const SelfCheckResult& r, const json& dump, const FrameFacts& facts) {
  const bool combined = dump.contains("view_projection");
  const json& p = combined ? dump.at("view_projection") : dump.at("projection");
  if (!r.depthRowPassed())
    throw ImportProblem(combined ? "--view-projection" : "--projection",
                        fmt::format("self-check failed: {} does not give the draw's vertices their clip-space z (largest "
                                    "residual {:.3g} in NDC over {} on-screen vertices, at most {:g}): it is not the "
                                    "{} this draw was rendered with",
                                    matrixName(p), r.depthRowResidual, r.verticesOnScreen, kSelfCheckMaxDepthRowResidual,
                                    combined ? "view-projection" : "projection"));
  const std::string what = fmt::format(
      "the depth's decoding ({} {}), its row order (flipped: {}) or the projection's depth convention (clip z in {}) "
      "does not match this capture",
      facts.applied.api, dump.at("depth").at("format").at("name").get<std::string>(),
      facts.applied.rowsBottomUp ? "yes" : "no", facts.applied.clipZMinusOneToOne ? "[-1, 1]" : "[0, 1]");
  const size_t seen = r.matched + r.disagreed;
  if (seen < kSelfCheckMinPoints)
    throw ImportProblem("--depth", fmt::format("self-check failed: only {} of {} points of the draw's triangles are "
                                               "visible in the imported depth (at least {} needed): either the draw "
                                               "is mostly hidden (choose another --event, or --no-self-check), or {}",
                                               seen, r.points, kSelfCheckMinPoints, what));
  throw ImportProblem("--depth", fmt::format("self-check failed: the imported depth disagrees with what the draw wrote "
                                             "at {} of {} visible points ({:.1f} %, at most {:g} %); worst at pixel ({}, "
                                             "{}): imported {:.6g}, drawn {:.6g}: {}",
                                             r.disagreed, seen, 100.0 * double(r.disagreed) / double(seen),
                                             100.0 * (1.0 - kSelfCheckMinMatchFraction), r.worstX, r.worstY,
                                             r.worstImported, r.worstDrawn, what));
}

// Checks the imported frame against the draw's own vertices (self_check.h); throws when it fails
// or cannot run, unless --no-self-check.
void selfCheck(const json& dump, const FrameFacts& facts, const CaptureFrameData& data,
               const RenderDocImportOptions& o, json& scene, std::FILE* log) {
  if (o.noSelfCheck) {
    fmt::print(log, "  self-check: skipped (--no-self-check)\n");
    scene["self_check"] = {{"skipped", "--no-self-check"}};
    return;
  }
  const json& check = dump.at("self_check");
  if (!check.at("possible").get<bool>())
    throw ImportProblem("--no-self-check",
                        fmt::format("self-check not possible: {}; --no-self-check imports the frame unchecked "
                                    "(capture.json records it)",
                                    check.at("reason").get<std::string>()));
  const auto start = std::chrono::steady_clock::now();
  SelfCheckInput in;
  in.corners = facts.corners;
  in.conventions = facts.conventions;
  in.viewport = facts.viewport;
  in.rect = facts.rect;
  in.depth = &data.gbuffer.depth;
  in.appProjection = facts.appProjection;
  in.captureProjection = data.projection;
  in.depthQuantum = facts.depthQuantum;
  in.samplePosition = facts.samplePosition;
  const SelfCheckResult r = runSelfCheck(in);
  const double seconds = check.at("seconds").get<double>() +
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  printSelfCheck(r, seconds, log);
  scene["self_check"] = selfCheckJson(r);
  if (!r.depthRowPassed() || !r.depthPassed()) failSelfCheck(r, dump, facts);
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
  FrameFacts facts;
  if (dump.contains("depth")) f.data.gbuffer.depth = importDepth(dump, folder, o, facts, s, log);
  if (dump.contains("error")) {
    const json& e = dump["error"];
    throw ImportProblem(e.at("field"), e.at("message"));
  }
  f.data.gbuffer.width = facts.rect.width;
  f.data.gbuffer.height = facts.rect.height;
  f.data.gbuffer.normals = importNormals(dump, folder, facts, o, s, log);
  if (!o.noSelfCheck && dump.contains("self_check") && dump["self_check"].value("possible", false))  // the camera and the check use them
    facts.corners = readCorners(folder / dump.at("self_check").at("file").get<std::string>());
  const ImportedCamera camera = importMatrices(dump, facts, s, log);
  if (o.normalsSpace == "view") viewNormalsToWorld(f.data.gbuffer.normals, facts.appView);
  f.data.view = camera.view;
  f.data.projection = camera.projection;
  selfCheck(dump, facts, f.data, o, s, log);
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
  r.viewProjection = o.viewProjection;
  r.arrayRows = o.arrayMatrix == "rows";
  r.sample = o.sample;
  r.noSelfCheck = o.noSelfCheck;
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
  ScratchFolder work("aoreplay-import");
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
