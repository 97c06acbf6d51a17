#include "vk/op_counter.h"

#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

#include "vk/context.h"

namespace aor {
namespace {

// A slot's 64-bit counters as (low, high) words. 256 bytes apart: the largest
// minStorageBufferOffsetAlignment Vulkan allows.
constexpr VkDeviceSize kSlotBytes = 256;
constexpr VkDeviceSize kSlotUsedBytes = kOpKinds * 2 * sizeof(uint32_t);

}  // namespace

const char* opKindName(OpKind kind) {
  switch (kind) {
    case OpKind::Fetch: return "texel_fetch";
    case OpKind::Sample: return "texture_lod";
    case OpKind::Gather: return "gather";
    case OpKind::ImageLoad: return "image_load";
    case OpKind::ImageStore: return "image_store";
  }
  return "unknown";
}

uint64_t DispatchCounts::textureReads() const {
  return op(OpKind::Fetch) + op(OpKind::Sample) + op(OpKind::Gather) + op(OpKind::ImageLoad);
}

OpCounter::OpCounter(VulkanContext& vk, uint32_t maxDispatches) : vk_(vk), maxDispatches_(maxDispatches) {
  buffer_ = createHostBuffer(vk, kSlotBytes * maxDispatches, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  std::memset(buffer_.mapped, 0, size_t(buffer_.size));
}

OpCounter::~OpCounter() { destroyBuffer(vk_, buffer_); }

BoundResource OpCounter::slot(const std::string& pass, uint64_t bytesRead, uint64_t bytesWritten, uint64_t invocations) {
  if (recorded_.size() >= maxDispatches_)
    throw std::runtime_error(fmt::format("op counter: pass {} would be counted dispatch {}, more than the {} a counter holds",
                                         pass, recorded_.size() + 1, maxDispatches_));
  DispatchCounts d;
  d.pass = pass;
  d.bytesRead = bytesRead;
  d.bytesWritten = bytesWritten;
  d.invocations = invocations;
  BoundResource r;
  r.buffer = buffer_.buffer;
  r.offset = kSlotBytes * recorded_.size();
  r.range = kSlotUsedBytes;
  recorded_.push_back(std::move(d));
  return r;
}

std::vector<DispatchCounts> OpCounter::dispatches() const {
  std::vector<DispatchCounts> out = recorded_;
  const auto* base = static_cast<const uint8_t*>(buffer_.mapped);
  for (size_t i = 0; i < out.size(); ++i) {
    uint32_t words[kOpKinds * 2];
    std::memcpy(words, base + kSlotBytes * i, sizeof words);
    for (size_t k = 0; k < kOpKinds; ++k) out[i].ops[k] = uint64_t{words[2 * k + 1]} << 32 | words[2 * k];
  }
  return out;
}

std::vector<DispatchCounts> lastFramePerPass(const std::vector<DispatchCounts>& dispatches,
                                             const std::vector<std::string>& passes) {
  std::vector<DispatchCounts> out;
  for (const auto& pass : passes) {
    // The last contiguous run of this pass's dispatches: a frame records each pass's dispatches together.
    size_t end = dispatches.size();
    while (end > 0 && dispatches[end - 1].pass != pass) --end;
    if (end == 0) continue;
    size_t begin = end - 1;
    while (begin > 0 && dispatches[begin - 1].pass == pass) --begin;
    DispatchCounts sum;
    sum.pass = pass;
    sum.dispatches = end - begin;
    for (size_t i = begin; i < end; ++i) {
      for (size_t k = 0; k < kOpKinds; ++k) sum.ops[k] += dispatches[i].ops[k];
      sum.bytesRead += dispatches[i].bytesRead;
      sum.bytesWritten += dispatches[i].bytesWritten;
      sum.invocations += dispatches[i].invocations;
    }
    out.push_back(std::move(sum));
  }
  return out;
}

}  // namespace aor
