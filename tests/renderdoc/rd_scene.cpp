// rd_scene: the small Vulkan program the RenderDoc import is tested with. It rasterises the known
// scene of scene.h, captures each frame through RenderDoc's in-application API (librenderdoc.so,
// loaded before the Vulkan instance exists so that its layer hooks the instance), and writes its
// own read-back beside the captures:
//   CAPTURE_DIR/NNNN.rdc        RenderDoc capture of frame N
//   READBACK_DIR/NNNN.depth     the depth attachment as floats (width*height, little-endian)
//   READBACK_DIR/NNNN.normals   the RGBA16F normal target's bits (width*height*4 halves)
//   READBACK_DIR/NNNN.json      width, height, depth format, view and projection (column-major)
// Usage: rd_scene --depth-format d16|x8d24|d24s8|d32|d32s8 [--reversed] [--size WxH] [--frames N]
//                 [--capture-dir DIR] --readback-dir DIR [--validate]
//                 [--camera separate|combined|model-folded|columns|push-constants] [--stripped-names]
//                 [--samples N] [--final-composite] [--gl-depth-row] [--depth-range MIN,MAX]
// --samples renders a multisampled G-buffer; the read-back is then its sample 0 (depth, by a
// depth resolve) and the average (normals). --final-composite adds a last draw to the G-buffer pass
// with depth test, depth writes and colour writes off. --gl-depth-row holds GL's depth row in
// camera.projection and maps clip z to [0, 1] in the vertex shader (the read-back's projection is
// the Vulkan one the draw ends up with); --depth-range sets the viewport's depth range.
// --camera picks which copy of the camera positions the vertices (shaders/scene.vert; all are
// filled); --stripped-names draws with the vertex shader's SPIR-V names stripped.
// Without --capture-dir nothing is captured (RenderDoc is not loaded); --validate then runs the
// program under the Khronos validation layer and fails on any message.
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <renderdoc_app.h>

#include <nlohmann/json.hpp>

#include "scene_renderer.h"
#include "test_program_support.h"

namespace fs = std::filesystem;
using namespace aor::rdtest;

namespace {

struct Options {
  RenderOptions render;
  std::string depthFormatName = "d32";
  int frames = 1;
  fs::path captureDir, readbackDir;
};

[[noreturn]] void usage(const std::string& problem) {
  std::fprintf(stderr, "rd_scene: %s\n", problem.c_str());
  std::exit(2);
}

Options parseOptions(int argc, char** argv) {
  static const std::map<std::string, VkFormat> formats = {{"d16", VK_FORMAT_D16_UNORM},
                                                          {"x8d24", VK_FORMAT_X8_D24_UNORM_PACK32},
                                                          {"d24s8", VK_FORMAT_D24_UNORM_S8_UINT},
                                                          {"d32", VK_FORMAT_D32_SFLOAT},
                                                          {"d32s8", VK_FORMAT_D32_SFLOAT_S8_UINT}};
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(a + " needs a value");
      return argv[++i];
    };
    if (a == "--depth-format") {
      o.depthFormatName = value();
      if (!formats.count(o.depthFormatName)) usage("unknown depth format " + o.depthFormatName);
    } else if (a == "--reversed") {
      o.render.reversed = true;
    } else if (a == "--size") {
      if (std::sscanf(value().c_str(), "%dx%d", &o.render.width, &o.render.height) != 2) usage("--size is WxH");
    } else if (a == "--frames") {
      o.frames = std::atoi(value().c_str());
    } else if (a == "--capture-dir") {
      o.captureDir = value();
    } else if (a == "--readback-dir") {
      o.readbackDir = value();
    } else if (a == "--validate") {
      o.render.validate = true;
    } else if (a == "--camera") {
      static const std::map<std::string, int> layouts = {
          {"separate", 0}, {"combined", 1}, {"model-folded", 2}, {"columns", 3}, {"push-constants", 4}};
      const std::string layout = value();
      if (!layouts.count(layout)) usage("--camera is separate, combined, model-folded, columns or push-constants");
      o.render.cameraLayout = layouts.at(layout);
    } else if (a == "--samples") {
      o.render.samples = std::atoi(value().c_str());
      if (o.render.samples != 1 && o.render.samples != 2 && o.render.samples != 4 && o.render.samples != 8)
        usage("--samples is 1, 2, 4 or 8");
    } else if (a == "--gl-depth-row") {
      o.render.glDepthRow = true;
    } else if (a == "--depth-range") {
      if (std::sscanf(value().c_str(), "%f,%f", &o.render.minDepth, &o.render.maxDepth) != 2) usage("--depth-range is MIN,MAX");
    } else if (a == "--final-composite") {
      o.render.finalComposite = true;
    } else if (a == "--stripped-names") {
      o.render.strippedNames = true;
    } else {
      usage("unknown argument " + a);
    }
  }
  if (o.readbackDir.empty()) usage("--readback-dir is required");
  if (o.frames < 1 || o.render.width < 1 || o.render.height < 1) usage("bad --frames or --size");
  o.render.depthFormat = formats.at(o.depthFormatName);
  return o;
}

