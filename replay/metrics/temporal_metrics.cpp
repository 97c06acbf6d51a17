#include "metrics/temporal_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/parallel_rows.h"
#include "metrics/temporal_response.h"

namespace aor {
namespace {

bool sameSize(const FrameGeometry& a, const FrameGeometry& b) { return a.width == b.width && a.height == b.height; }

// Lai et al. 2018: previous output warped into this frame, squared difference over unmasked pixels.
double warpingError(const float* visibility, const std::vector<float>& previous, const Reprojection& r, int width,
                    int height) {
  return rowOrderedMean(
      width, height, [&](size_t i) { return r.state[i] == PixelHistory::Reprojected; },
      [&](size_t i) {
        double d = double(visibility[i]) - double(sampleBilinear(previous, width, height, r.position[i]));
        return d * d;
      });
}

double derivativeError(const float* output, const std::vector<float>& previousOutput, const float* reference,
                       const std::vector<float>& previousReference, const FrameGeometry& g) {
  return rowOrderedMean(
      g.width, g.height, [&](size_t i) { return !g.isSky(i); },
      [&](size_t i) {
        double outputChange = double(output[i]) - double(previousOutput[i]);
        double referenceChange = double(reference[i]) - double(previousReference[i]);
        return std::abs(outputChange - referenceChange);
      });
}

double meanAbsError(const float* output, const float* truth, const FrameGeometry& g) {
  return rowOrderedMean(
      g.width, g.height, [&](size_t i) { return !g.isSky(i); },
      [&](size_t i) { return std::abs(double(output[i]) - double(truth[i])); });
}

nlohmann::json responseJson(const ResponseSummary& r) {
  return {{"response_frames", r.responseFrames}, {"ghost_energy", r.ghostEnergy}, {"settled_error", r.settled},
          {"settled", r.settledReached}, {"ema_response_frames", r.emaFrames}};
}

// Mean, max and the frame of the max of one per-frame value over the frames that measured it.
nlohmann::json frameValueSummary(const std::vector<TemporalFrameMetrics>& frames, double TemporalFrameMetrics::*value) {
  double sum = 0, max = -1;
  int count = 0, maxFrame = -1;
  for (const auto& f : frames) {
    double v = f.*value;
    if (v < 0) continue;
    sum += v;
    ++count;
    if (v > max) { max = v; maxFrame = f.index; }
  }
  if (!count) return nullptr;
  return {{"mean", sum / count}, {"max", max}, {"max_frame", maxFrame}, {"frames", count}};
}

}  // namespace

void TemporalAnalysis::addFrame(const AnalyzedFrame& frame) {
  historyWeight_ = frame.historyWeight;
  FrameGeometry geometry = frameGeometry(frame.width, frame.height, frame.depth, frame.view, frame.projection);
  TemporalFrameMetrics m;
  m.index = frame.index;
  m.historyValid = frame.historyValid;
  m.resetReason = frame.resetReason;
  const float* truth = frame.reference ? frame.reference->data() : frame.noHistory;
  if (truth) {
    std::string source = frame.reference ? "reference" : "no-history replay";
    errorSource_ = errorSource_.empty() || errorSource_ == source ? source : "mixed";
    m.absError = meanAbsError(frame.visibility, truth, geometry);
  }

  if (!window_.continues(geometry, frame.cut)) {
    auto deviations = window_.pixelDeviations();
    if (!deviations.empty()) {
      closedWindowDeviations_.insert(closedWindowDeviations_.end(), deviations.begin(), deviations.end());
      staticWindows_.push_back({window_.firstFrame(), window_.firstFrame() + window_.frameCount() - 1});
    }
    window_.start(frame.index, geometry);
  }
  window_.add(frame.visibility);

  std::unique_ptr<Reprojection> reprojection;
  if (previous_ && sameSize(previous_->geometry, geometry)) {
    reprojection = std::make_unique<Reprojection>(reproject(geometry, previous_->geometry));
    size_t disoccluded = reprojection->count(PixelHistory::Disoccluded);
    size_t surface = disoccluded + reprojection->count(PixelHistory::Reprojected);
    if (!frame.cut) {
      m.disoccludedFraction = surface ? double(disoccluded) / double(surface) : 0.0;
      m.warpingError = warpingError(frame.visibility, previous_->visibility, *reprojection, frame.width, frame.height);
      if (frame.reference && !previous_->reference.empty())
        m.derivativeError = derivativeError(frame.visibility, previous_->visibility, frame.reference->data(),
                                            previous_->reference, geometry);
    }
  }

  auto next = std::make_unique<Previous>();
  trackAges(frame, geometry, reprojection.get(), truth, *next);
  size_t pixels = geometry.distance.size();
  next->visibility.assign(frame.visibility, frame.visibility + pixels);
  if (frame.reference) next->reference = *frame.reference;
  next->geometry = std::move(geometry);
  previous_ = std::move(next);
  frames_.push_back(std::move(m));
}

// Frames since each pixel's history started, followed through the reprojection. Pixels whose
// history started at a disocclusion feed the disocclusion curve. Rows run in bands on all cores;
// each row's sums are added to the curve's in row order (see rowOrderedMean).
void TemporalAnalysis::trackAges(const AnalyzedFrame& frame, const FrameGeometry& geometry,
                                 const Reprojection* reprojection, const float* truth, Previous& next) {
  size_t pixels = geometry.distance.size();
  next.age.assign(pixels, -1);
  next.sinceDisocclusion.assign(pixels, 0);
  next.error.assign(pixels, -1.0f);
  if (historyWeight_ <= 0.0f) return;  // no history: nothing to follow
  bool continued = frame.historyValid && reprojection;
  struct RowSums {
    double fresh = 0;
    size_t freshCount = 0;
    std::array<double, kMaxTrackedAge + 1> step{};
    std::array<size_t, kMaxTrackedAge + 1> stepCount{};
  };
  std::vector<RowSums> rows(size_t(geometry.height));
  size_t width = size_t(geometry.width);
  forEachRowBand(geometry.height, [&](int firstRow, int endRow) {
    for (size_t y = size_t(firstRow); y < size_t(endRow); ++y)
      for (size_t i = y * width; i < (y + 1) * width; ++i) {
        if (geometry.isSky(i)) continue;
        if (truth) next.error[i] = std::abs(frame.visibility[i] - truth[i]);
        next.age[i] = 0;
        if (!continued) continue;  // reset: every pixel starts over, and not from a disocclusion
        if (reprojection->state[i] != PixelHistory::Reprojected) {
          next.sinceDisocclusion[i] = 1;
          if (truth) {
            rows[y].fresh += next.error[i];
            ++rows[y].freshCount;
          }
          continue;
        }
        size_t from = reprojection->nearest[i];
        if (previous_->age[from] < 0) continue;
        int age = std::min(previous_->age[from] + 1, kMaxTrackedAge);
        next.age[i] = age;
        next.sinceDisocclusion[i] = previous_->sinceDisocclusion[from];
        if (next.sinceDisocclusion[i] && truth && previous_->error[from] >= 0.0f) {
          rows[y].step[size_t(age)] += double(next.error[i]) - double(previous_->error[from]);
          ++rows[y].stepCount[size_t(age)];
        }
      }
  });
  for (const auto& row : rows) {
    freshErrorSum_ += row.fresh;
    freshCount_ += row.freshCount;
    for (size_t a = 0; a < row.step.size(); ++a) {
      stepSum_[a] += row.step[a];
      stepCount_[a] += row.stepCount[a];
    }
  }
}

NoiseSummary TemporalAnalysis::staticNoise() const { return staticNoise(window_.pixelDeviations()); }

// The closed windows' deviations and those of the open window, computed once by the caller.
NoiseSummary TemporalAnalysis::staticNoise(const std::vector<float>& openWindowDeviations) const {
  auto deviations = closedWindowDeviations_;
  deviations.insert(deviations.end(), openWindowDeviations.begin(), openWindowDeviations.end());
  return summarizeNoise(std::move(deviations));
}

std::vector<double> TemporalAnalysis::disocclusionCurve() const {
  std::vector<double> curve;
  if (freshCount_ < kMinPixelsPerAge) return curve;
  curve.push_back(freshErrorSum_ / double(freshCount_));
  for (size_t a = 1; a < stepCount_.size() && stepCount_[a] >= kMinPixelsPerAge; ++a)
    curve.push_back(curve.back() + stepSum_[a] / double(stepCount_[a]));
  return curve;
}

std::vector<size_t> TemporalAnalysis::disocclusionPixels() const {
  std::vector<size_t> pixels{freshCount_};
  pixels.insert(pixels.end(), stepCount_.begin() + 1, stepCount_.end());
  pixels.resize(disocclusionCurve().size());
  return pixels;
}

// abs_error from the history reset at frames_[start] up to the next reset; empty when that frame is
// no reset worth following (only runs that keep history have those) or measured no abs_error.
std::vector<double> TemporalAnalysis::resetCurve(size_t start) const {
  std::vector<double> curve;
  if (historyWeight_ <= 0.0f) return curve;
  if (frames_[start].historyValid || frames_[start].resetReason == "single-frame replay") return curve;
  for (size_t j = start; j < frames_.size() && (j == start || frames_[j].historyValid) && frames_[j].absError >= 0; ++j)
    curve.push_back(frames_[j].absError);
  return curve;
}

nlohmann::json TemporalAnalysis::frameJson(int index) const {
  auto it = std::find_if(frames_.begin(), frames_.end(), [&](const auto& f) { return f.index == index; });
  if (it == frames_.end()) return nullptr;
  nlohmann::json j = nlohmann::json::object();
  if (it->disoccludedFraction >= 0) j["disoccluded_fraction"] = it->disoccludedFraction;
  if (it->warpingError >= 0) j["warping_error"] = it->warpingError;
  if (it->derivativeError >= 0) j["derivative_error"] = it->derivativeError;
  if (it->absError >= 0) j["abs_error"] = it->absError;
  for (size_t i = size_t(it - frames_.begin()); i < frames_.size(); ++i) {
    if (frames_[i].index != index) continue;
    auto curve = resetCurve(i);
    if (!curve.empty()) j.update(responseJson(analyzeResponse(curve, historyWeight_)));
  }
  if (j.empty()) return nullptr;
  return j;
}

nlohmann::json TemporalAnalysis::summaryJson() const {
  if (frames_.empty()) return nullptr;
  nlohmann::json j;
  int predicted = emaResponseFrames(historyWeight_);
  j["history_weight"] = historyWeight_;
  j["error_source"] = errorSource_.empty() ? nlohmann::json(nullptr) : nlohmann::json(errorSource_);
  j["ema"] = {{"predicted_response_frames", predicted},
              {"residual", emaResidual(historyWeight_, std::max(predicted + 1, 2))},
              {"note", "stale history keeps w^n of its amplitude after n frames (w = history weight)"}};

  auto openWindowDeviations = window_.pixelDeviations();
  auto noise = staticNoise(openWindowDeviations);
  if (noise.pixels > 0) {
    auto windows = staticWindows_;
    if (!openWindowDeviations.empty())
      windows.push_back({window_.firstFrame(), window_.firstFrame() + window_.frameCount() - 1});
    j["static_noise"] = {{"mean", noise.mean}, {"p99", noise.p99}, {"pixels", noise.pixels}, {"windows", windows}};
  } else {
    j["static_noise"] = nullptr;
  }
  j["warping_error"] = frameValueSummary(frames_, &TemporalFrameMetrics::warpingError);
  j["derivative_error"] = frameValueSummary(frames_, &TemporalFrameMetrics::derivativeError);
  j["abs_error"] = frameValueSummary(frames_, &TemporalFrameMetrics::absError);

  nlohmann::json resets = nlohmann::json::array();
  for (size_t i = 0; i < frames_.size(); ++i) {
    auto curve = resetCurve(i);
    if (curve.empty()) continue;
    nlohmann::json r{{"frame", frames_[i].index}, {"reason", frames_[i].resetReason}, {"abs_error", curve}};
    r.update(responseJson(analyzeResponse(curve, historyWeight_)));
    resets.push_back(r);
  }
  j["resets"] = resets;

  auto curve = disocclusionCurve();
  if (!curve.empty()) {
    nlohmann::json d{{"abs_error_by_age", curve}, {"pixels_by_age", disocclusionPixels()}};
    d.update(responseJson(analyzeResponse(curve, historyWeight_)));
    j["disocclusion"] = d;
  } else {
    j["disocclusion"] = nullptr;
  }
  return j;
}

}  // namespace aor
