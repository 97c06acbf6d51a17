#include "tune/cross_validation.h"

#include "core/input_error.h"

namespace aor {

int refusedFold(const std::vector<CrossValidationFold>& folds, double margin) {
  int worst = -1;
  for (size_t i = 0; i < folds.size(); ++i) {
    if (folds[i].after() <= folds[i].before() * (1.0 + margin)) continue;
    if (worst < 0 || folds[i].change() > folds[size_t(worst)].change()) worst = int(i);
  }
  return worst;
}

void requireFolds(size_t captures) {
  if (captures < 2)
    throw InputError("", std::nullopt, "--cv", "cross-validation leaves one capture out per fold: give at least two captures");
}

namespace {

std::vector<TuneCapture> allBut(const std::vector<TuneCapture>& captures, size_t left) {
  std::vector<TuneCapture> others;
  for (size_t i = 0; i < captures.size(); ++i)
    if (i != left) others.push_back(captures[i]);
  return others;
}

}  // namespace

CrossValidation crossValidate(VulkanContext& vk, const TuneRequest& request, const TuneLimits& limits,
                              const std::vector<TuneCapture>& captures, double margin,
                              const std::function<void(size_t, size_t)>& foldStarted) {
  requireFolds(captures.size());
  CrossValidation cv;
  cv.margin = margin;
  for (size_t i = 0; i < captures.size(); ++i) {
    if (foldStarted) foldStarted(i, captures.size());
    std::vector<TuneCapture> training = allBut(captures, i), heldOut{captures[i]};
    CrossValidationFold fold{captures[i].capture.name, planTuning(request, limits, training, heldOut)};
    tuneSettings(vk, request, limits, training, heldOut, fold.run);
    cv.folds.push_back(std::move(fold));
  }
  cv.refusedFold = refusedFold(cv.folds, margin);
  return cv;
}

}  // namespace aor
