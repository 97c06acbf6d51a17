#pragma once
// Records a compiled render graph: before each live pass, one synchronization2 barrier batch built
// from the graph's derived barriers (image barriers per range of levels and layers, buffer
// barriers); around each pass, two timestamp queries. Under counted cost, each pass alone.
#include <vector>

#include "cost/callgrind_counter.h"
#include "runtime/pass_context.h"
#include "graph/render_graph.h"

namespace aor {

struct VulkanContext;

class GraphExecutor {
 public:
  explicit GraphExecutor(VulkanContext& vk);
  ~GraphExecutor();
  GraphExecutor(const GraphExecutor&) = delete;
  GraphExecutor& operator=(const GraphExecutor&) = delete;

  void record(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled,
              const std::vector<graph::PhysicalResource>& resources);
  struct PassTime {
    double startMs = 0;     // from the first pass's start
    double durationMs = 0;
  };
  // Submits what was recorded, waits for it and returns each live pass's GPU time.
  std::vector<PassTime> submitAndWait();
  // Counted cost: each live pass recorded and submitted alone (with the barriers before it), the
  // counter bracketing its submission and wait; the passes' counts in execution order.
  std::vector<EventCounts> countPasses(const graph::RenderGraph& graph, const graph::CompiledGraph& compiled,
                                       const std::vector<graph::PhysicalResource>& resources, CallgrindCounter& counter);

 private:
  VulkanContext& vk_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkQueryPool queries_ = VK_NULL_HANDLE;
  uint32_t queryCapacity_ = 0;
  uint32_t recordedPasses_ = 0;

  void recordPass(graph::PassContext& context, const graph::CompiledPass& pass);
};

}  // namespace aor
