#pragma once
// How fast the output recovers after history is thrown away (a reset, or a disocclusion): an error
// curve e_0, e_1, ... (frames since the event) reduced to a response time and a ghost energy, and
// what the EMA blend predicts for it.
#include <vector>

namespace aor {

inline constexpr double kResponseBand = 0.1;  // "settled" = within 10% of the settled value
inline constexpr int kSettleTail = 3;         // the settled value is the mean of the last 3 frames

struct ResponseSummary {
  double settled = 0;        // mean of the last kSettleTail values of the curve
  int responseFrames = 0;    // first n with |e_n - settled| <= 10% of settled
  double ghostEnergy = 0;    // sum over n of max(0, e_n - settled)
  bool settledReached = false;  // the tail lies past emaResponseFrames(w), so `settled` is one
  // What a plain EMA predicts for this curve: a ghost of the measured initial excess e_0 - settled
  // that keeps w^n of itself falls inside the band after n >= ln(0.1 settled / excess) / ln w frames.
  int emaFrames = 0;
};

// `historyWeight` w: the run's `temporal` setting. Empty curve: zeros.
ResponseSummary analyzeResponse(const std::vector<double>& errors, double historyWeight);

// The temporal pass blends out = mix(current, history, w) with history weight w (setting `temporal`;
// the alpha = 1 - w). Anything stale in the history therefore keeps the fraction w^n of its
// amplitude n frames later. Returns the smallest n with w^n <= fraction (0 for w = 0).
int emaResponseFrames(double historyWeight, double fraction = kResponseBand);
std::vector<double> emaResidual(double historyWeight, int frames);  // w^n for n = 0 .. frames-1

}  // namespace aor
