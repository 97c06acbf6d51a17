#pragma once
// The stages of RenderGraph::compile(), in order (compile.cpp runs them). Internal to the graph.
#include <vector>

#include "graph/render_graph.h"

namespace aor::graph::stages {

// For each pass, each of its reads: the resource and the passes whose writes it sees (the nearest
// earlier writer of each subresource it reads; none for data from outside the graph).
struct ReadSource {
  ResourceId resource;
  std::vector<uint32_t> producers;
};
using ReadSources = std::vector<std::vector<ReadSource>>;  // indexed by pass
ReadSources findProducers(const std::vector<ResourceDecl>& resources, const std::vector<PassDecl>& passes);

// Live passes (reachable backwards from the side-effect passes), the culled ones with their
// reasons, and which accesses of each live pass stay (writeIfRead writes nobody reads are dropped).
struct Liveness {
  std::vector<bool> live;                     // per pass
  std::vector<std::vector<bool>> accessLive;  // per pass, per access
};
Liveness cull(const std::vector<ResourceDecl>& resources, const std::vector<PassDecl>& passes,
              const ReadSources& sources, std::vector<CulledPass>& culled);

// Live passes in declaration order, and each resource's lifetime and usage flags.
void lifetimes(const std::vector<ResourceDecl>& resources, const std::vector<PassDecl>& passes, const Liveness& liveness, CompiledGraph& out);

// Transients with disjoint lifetimes share memory slots; memory totals.
void alias(const std::vector<ResourceDecl>& resources, CompiledGraph& out);

// Barriers and layout transitions per subresource, derived from the live accesses in execution
// order; final states.
void barriers(const std::vector<ResourceDecl>& resources, const std::vector<PassDecl>& passes, CompiledGraph& out);

}  // namespace aor::graph::stages
