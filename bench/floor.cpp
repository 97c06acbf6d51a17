#include "floor.h"

#include <fmt/format.h>

namespace aor::bench {

PassFloor passFloor(const std::string& config, const DispatchCounts& counts, const DeviceRates* rates,
                    std::optional<double> measuredMs) {
  PassFloor f;
  f.config = config;
  f.counts = counts;
  f.measuredMs = measuredMs;
  if (rates) {
    f.bytesMs = double(counts.bytesRead + counts.bytesWritten) / rates->copyBytesPerMs;
    f.fetchMs = double(counts.textureReads()) / rates->texelFetchesPerMs;
    f.dispatchMs = double(counts.dispatches) * rates->dispatchMs;
  }
  return f;
}

void printFloorTable(std::FILE* out, const std::vector<PassFloor>& rows, const DeviceRates* rates) {
  if (rates) {
    fmt::print(out, "floor rates: copy {:.1f} GB/s (read + written, fastest: {} at {} MiB), texelFetch {:.1f} G/s (R32F, {}x{}), "
               "empty dispatch in a chain {:.4f} ms\n",
               rates->copyBytesPerMs * 1e-6, copyPathName(rates->copyPath), rates->copyBytes >> 20, rates->texelFetchesPerMs * 1e-6,
               rates->fetchSize.first, rates->fetchSize.second, rates->dispatchMs);
    for (const auto& f : rates->scatteredFetches)
      fmt::print(out, "  texelFetch scattered to {:>3} px: {:.1f} G/s (not in the floor)\n", f.spread, f.texelFetchesPerMs * 1e-6);
    for (const auto& c : rates->copies)
      fmt::print(out, "  copy {:>5} MiB, {:<15}: {:.1f} GB/s\n", c.bytes >> 20, copyPathName(c.path), c.bytesPerMs * 1e-6);
  }
  fmt::print(out, "{:<34} {:<18} {:>12} {:>12} {:>10} {:>10} {:>9} {:>9} {:>7} {}\n", "config", "pass", "tex reads",
             "stores", "MB read", "MB written", "ms", "floor ms", "ratio", "bound by");
  for (const auto& r : rows) {
    std::string ms = r.measuredMs ? fmt::format("{:.4f}", *r.measuredMs) : "-";
    std::string ratio = r.measuredMs && r.floorMs() > 0 ? fmt::format("{:.2f}", *r.measuredMs / r.floorMs()) : "-";
    fmt::print(out, "{:<34} {:<18} {:>12} {:>12} {:>10.2f} {:>10.2f} {:>9} {:>9.4f} {:>7} {}\n", r.config, r.counts.pass,
               r.counts.textureReads(), r.counts.op(OpKind::ImageStore), r.counts.bytesRead * 1e-6,
               r.counts.bytesWritten * 1e-6, ms, r.floorMs(), ratio, rates ? r.boundBy() : "-");
  }
}

nlohmann::json floorJson(const std::vector<PassFloor>& rows, const DeviceRates* rates, const std::string& device) {
  nlohmann::json j;
  j["device"] = device;
  if (rates) {
    j["rates"] = {{"copy_bytes_per_ms", rates->copyBytesPerMs}, {"texel_fetches_per_ms", rates->texelFetchesPerMs},
                  {"dispatch_ms", rates->dispatchMs}, {"copy_buffer_bytes", rates->copyBytes},
                  {"copy_path", copyPathName(rates->copyPath)},
                  {"fetch_grid", {rates->fetchSize.first, rates->fetchSize.second}}};
    auto& scattered = j["rates"]["scattered_fetches"] = nlohmann::json::array();
    for (const auto& f : rates->scatteredFetches)
      scattered.push_back({{"spread_px", f.spread}, {"texel_fetches_per_ms", f.texelFetchesPerMs}});
    auto& copies = j["rates"]["copies"] = nlohmann::json::array();
    for (const auto& c : rates->copies)
      copies.push_back({{"bytes", c.bytes}, {"bytes_per_ms", c.bytesPerMs}, {"path", copyPathName(c.path)}});
  }
  auto& passes = j["passes"] = nlohmann::json::array();
  for (const auto& r : rows) {
    nlohmann::json p{{"config", r.config},
                     {"pass", r.counts.pass},
                     {"invocations", r.counts.invocations},
                     {"bytes_read", r.counts.bytesRead},
                     {"bytes_written", r.counts.bytesWritten},
                     {"texture_reads", r.counts.textureReads()}};
    for (size_t k = 0; k < kOpKinds; ++k) p[opKindName(OpKind(k))] = r.counts.ops[k];
    if (rates) {
      p["bytes_ms"] = r.bytesMs;
      p["fetch_ms"] = r.fetchMs;
      p["dispatch_ms"] = r.dispatchMs;
      p["floor_ms"] = r.floorMs();
      p["bound_by"] = r.boundBy();
    }
    if (r.measuredMs) {
      p["measured_ms"] = *r.measuredMs;
      if (r.floorMs() > 0) p["ratio"] = *r.measuredMs / r.floorMs();
    }
    passes.push_back(std::move(p));
  }
  return j;
}

}  // namespace aor::bench
