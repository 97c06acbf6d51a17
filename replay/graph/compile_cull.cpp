// Compile stages 1 and 2: who produces what each pass reads, and which passes (and writes) the
// side-effect passes need.
#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "graph/compile_stages.h"

namespace aor::graph::stages {
namespace {

uint32_t subresourceIndex(const ResourceDecl& res, uint32_t mip, uint32_t layer) {
  return res.isBuffer() ? 0 : layer * res.desc.mipLevels + mip;
}

template <typename F>
void forEachSubresource(const ResourceDecl& res, const Subresources& range, F&& f) {
  for (uint32_t layer = range.baseLayer; layer < range.baseLayer + range.layerCount; ++layer)
    for (uint32_t mip = range.baseMip; mip < range.baseMip + range.mipCount; ++mip) f(subresourceIndex(res, mip, layer));
}

template <typename T>
void pushUnique(std::vector<T>& list, T value) {
  if (std::find(list.begin(), list.end(), value) == list.end()) list.push_back(value);
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
  return out;
}

bool mustBeWrittenFirst(const ResourceDecl& res) {
  return res.kind == ResourceKind::Transient || (res.kind == ResourceKind::History && res.historyCurrent);
}

// Why an unneeded pass is culled: what it writes, and which culled passes alone read that.
std::string cullReason(const std::vector<ResourceDecl>& resources, const std::vector<PassDecl>& passes,
                       const ReadSources& sources, uint32_t p) {
  std::vector<ResourceId> outputs;
  for (const auto& a : passes[p].accesses)
    if (isWrite(a.access)) pushUnique(outputs, a.resource);
  if (outputs.empty()) return "no outputs and no side effects";
  std::vector<std::string> names, culledReaders;
  for (ResourceId id : outputs) {
    names.push_back(resources[id].name);
    for (size_t q = p + 1; q < passes.size(); ++q)
      for (const auto& source : sources[q])
        if (source.resource == id && std::count(source.producers.begin(), source.producers.end(), p))
          pushUnique(culledReaders, passes[q].name);
  }
  std::string reason = fmt::format("writes {}, which no live pass reads", joinNames(names));
  if (!culledReaders.empty())
    reason += fmt::format(" (read only by culled pass{} {})", culledReaders.size() > 1 ? "es" : "",
                          joinNames(culledReaders));
  return reason;
}

}  // namespace

ReadSources findProducers(const std::vector<ResourceDecl>& resources, const std::vector<PassDecl>& passes) {
  ReadSources sources(passes.size());
  std::vector<std::vector<int>> lastWriter(resources.size());
  for (size_t id = 0; id < resources.size(); ++id) lastWriter[id].assign(resources[id].subresourceCount(), -1);
  for (size_t p = 0; p < passes.size(); ++p) {
    for (const auto& a : passes[p].accesses) {
      if (isWrite(a.access)) continue;
      const ResourceDecl& res = resources[a.resource];
      auto source = std::find_if(sources[p].begin(), sources[p].end(), [&](const auto& s) { return s.resource == a.resource; });
      if (source == sources[p].end()) source = sources[p].insert(sources[p].end(), ReadSource{a.resource, {}});
      forEachSubresource(res, a.range, [&](uint32_t sub) {
        int writer = lastWriter[a.resource][sub];
        if (writer < 0 && mustBeWrittenFirst(res))
          throw std::logic_error(fmt::format("pass '{}' reads {} '{}'{} before any earlier pass writes it", passes[p].name,
                                             res.kind == ResourceKind::Transient ? "transient" : "history image",
                                             res.name, rangeText(res, a.range)));
        if (writer >= 0) pushUnique(source->producers, uint32_t(writer));
      });
    }
    for (const auto& a : passes[p].accesses)
      if (isWrite(a.access))
        forEachSubresource(resources[a.resource], a.range, [&](uint32_t sub) { lastWriter[a.resource][sub] = int(p); });
  }
  return sources;
}

Liveness cull(const std::vector<ResourceDecl>& resources, const std::vector<PassDecl>& passes, const ReadSources& sources,
              std::vector<CulledPass>& culled) {
  Liveness out;
  out.live.assign(passes.size(), false);
  // read[p][id]: a live pass reads id from p.
  std::vector<std::vector<ResourceId>> readFrom(passes.size());
  for (size_t i = passes.size(); i-- > 0;) {
    if (passes[i].sideEffect) out.live[i] = true;
    if (!out.live[i]) continue;
    for (const auto& source : sources[i])
      for (uint32_t producer : source.producers) {
        out.live[producer] = true;
        pushUnique(readFrom[producer], source.resource);
      }
  }
  out.accessLive.resize(passes.size());
  for (size_t p = 0; p < passes.size(); ++p) {
    for (const auto& a : passes[p].accesses)
      out.accessLive[p].push_back(out.live[p] && (!a.ifRead || std::count(readFrom[p].begin(), readFrom[p].end(), a.resource)));
    if (!out.live[p]) culled.push_back(CulledPass{uint32_t(p), cullReason(resources, passes, sources, uint32_t(p))});
  }
  return out;
}

}  // namespace aor::graph::stages
