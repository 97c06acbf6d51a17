#pragma once
// `tune --cv` (docs/tuning.md): leave-one-capture-out cross-validation. Each fold tunes on every
// capture but one and scores the one left out before and after; the fit on all captures is
// recommended only when no fold's held-out objective got worse than the defaults' by more than a
// margin, else the defaults are (the worst such fold named).
#include <limits>
#include <string>
#include <vector>

#include "tune/tuning.h"

namespace aor {

struct CrossValidationFold {
  std::string heldOut;
  TuneRun run;  // trained on the other captures; its hold-out is the one left out
  double before() const { return run.holdoutBefore.objective; }
  double after() const { return run.holdoutAfter.objective; }
  // Relative change; the objectives are lower-is-better. 0 when both are 0 (a flat plane's exact
  // answer), infinite when only the fit's is above 0.
  double change() const {
    if (before() > 0.0) return after() / before() - 1.0;
    return after() > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
  }
};

struct CrossValidation {
  double margin = 0.02;
  std::vector<CrossValidationFold> folds;
  int refusedFold = -1;  // the fold that got worse by the most beyond the margin; -1: the fit generalises
  bool accepted() const { return refusedFold < 0; }
};

inline constexpr double kDefaultCrossValidationMargin = 0.02;

// The fold whose held-out objective rose by the most over before x (1 + margin), or -1 when none did.
int refusedFold(const std::vector<CrossValidationFold>& folds, double margin);

// InputError naming --cv unless there are at least two captures (one fold leaves one out).
void requireFolds(size_t captures);

// One fold per capture (at least two: requireFolds), each a whole tuning of the
// others under `limits`; `foldStarted(i, n)` is called before fold i of n.
CrossValidation crossValidate(VulkanContext& vk, const TuneRequest& request, const TuneLimits& limits,
                              const std::vector<TuneCapture>& captures, double margin,
                              const std::function<void(size_t, size_t)>& foldStarted);

}  // namespace aor
