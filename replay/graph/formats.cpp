// Formats, access → synchronisation state mapping and the names used in reports.
#include <algorithm>
#include <array>
#include <cstdio>
#include <string>

#include <fmt/format.h>

#include "graph/render_graph.h"

namespace aor::graph {
namespace {

struct FormatInfo {
  VkFormat format;
  uint32_t bytes;
  const char* name;
};

#define AOR_FORMAT(fmt, bytes) FormatInfo{VK_FORMAT_##fmt, bytes, #fmt}
constexpr std::array kFormats = {
    AOR_FORMAT(R8_UNORM, 1),
    AOR_FORMAT(R8_SNORM, 1),
    AOR_FORMAT(R8_UINT, 1),
    AOR_FORMAT(R8_SINT, 1),
    AOR_FORMAT(R8G8_UNORM, 2),
    AOR_FORMAT(R8G8_SNORM, 2),
    AOR_FORMAT(R8G8_UINT, 2),
    AOR_FORMAT(R8G8B8A8_UNORM, 4),
    AOR_FORMAT(R8G8B8A8_SNORM, 4),
    AOR_FORMAT(R8G8B8A8_UINT, 4),
    AOR_FORMAT(R8G8B8A8_SRGB, 4),
    AOR_FORMAT(B8G8R8A8_UNORM, 4),
    AOR_FORMAT(B8G8R8A8_SRGB, 4),
    AOR_FORMAT(A2B10G10R10_UNORM_PACK32, 4),
    AOR_FORMAT(A2R10G10B10_UNORM_PACK32, 4),
    AOR_FORMAT(B10G11R11_UFLOAT_PACK32, 4),
    AOR_FORMAT(E5B9G9R9_UFLOAT_PACK32, 4),
    AOR_FORMAT(R16_UNORM, 2),
    AOR_FORMAT(R16_SNORM, 2),
    AOR_FORMAT(R16_UINT, 2),
    AOR_FORMAT(R16_SFLOAT, 2),
    AOR_FORMAT(R16G16_UNORM, 4),
    AOR_FORMAT(R16G16_SNORM, 4),
    AOR_FORMAT(R16G16_UINT, 4),
    AOR_FORMAT(R16G16_SFLOAT, 4),
    AOR_FORMAT(R16G16B16A16_UNORM, 8),
    AOR_FORMAT(R16G16B16A16_SNORM, 8),
    AOR_FORMAT(R16G16B16A16_UINT, 8),
    AOR_FORMAT(R16G16B16A16_SFLOAT, 8),
    AOR_FORMAT(R32_UINT, 4),
    AOR_FORMAT(R32_SINT, 4),
    AOR_FORMAT(R32_SFLOAT, 4),
    AOR_FORMAT(R32G32_UINT, 8),
    AOR_FORMAT(R32G32_SINT, 8),
    AOR_FORMAT(R32G32_SFLOAT, 8),
    AOR_FORMAT(R32G32B32_SFLOAT, 12),
    AOR_FORMAT(R32G32B32A32_UINT, 16),
    AOR_FORMAT(R32G32B32A32_SINT, 16),
    AOR_FORMAT(R32G32B32A32_SFLOAT, 16),
    AOR_FORMAT(D16_UNORM, 2),
    AOR_FORMAT(D32_SFLOAT, 4),
    AOR_FORMAT(X8_D24_UNORM_PACK32, 4),
};
#undef AOR_FORMAT

const FormatInfo* findFormat(VkFormat format) {
  for (const FormatInfo& info : kFormats) {
    if (info.format == format) return &info;
  }
  return nullptr;
}

template <typename Flags, size_t N>
std::string flagNames(Flags flags, const std::array<std::pair<Flags, const char*>, N>& names) {
  if (flags == 0) return "NONE";
  std::string out;
  for (const auto& [bit, name] : names) {
    if ((flags & bit) == bit && bit != 0) {
      if (!out.empty()) out += '|';
      out += name;
      flags &= ~bit;
    }
  }
  if (flags != 0) {
    if (!out.empty()) out += '|';
    char buf[32];
    std::snprintf(buf, sizeof buf, "0x%llx", static_cast<unsigned long long>(flags));
    out += buf;
  }
  return out;
}

}  // namespace

uint32_t bytesPerPixel(VkFormat format) {
  const FormatInfo* info = findFormat(format);
  return info ? info->bytes : 0;
}

uint64_t imageBytes(const ImageDesc& desc) {
  uint64_t texels = 0;
  for (uint32_t m = 0; m < desc.mipLevels; ++m)
    texels += uint64_t{std::max(1u, desc.width >> m)} * uint64_t{std::max(1u, desc.height >> m)};
  return texels * desc.arrayLayers * bytesPerPixel(desc.format);
}

const char* formatName(VkFormat format) {
  if (format == VK_FORMAT_UNDEFINED) return "UNDEFINED";
  const FormatInfo* info = findFormat(format);
  return info ? info->name : "unknown format";
}

ResourceState requiredState(Access access) {
  switch (access) {
    case Access::SampledRead:
      return {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    case Access::StorageRead:
      return {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
              VK_IMAGE_LAYOUT_GENERAL};
    case Access::StorageWrite:
      return {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
              VK_IMAGE_LAYOUT_GENERAL};
    case Access::TransferRead:
      return {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
              VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
    case Access::TransferWrite:
      return {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
              VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
    case Access::ClearWrite:
      return {VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
              VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
    case Access::UniformRead:
      return {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_UNIFORM_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED};
    case Access::IndirectRead:
      return {VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED};
    case Access::AccelerationStructureRead:
      return {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR, VK_IMAGE_LAYOUT_UNDEFINED};
  }
  return {};
}

bool isWrite(Access access) {
  return access == Access::StorageWrite || access == Access::TransferWrite || access == Access::ClearWrite;
}

ResourceState requiredState(const PassDecl& pass, ResourceId id, Subresources range) {
  ResourceState merged;
  bool any = false;
  for (const auto& a : pass.accesses) {
    if (a.resource != id) continue;
    if (!(range == Subresources{}) && !overlaps(a.range, range)) continue;
    ResourceState need = requiredState(a.access);
    merged.stage |= need.stage;
    merged.access |= need.access;
    if (!any) {
      merged.layout = need.layout;
    } else if (merged.layout != need.layout) {
      merged.layout = VK_IMAGE_LAYOUT_GENERAL;  // the one layout every access here supports
    }
    any = true;
  }
  return merged;
}

const char* accessName(Access access) {
  switch (access) {
    case Access::SampledRead: return "sampled read";
    case Access::StorageRead: return "storage read";
    case Access::StorageWrite: return "storage write";
    case Access::TransferRead: return "transfer read";
    case Access::TransferWrite: return "transfer write";
    case Access::ClearWrite: return "clear";
    case Access::UniformRead: return "uniform read";
    case Access::IndirectRead: return "indirect read";
    case Access::AccelerationStructureRead: return "acceleration structure read";
  }
  return "?";
}

std::string rangeText(const ResourceDecl& decl, const Subresources& range) {
  if (decl.isBuffer() || (decl.desc.mipLevels == 1 && decl.desc.arrayLayers == 1)) return "";
  auto span = [](const char* what, uint32_t base, uint32_t count, uint32_t total) -> std::string {
    if (total == 1 || (base == 0 && count == total)) return "";
    return count == 1 ? fmt::format(" {} {}", what, base) : fmt::format(" {}s {}-{}", what, base, base + count - 1);
  };
  return span("mip", range.baseMip, range.mipCount, decl.desc.mipLevels) +
         span("layer", range.baseLayer, range.layerCount, decl.desc.arrayLayers);
}

const char* kindName(ResourceKind kind) {
  switch (kind) {
    case ResourceKind::Transient: return "transient";
    case ResourceKind::Imported: return "imported";
    case ResourceKind::History: return "history";
  }
  return "?";
}

const char* layoutName(VkImageLayout layout) {
  switch (layout) {
    case VK_IMAGE_LAYOUT_UNDEFINED: return "UNDEFINED";
    case VK_IMAGE_LAYOUT_GENERAL: return "GENERAL";
    case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL: return "COLOR_ATTACHMENT_OPTIMAL";
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL: return "DEPTH_STENCIL_ATTACHMENT_OPTIMAL";
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL: return "DEPTH_STENCIL_READ_ONLY_OPTIMAL";
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: return "SHADER_READ_ONLY_OPTIMAL";
    case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: return "TRANSFER_SRC_OPTIMAL";
    case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: return "TRANSFER_DST_OPTIMAL";
    case VK_IMAGE_LAYOUT_PREINITIALIZED: return "PREINITIALIZED";
    case VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL: return "READ_ONLY_OPTIMAL";
    case VK_IMAGE_LAYOUT_ATTACHMENT_OPTIMAL: return "ATTACHMENT_OPTIMAL";
    case VK_IMAGE_LAYOUT_PRESENT_SRC_KHR: return "PRESENT_SRC_KHR";
    default: return "unknown layout";
  }
}

std::string stageNames(VkPipelineStageFlags2 stages) {
  static const std::array<std::pair<VkPipelineStageFlags2, const char*>, 15> kNames = {{
      {VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, "DRAW_INDIRECT"},
      {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, "ALL_COMMANDS"},
      {VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, "TOP_OF_PIPE"},
      {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, "COMPUTE_SHADER"},
      {VK_PIPELINE_STAGE_2_COPY_BIT, "COPY"},
      {VK_PIPELINE_STAGE_2_BLIT_BIT, "BLIT"},
      {VK_PIPELINE_STAGE_2_CLEAR_BIT, "CLEAR"},
      {VK_PIPELINE_STAGE_2_RESOLVE_BIT, "RESOLVE"},
      {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, "ALL_TRANSFER"},
      {VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, "FRAGMENT_SHADER"},
      {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, "COLOR_ATTACHMENT_OUTPUT"},
      {VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT, "ALL_GRAPHICS"},
      {VK_PIPELINE_STAGE_2_HOST_BIT, "HOST"},
      {VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, "BOTTOM_OF_PIPE"},
      {VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, "ACCELERATION_STRUCTURE_BUILD"},
  }};
  return flagNames(stages, kNames);
}

std::string accessNames(VkAccessFlags2 access) {
  static const std::array<std::pair<VkAccessFlags2, const char*>, 17> kNames = {{
      {VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, "INDIRECT_COMMAND_READ"},
      {VK_ACCESS_2_MEMORY_READ_BIT, "MEMORY_READ"},
      {VK_ACCESS_2_MEMORY_WRITE_BIT, "MEMORY_WRITE"},
      {VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, "SHADER_SAMPLED_READ"},
      {VK_ACCESS_2_SHADER_STORAGE_READ_BIT, "SHADER_STORAGE_READ"},
      {VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, "SHADER_STORAGE_WRITE"},
      {VK_ACCESS_2_SHADER_READ_BIT, "SHADER_READ"},
      {VK_ACCESS_2_SHADER_WRITE_BIT, "SHADER_WRITE"},
      {VK_ACCESS_2_TRANSFER_READ_BIT, "TRANSFER_READ"},
      {VK_ACCESS_2_TRANSFER_WRITE_BIT, "TRANSFER_WRITE"},
      {VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, "COLOR_ATTACHMENT_READ"},
      {VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, "COLOR_ATTACHMENT_WRITE"},
      {VK_ACCESS_2_UNIFORM_READ_BIT, "UNIFORM_READ"},
      {VK_ACCESS_2_HOST_READ_BIT, "HOST_READ"},
      {VK_ACCESS_2_HOST_WRITE_BIT, "HOST_WRITE"},
      {VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR, "ACCELERATION_STRUCTURE_READ"},
      {VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR, "ACCELERATION_STRUCTURE_WRITE"},
  }};
  return flagNames(access, kNames);
}

}  // namespace aor::graph