// RenderDoc's in-application API, from the library the Vulkan layer also loads.
RENDERDOC_API_1_6_0* loadRenderDoc() {
  setenv("ENABLE_VULKAN_RENDERDOC_CAPTURE", "1", 1);
  void* library = dlopen("librenderdoc.so", RTLD_NOW | RTLD_GLOBAL);
  if (!library) usage(std::string("cannot load librenderdoc.so (Debian: librenderdoc): ") + dlerror());
  auto getApi = reinterpret_cast<pRENDERDOC_GetAPI>(dlsym(library, "RENDERDOC_GetAPI"));
  RENDERDOC_API_1_6_0* api = nullptr;
  if (!getApi || !getApi(eRENDERDOC_API_Version_1_6_0, reinterpret_cast<void**>(&api)) || !api)
    usage("librenderdoc.so has no usable RENDERDOC_GetAPI 1.6.0");
  return api;
}


}  // namespace

int main(int argc, char** argv) {
  const Options o = parseOptions(argc, argv);
  RENDERDOC_API_1_6_0* api = nullptr;
  try {
    fs::create_directories(o.readbackDir);
    if (!o.captureDir.empty()) {
      fs::create_directories(o.captureDir);
      api = loadRenderDoc();
      api->SetCaptureFilePathTemplate((o.captureDir / "rd_scene").c_str());
    }
    SceneRenderer renderer(o.render);
    for (int frame = 0; frame < o.frames; ++frame) {
      const Camera camera = sceneCamera(frame, o.render.width, o.render.height, o.render.reversed);
      void* device = RENDERDOC_DEVICEPOINTER_FROM_VKINSTANCE(renderer.instance());
      if (api) api->StartFrameCapture(device, nullptr);
      FrameReadback readback = renderer.renderFrame(camera);
      char stem[16];
      std::snprintf(stem, sizeof stem, "%04d", frame);
      if (api) {
        if (!api->EndFrameCapture(device, nullptr)) usage("RenderDoc did not end the frame capture");
        moveNewestCapture(api, o.captureDir / (std::string(stem) + ".rdc"));
      }
      writeBinary(o.readbackDir / (std::string(stem) + ".depth"), readback.depth);
      writeBinary(o.readbackDir / (std::string(stem) + ".normals"), readback.normalsHalf);
      nlohmann::json meta = {{"width", o.render.width},         {"height", o.render.height},
                             {"depth_format", o.depthFormatName}, {"reversed", o.render.reversed},
                             {"view", matrixJson(camera.view)},  {"projection", matrixJson(camera.projection)},
                             {"model", matrixJson(sceneModel())}};
      std::ofstream(o.readbackDir / (std::string(stem) + ".json")) << meta.dump(2) << "\n";
    }
    if (renderer.validationMessages()) {
      std::fprintf(stderr, "rd_scene: %zu validation message(s)\n", renderer.validationMessages());
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rd_scene: %s\n", e.what());
    return 1;
  }
  return 0;
}
