#include "techniques/user/user_technique.h"

#include <functional>
#include <map>
#include <memory>
#include <mutex>

#include <fmt/format.h>

#include "shared_passes/shared_passes.h"
#include "core/input_error.h"
#include "runtime/pass_context.h"
#include "techniques/registry.h"
#include "techniques/user/shader_compiler.h"
#include "techniques/user/user_header.h"
#include "techniques/user/user_technique_spec.h"
#include "vk/context.h"
#include "vk/device_limits.h"
#include "vk/op_counter.h"
#include "vk/shader_reflection.h"

namespace aor {
namespace fs = std::filesystem;
namespace {

constexpr const char* kHistoryBase = "user_history";
constexpr double kTemporalDenoiseDefault = 0.9;  // gtao's

struct UserTechnique {
  UserTechniqueSpec spec;
  std::vector<std::vector<uint32_t>> spirv;  // per pass
  std::vector<std::string> pipelineNames;   // per pass, unique in the process
  // Per pass, the counting build (vk/op_counter.h), compiled the first time a counted replay runs it.
  mutable std::mutex countingMutex;
  mutable std::map<size_t, std::vector<uint32_t>> countingSpirv;
  ShaderCode countingCode(size_t pass) const {
    std::lock_guard lock(countingMutex);
    auto [it, fresh] = countingSpirv.try_emplace(pass);
    if (fresh) it->second = compileUserPass(spec, pass, true).spirv;
    return {pipelineNames[pass] + std::string(kCountingBuildSuffix), it->second};
  }
  Technique technique;
};

bool readsHistory(const UserTechniqueSpec& spec) {
  for (const auto& p : spec.passes)
    for (const auto& r : p.reads)
      if (r == "history") return true;
  return false;
}

glm::uvec2 sizeOf(const FrameBuilder& frame, const UserImageWrite& w) {
  glm::uvec2 full = frame.size();
  return w.half ? (full + 1u) / 2u : full;
}

// `linear_depth`: the front's distance with sky as 0.
graph::ResourceId addLinearDepthPass(FrameBuilder& frame) {
  auto distance = frame.linearDistance();
  auto out = frame.graph().createImage("linear_depth", {frame.size().x, frame.size().y, VK_FORMAT_R32_SFLOAT});
  auto& pipelines = frame.pipelines();
  glm::uvec2 size = frame.size();
  frame.graph().addPass(
      "linear_depth",
      [&](graph::PassBuilder& b) {
        b.read(distance, graph::Access::StorageRead);
        b.write(out);
      },
      [&pipelines, distance, out, size](graph::PassContext& ctx) {
        dispatchCompute(ctx, pipelines.get("user/linear_depth"), {distance, out}, nullptr, size.x, size.y);
      });
  return out;
}

// Copies this frame's final visibility into the history image next frame reads: nothing reads it
// this frame, so the pass is a root, or the graph would cull it.
void addHistoryCopyPass(graph::RenderGraph& graph, graph::ResourceId from, graph::ResourceId to) {
  graph.addPass(
      "history_copy",
      [&](graph::PassBuilder& b) {
        b.read(from, graph::Access::TransferRead);
        b.write(to, graph::Access::TransferWrite);
        b.sideEffect();
      },
      [from, to](graph::PassContext& ctx) {
        const auto& src = ctx.image(from);
        VkImageCopy region{};
        region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.dstSubresource = region.srcSubresource;
        region.extent = {src.width, src.height, 1};
        vkCmdCopyImage(ctx.cmd, src.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, ctx.image(to).image,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
      });
}

UserFrameBlock frameBlock(const FrameBuilder& frame, const Settings& settings, glm::uvec2 size) {
  const auto& cam = frame.camera();
  UserFrameBlock b;
  b.view = cam.view;
  b.projection = cam.projection;
  b.invProjection = glm::inverse(cam.projection);
  const auto& prev = frame.historyValid() ? frame.previousCamera() : cam;
  b.prevViewProjection = prev.projection * prev.view;
  b.size = glm::vec2(size);
  b.invSize = 1.0f / glm::vec2(size);
  b.frameIndex = cam.frameIndex;
  b.historyValid = frame.historyValid() ? 1u : 0u;
  b.radius = settings.f(kRadiusKey);
  return b;
}

struct History {
  graph::ResourceId read = graph::kNoResource;     // what `history` binds
  graph::ResourceId current = graph::kNoResource;  // where the final visibility goes (kNoResource: nowhere)
};

History declareHistory(FrameBuilder& frame, VkFormat format) {
  History h;
  graph::ImageDesc desc{frame.size().x, frame.size().y, format};
  if (frame.historyWanted()) {
    auto pair = frame.history(kHistoryBase, desc);
    h.current = pair.current;
    h.read = pair.previous;
  }
  if (h.read == graph::kNoResource) {
    h.read = frame.graph().createImage("history_invalid", desc);
    shared_passes::addFillPass(frame.graph(), h.read, 1.0f);
  }
  return h;
}

// The uniform buffers of one frame: each pass's `frame` block and the `params` block.
struct Constants {
  std::vector<graph::ResourceId> frameBlocks;  // per pass
  graph::ResourceId params = graph::kNoResource;
};

// Fills the blocks with vkCmdUpdateBuffer: recorded into the frame's command buffer, so frames in
// flight never share them; a block whose pass is culled is neither written nor allocated.
Constants addConstantsPass(FrameBuilder& frame, const Settings& settings, const UserTechniqueSpec& spec) {
  auto& g = frame.graph();
  std::vector<double> values;
  for (const auto& p : spec.parameters) values.push_back(settings.value(p.key));
  auto params = std::make_shared<std::vector<uint32_t>>(userParamsBlock(spec, values));
  Constants c;
  if (!spec.parameters.empty()) c.params = g.createBuffer("params", {params->size() * 4});
  std::vector<std::pair<graph::ResourceId, UserFrameBlock>> blocks;
  for (const auto& pass : spec.passes) {
    c.frameBlocks.push_back(g.createBuffer(pass.name + ".frame", {sizeof(UserFrameBlock)}));
    blocks.emplace_back(c.frameBlocks.back(), frameBlock(frame, settings, sizeOf(frame, pass.writes[0])));
  }
  g.addPass(
      "constants",
      [&](graph::PassBuilder& b) {
        for (const auto& [id, block] : blocks) b.writeIfRead(id, graph::Access::ClearWrite);
        if (c.params != graph::kNoResource) b.writeIfRead(c.params, graph::Access::ClearWrite);
      },
      [blocks, paramsBuffer = c.params, params](graph::PassContext& ctx) {
        for (const auto& [id, block] : blocks)
          if (ctx.has(id)) vkCmdUpdateBuffer(ctx.cmd, ctx.buffer(id).buffer, 0, sizeof(block), &block);
        if (paramsBuffer != graph::kNoResource && ctx.has(paramsBuffer))
          vkCmdUpdateBuffer(ctx.cmd, ctx.buffer(paramsBuffer).buffer, 0, params->size() * 4, params->data());
      });
  return c;
}

// One pass of the file: its resources bound in the generated header's order, one invocation per
// pixel of its first write.
void addUserPass(FrameBuilder& frame, const UserTechnique& ut, size_t p, const Constants& constants,
                 const std::map<std::string, graph::ResourceId>& images,
                 const std::function<graph::ResourceId(const std::string&)>& input) {
  const UserPass& pass = ut.spec.passes[p];
  std::vector<Bind> binds;
  for (const auto& b : userPassBindings(ut.spec, pass)) {
    switch (b.kind) {
      case UserBinding::Kind::Frame: binds.emplace_back(constants.frameBlocks[p]); break;
      case UserBinding::Kind::Params: binds.emplace_back(constants.params); break;
      case UserBinding::Kind::Read: binds.emplace_back(input(b.image)); break;
      case UserBinding::Kind::Write: binds.emplace_back(images.at(b.image)); break;
    }
  }
  glm::uvec2 size = sizeOf(frame, pass.writes[0]);
  ShaderCode code{ut.pipelineNames[p], ut.spirv[p]};
  auto& pipelines = frame.pipelines();
  frame.graph().addPass(
      pass.name,
      [&](graph::PassBuilder& b) {
        b.read(constants.frameBlocks[p], graph::Access::UniformRead);
        if (constants.params != graph::kNoResource) b.read(constants.params, graph::Access::UniformRead);
        for (const auto& r : pass.reads) b.read(input(r));
        for (const auto& w : pass.writes) b.write(images.at(w.name));
      },
      [&pipelines, &ut, p, code, binds, size](graph::PassContext& ctx) {
        const auto& pipeline = pipelines.get(ctx.vk.opCounter ? ut.countingCode(p) : code);
        dispatchCompute(ctx, pipeline, binds, nullptr, 0, groupsFor(pipeline, size.x, size.y));
      });
}

void addUserPasses(const UserTechnique& ut, FrameBuilder& frame, const Settings& settings) {
  const UserTechniqueSpec& spec = ut.spec;
  auto& g = frame.graph();
  std::map<std::string, graph::ResourceId> images;
  const UserImageWrite& output = *spec.write(spec.output);
  const bool seed000 = spec.denoise == UserDenoise::Seed000;
  History history;
  if (readsHistory(spec)) history = declareHistory(frame, output.format);

  // The technique's own images; the output is the history's current image when nothing follows it.
  for (const auto& pass : spec.passes)
    for (const auto& w : pass.writes) {
      glm::uvec2 size = sizeOf(frame, w);
      bool intoHistory = w.name == spec.output && !seed000 && history.current != graph::kNoResource;
      images[w.name] = intoHistory ? history.current : g.createImage(w.name, {size.x, size.y, w.format});
    }
  auto input = [&](const std::string& name) {
    if (auto it = images.find(name); it != images.end()) return it->second;
    graph::ResourceId id = name == "depth"          ? frame.depth()
                           : name == "view_normals" ? frame.viewNormals()
                           : name == "history"      ? history.read
                                                    : addLinearDepthPass(frame);
    images[name] = id;
    return id;
  };

  Constants constants = addConstantsPass(frame, settings, spec);
  for (size_t p = 0; p < spec.passes.size(); ++p) addUserPass(frame, ut, p, constants, images, input);
  for (const auto& pass : spec.passes)
    for (const auto& w : pass.writes) frame.debugView(w.name, images.at(w.name));

  graph::ResourceId final = images.at(spec.output);
  if (seed000) {
    shared_passes::DenoiseInput in{final, false, 1};
    in.ao = shared_passes::addSpatialDenoise(frame, in);
    final = shared_passes::addTemporalDenoise(frame, in);
    if (history.current != graph::kNoResource) addHistoryCopyPass(g, final, history.current);
  }
  frame.setOutput(final, OutputLayout::visibilityOnly());
}

HistoryNeeds userHistory(const UserTechniqueSpec& spec, const Settings& settings) {
  HistoryNeeds needs;
  if (spec.denoise == UserDenoise::Seed000) needs = shared_passes::temporalDenoiseHistory(settings);
  if (readsHistory(spec)) {
    needs.keeps = true;
    needs.whyNot.clear();
  } else if (!needs.keeps && needs.whyNot.empty()) {
    needs.whyNot = "no pass reads history";
  }
  return needs;
}

// Every pass's shader against the device's limits, and the params block against its uniform range.
void checkUserDeviceLimits(const UserTechnique& ut, const DeviceInfo& device) {
  const UserTechniqueSpec& spec = ut.spec;
  const uint64_t paramsBytes = spec.parameters.empty() ? 0 : userParamsBlock(spec, std::vector<double>(spec.parameters.size())).size() * 4;
  for (size_t p = 0; p < spec.passes.size(); ++p) {
    const UserPass& pass = spec.passes[p];
    std::optional<std::string> exceeded = exceededLimit(reflectComputeShader(ut.spirv[p], pass.name), {pass.workgroup[0], pass.workgroup[1], 1},
                                                        device.limits);
    if (!exceeded && paramsBytes > device.limits.maxUniformBufferRange)
      exceeded = fmt::format("a params block of {} bytes (the device's uniform range is {})", paramsBytes, device.limits.maxUniformBufferRange);
    if (exceeded)
      throw InputError(spec.display, std::nullopt, fmt::format("passes[{}]", p),
                       fmt::format("pass '{}' needs {} on device '{}'", pass.name, *exceeded, device.name));
  }
}

Technique makeTechnique(const UserTechnique& ut) {
  const UserTechniqueSpec& spec = ut.spec;
  Technique t;
  t.name = spec.name;
  t.file = spec.display;
  t.seed = "";
  t.summary = fmt::format("user technique from {} ({} pass{}{})", spec.display, spec.passes.size(),
                          spec.passes.size() == 1 ? "" : "es", spec.denoise == UserDenoise::Seed000 ? ", then seed 000's denoisers" : "");
  t.parameters.push_back(radiusParameter(1.0));
  for (const auto& p : spec.parameters) t.parameters.push_back(p);
  if (spec.denoise == UserDenoise::Seed000) {
    t.parameters.push_back(shared_passes::spatialParameter());
    t.parameters.push_back(shared_passes::temporalParameter(kTemporalDenoiseDefault));
  }
  t.presets = spec.presets;
  t.defaultPreset = spec.defaultPreset;
  for (const auto& pass : spec.passes)
    for (const auto& w : pass.writes)
      t.debugViews.push_back({w.name, fmt::format("written by pass {} ({}, {} scale)", pass.name, w.formatName, w.half ? "half" : "full")});
  t.addPasses = [&ut](FrameBuilder& frame, const Settings& settings) { addUserPasses(ut, frame, settings); };
  t.history = [&ut](const Settings& settings) { return userHistory(ut.spec, settings); };
  t.checkDeviceLimits = [&ut](const DeviceInfo& device) { checkUserDeviceLimits(ut, device); };
  if (spec.denoise == UserDenoise::Seed000 && !readsHistory(spec))
    t.withoutHistory = shared_passes::withoutTemporalDenoise;
  return t;
}

// Loaded techniques by canonical path: a sweep naming one file twice gets one technique.
std::map<std::string, std::unique_ptr<UserTechnique>>& loaded() {
  static std::map<std::string, std::unique_ptr<UserTechnique>> all;
  return all;
}

std::string canonicalKey(const std::string& path) {
  std::error_code ec;
  fs::path c = fs::weakly_canonical(fs::absolute(path), ec);
  return ec ? fs::absolute(path).lexically_normal().string() : c.string();
}

}  // namespace

bool isTechniquePath(std::string_view value) {
  return value.find('/') != std::string_view::npos || (value.size() >= 5 && value.substr(value.size() - 5) == ".json");
}

const Technique& loadUserTechnique(const std::string& path) {
  static std::mutex mutex;
  std::lock_guard lock(mutex);
  const std::string key = canonicalKey(path);
  if (auto it = loaded().find(key); it != loaded().end()) return it->second->technique;
  auto ut = std::make_unique<UserTechnique>();
  ut->spec = loadUserTechniqueSpec(path, path);
  for (const auto* t : userTechniques())
    if (t->name == ut->spec.name)
      throw InputError(path, std::nullopt, "name",
                       fmt::format("'{}' is already the name of {}", t->name,
                                   t->file.empty() ? std::string("a built-in technique") : "the technique of " + t->file));
  for (size_t p = 0; p < ut->spec.passes.size(); ++p) {
    ut->spirv.push_back(compileUserPass(ut->spec, p).spirv);
    ut->pipelineNames.push_back(fmt::format("user:{}#{}/{}", ut->spec.name, loaded().size(), ut->spec.passes[p].name));
  }
  ut->technique = makeTechnique(*ut);
  registerTechnique(&ut->technique);
  return loaded().emplace(key, std::move(ut)).first->second->technique;
}

std::string userTechniqueHeader(const std::string& path, const std::string& pass) {
  UserTechniqueSpec spec = loadUserTechniqueSpec(path, path);
  const UserPass* p = spec.pass(pass);
  if (!p) {
    std::vector<std::string> names;
    for (const auto& q : spec.passes) names.push_back(q.name);
    throw InputError(path, std::nullopt, "passes", fmt::format("no pass '{}' (passes: {})", pass, fmt::join(names, ", ")));
  }
  return userPassHeader(spec, *p);
}

}  // namespace aor
