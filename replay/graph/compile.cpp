// RenderGraph::compile(): the named stages of compile_stages.h, one after another.
#include "graph/compile_stages.h"

namespace aor::graph {

CompiledGraph RenderGraph::compile() const {
  CompiledGraph out;
  out.resources.resize(resources_.size());
  auto sources = stages::findProducers(resources_, passes_);
  auto liveness = stages::cull(resources_, passes_, sources, out.culled);
  stages::lifetimes(resources_, passes_, liveness, out);
  stages::alias(resources_, out);
  stages::barriers(resources_, passes_, out);
  return out;
}

}  // namespace aor::graph
