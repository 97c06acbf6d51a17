#include "techniques/user/user_header.h"

#include <cstring>

#include <fmt/format.h>

#include "core/plain_text.h"

namespace aor {
namespace {

const char* inputDoc(const std::string& name) {
  if (name == "depth") return "the capture's raw depth (.r)";
  if (name == "linear_depth") return "positive view-space distance along -Z (.r), 0 for sky";
  if (name == "view_normals") return "view-space unit normals (.xyz): rotated from the capture's, or reconstructed from depth";
  if (name == "history") return "this technique's final visibility of the previous frame (.r); 1.0 where frame.history_valid is 0";
  return "written by an earlier pass";
}

std::string paramDecl(const Parameter& p) {
  switch (p.type) {
    case ParameterType::Float: return fmt::format("  float {};  // {}, [{}, {}]", p.key, p.doc.empty() ? "float" : p.doc, valueText(p, p.min), valueText(p, p.max));
    case ParameterType::Int: return fmt::format("  int {};  // {}, [{}, {}]", p.key, p.doc.empty() ? "int" : p.doc, valueText(p, p.min), valueText(p, p.max));
    case ParameterType::Bool: return fmt::format("  int {};  // {}bool: 0 or 1", p.key, p.doc.empty() ? "" : p.doc + "; ");
    case ParameterType::Enum: {
      std::vector<std::string> items;
      for (size_t i = 0; i < p.choices.size(); ++i) items.push_back(fmt::format("{} = {}", i, p.choices[i]));
      return fmt::format("  int {};  // {}enum: {}", p.key, p.doc.empty() ? "" : p.doc + "; ", fmt::join(items, ", "));
    }
  }
  return "";
}

const UserImageWrite& writeOf(const UserTechniqueSpec& spec, const std::string& image) { return *spec.write(image); }

}  // namespace

std::vector<UserBinding> userPassBindings(const UserTechniqueSpec& spec, const UserPass& pass) {
  std::vector<UserBinding> out{{UserBinding::Kind::Frame, ""}};
  if (!spec.parameters.empty()) out.push_back({UserBinding::Kind::Params, ""});
  for (const auto& r : pass.reads) out.push_back({UserBinding::Kind::Read, r});
  for (const auto& w : pass.writes) out.push_back({UserBinding::Kind::Write, w.name});
  return out;
}

std::string userPassHeader(const UserTechniqueSpec& spec, const UserPass& pass) {
  std::string h;
  h += fmt::format("// aoreplay.glsl: generated for pass '{}' of technique '{}' ({}).\n", pass.name, spec.name, printable(spec.display));
  h += "// `aoreplay technique-header FILE.json PASS` prints it; user_techniques/FORMAT.md documents it.\n";
  h += "#ifndef AOREPLAY_GLSL\n#define AOREPLAY_GLSL\n\n";
  h += fmt::format("// One invocation per pixel of '{}' ({} scale), in whole workgroups: return where\n", pass.writes[0].name,
                   pass.writes[0].half ? "half" : "full");
  h += "// gl_GlobalInvocationID.xy is outside frame.size.\n";
  h += fmt::format("layout(local_size_x = {}, local_size_y = {}, local_size_z = 1) in;\n\n", pass.workgroup[0], pass.workgroup[1]);
  uint32_t binding = 0;
  for (const auto& b : userPassBindings(spec, pass)) {
    switch (b.kind) {
      case UserBinding::Kind::Frame:
        h += fmt::format(
            "layout(set = 0, binding = {}, std140) uniform AoreplayFrame {{\n"
            "  mat4 view;                  // world to view\n"
            "  mat4 projection;            // view to clip (the capture's)\n"
            "  mat4 inv_projection;        // clip to view\n"
            "  mat4 prev_view_projection;  // last frame's projection * view (this frame's when history_valid is 0)\n"
            "  vec2 size;                  // this pass's output size in pixels\n"
            "  vec2 inv_size;              // 1 / size\n"
            "  uint frame_index;           // the frame's index in the capture (for noise)\n"
            "  uint history_valid;         // 1 when in_history holds last frame's result\n"
            "  float radius;               // the run's AO radius in world units\n"
            "}} frame;\n\n",
            binding);
        break;
      case UserBinding::Kind::Params: {
        h += fmt::format("layout(set = 0, binding = {}, std140) uniform AoreplayParams {{\n", binding);
        for (const auto& p : spec.parameters) h += paramDecl(p) + "\n";
        h += "} params;\n\n";
        break;
      }
      case UserBinding::Kind::Read:
        h += fmt::format("layout(set = 0, binding = {}) uniform sampler2D in_{};  // {}; nearest, clamp to edge{}\n", binding, b.image,
                         inputDoc(b.image),
                         spec.write(b.image) ? fmt::format(" ({}, {} scale)", writeOf(spec, b.image).formatName,
                                                           writeOf(spec, b.image).half ? "half" : "full")
                                             : "");
        break;
      case UserBinding::Kind::Write: {
        const auto& w = writeOf(spec, b.image);
        h += fmt::format("layout(set = 0, binding = {}, {}) uniform writeonly image2D out_{};  // {} scale{}\n", binding, w.formatName,
                         w.name, w.half ? "half" : "full", w.name == spec.output ? "; the technique's output: visibility in .r" : "");
        break;
      }
    }
    ++binding;
  }
  h += "\n#endif\n";
  return h;
}

std::vector<uint32_t> userParamsBlock(const UserTechniqueSpec& spec, const std::vector<double>& values) {
  std::vector<uint32_t> words((spec.parameters.size() + 3) / 4 * 4, 0u);
  for (size_t i = 0; i < spec.parameters.size(); ++i) {
    if (spec.parameters[i].type == ParameterType::Float) {
      float f = float(values[i]);
      std::memcpy(&words[i], &f, 4);
    } else {
      int32_t v = int32_t(values[i]);
      std::memcpy(&words[i], &v, 4);
    }
  }
  return words;
}

}  // namespace aor
