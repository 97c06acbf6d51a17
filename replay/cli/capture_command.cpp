// `aoreplay capture`: generate a synthetic capture (format v1) with Embree-traced G-buffers and,
// optionally, a ray-traced reference.
#include <unistd.h>

#include <memory>

#include <fmt/format.h>

#include "core/input_error.h"
#include "cli/commands.h"
#include "cli/handlers.h"
#include "cli/number_options.h"
#include "options/progress.h"
#include "generator/generator.h"
#include "options/size.h"

namespace aor::cli {
namespace {

struct CaptureArgs {
  gen::GeneratorOptions options;
  std::string out;
  std::string size = "320x180";
  float radius = 0.0f;
  bool noNormals = false;
  CLI::Option* separation = nullptr;  // --depth2-separation, to tell it was given
};

int captureCommand(CaptureArgs& args) {
  auto& o = args.options;
  std::tie(o.width, o.height) = parseSize(args.size, "--size");
  if (args.radius > 0.0f) o.radius = args.radius;
  o.writeNormals = !args.noNormals;
  // A separation without a second layer would be silently ignored.
  if (args.separation->count() > 0 && !o.depth2)
    throw InputError("", std::nullopt, "--depth2-separation", "applies to the second depth layer; add --depth2");
  // A bar on a terminal, a line every few seconds off one (options/progress.h): ray-traced
  // references take seconds a frame.
  o.progress = progressCallback("capture", "frames");
  gen::generateCapture(o, args.out);
  fmt::print("capture: {} ({} {}x{}, {} frames, path {}, reference spp {}{})\n", args.out, o.scene, o.width, o.height,
             o.frames, o.path, o.referenceSpp,
             o.depth2 ? fmt::format(", depth2 separation {}", o.depth2Separation) : std::string());
  return kExitOk;
}

}  // namespace

void registerCaptureCommand(CLI::App& app) {
  auto args = std::make_shared<CaptureArgs>();
  auto* cmd = app.add_subcommand("capture", "generate a synthetic capture (Embree ray traced)");
  cmd->add_option("scene", args->options.scene, "plane | pit | sphere | boxes | bunny | thin")->required();
  cmd->add_option("--out", args->out, "capture folder to write")->required();
  cmd->add_option("--size", args->size, "WxH")->capture_default_str();
  cmd->add_option("--frames", args->options.frames, "number of frames")->check(wholeIn(1, 100000))->capture_default_str();
  cmd->add_option("--path", args->options.path, "orbit | dolly | static | cut | strafe")->capture_default_str();
  cmd->add_option("--reference-spp", args->options.referenceSpp, "reference rays per pixel (0: no reference)")
      ->check(wholeIn(0, 1 << 20))
      ->capture_default_str();
  cmd->add_option("--radius", args->radius, "AO radius in world units (default: the scene's)");
  cmd->add_flag("--reversed-z", args->options.reversedZ, "reversed depth (near 1, far 0)");
  cmd->add_flag("--infinite-far", args->options.infiniteFar, "infinite far plane");
  cmd->add_flag("--no-normals", args->noNormals, "depth-only capture (normals reconstructed on replay)");
  cmd->add_flag("--depth2", args->options.depth2, "also write a second depth layer (depth2), by depth peeling");
  args->separation = cmd->add_option("--depth2-separation", args->options.depth2Separation,
                   "world units a second-layer surface lies at least behind layer 0 along the ray")
      ->capture_default_str();
  cmd->add_option("--fov", args->options.verticalFovDegrees, "vertical field of view, degrees")->check(numberIn(0.5, 179.0))->capture_default_str();
  cmd->add_option("--seed", args->options.seed, "seed of the reference sampling")->capture_default_str();
  handlers()["capture"] = [args] { return captureCommand(*args); };
}

}  // namespace aor::cli
