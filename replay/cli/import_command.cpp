// `aoreplay import renderdoc FILE.rdc...`: a bug frame captured with RenderDoc becomes an aoreplay
// capture (replay/import/, docs/renderdoc.md).
#include <cstdio>
#include <map>
#include <memory>

#include "cli/commands.h"
#include "cli/handlers.h"
#include "core/input_error.h"
#include "cli/number_options.h"
#include "import/renderdoc_import.h"

namespace aor::cli {
namespace {

struct ImportArgs {
  RenderDocImportOptions options;
  std::vector<std::string> files;
  std::string framesFromDir, out, passName;
  int event = -1;
};

int importCommand(ImportArgs& args) {
  RenderDocImportOptions& o = args.options;
  if (o.viewProjection.empty() && (o.view.empty() || o.projection.empty()))
    throw InputError("", std::nullopt, o.view.empty() ? "--view" : "--projection",
                     "the camera is --view BLOCK.member with --projection BLOCK.member, or --view-projection BLOCK.member");
  o.files.assign(args.files.begin(), args.files.end());
  if (!args.framesFromDir.empty()) o.framesFromDir = args.framesFromDir;
  o.out = args.out;
  if (args.event >= 0) o.event = args.event;
  if (!args.passName.empty()) o.passName = args.passName;
  importRenderDoc(o, stdout);
  return kExitOk;
}

}  // namespace

void registerImportCommand(CLI::App& app) {
  auto args = std::make_shared<ImportArgs>();
  auto* cmd = app.add_subcommand("import", "make a capture from another tool's frame capture");
  cmd->require_subcommand(1);
  auto* rd = cmd->add_subcommand("renderdoc", "import the depth, normals and camera of one draw per RenderDoc capture");
  RenderDocImportOptions& o = args->options;
  rd->add_option("files", args->files, "RenderDoc captures (.rdc), one frame each, in file-name order");
  rd->add_option("--out", args->out, "capture folder to write")->required();
  auto* event = rd->add_option("--event", args->event, "event ID to import (default: the last draw with a depth target)")
                    ->check(wholeIn(0, 2147483647));
  rd->add_option("--pass", args->passName, "the last draw with a depth target inside this marker region")
      ->excludes(event);
  rd->add_option("--depth", o.depth, "auto, or the depth texture (RenderDoc's name, ResourceId::N or N)")
      ->capture_default_str();
  rd->add_option("--normals", o.normals, "the normal target (name or ID), or none")->capture_default_str();
  rd->add_option("--normals-space", o.normalsSpace, "world | view: the space the normal target holds")
      ->check(CLI::IsMember({"world", "view"}))
      ->capture_default_str();
  auto* view = rd->add_option("--view", o.view,
                              "world -> view matrix: BLOCK.member of a uniform or push-constant block, or BLOCK.member[I] "
                              "(four vec4 elements from I)");
  auto* projection = rd->add_option("--projection", o.projection, "view -> clip matrix, named as --view");
  auto* combined = rd->add_option("--view-projection", o.viewProjection,
                                  "instead of --view and --projection: their product (P.V, or P.V.M with a rigid model), "
                                  "factored exactly into a perspective projection and a rigid view");
  combined->excludes(view)->excludes(projection);
  rd->add_option("--sample", o.sample, "of multisampled depth (and normals), the sample to import (default 0)")
      ->check(wholeIn(0, 63));
  rd->add_option("--array-matrix", o.arrayMatrix, "BLOCK.member[I]: the four elements are the matrix's columns or its rows")
      ->check(CLI::IsMember({"columns", "rows"}))
      ->capture_default_str();
  rd->add_option("--frames-from-dir", args->framesFromDir, "every .rdc in this folder, one frame each");
  rd->add_flag("--no-self-check", o.noSelfCheck,
              "import without checking the frame against the draw's own vertices (capture.json records it)");
  // Tests only: a mistake made on purpose, to show that the self-check catches it (hidden from --help).
  rd->add_option("--test-only-fault", o.fault)
      ->transform(CLI::CheckedTransformer(std::map<std::string, ImportFault>{
          {"rows", ImportFault::RowsUnflipped}, {"d24-low-bits", ImportFault::D24LowBits},
          {"clip-z", ImportFault::ClipZAsZeroToOne}}))
      ->group("");
  rd->add_option("--renderdoc-python", o.renderdocPython,
                 "folder holding renderdoc.so of a RenderDoc build (default: Debian's python3-renderdoc)");
  handlers()["import"] = [args] { return importCommand(*args); };
}

}  // namespace aor::cli
