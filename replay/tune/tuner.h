#pragma once
// The search behind `aoreplay tune`: minimise a noisy-free objective (error against a reference)
// over a box of continuous and integer dimensions, with an optional budget on a second measure
// (GPU ms). A coarse grid first, for robustness against local minima the error surface of AO
// constants has (power and radius trade against each other), then NLopt's BOBYQA, a
// derivative-free trust-region method, from the best grid point. No randomness: the same
// objective gives the same evaluations in the same order.
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace aor {

struct TuneDimension {
  std::string name;
  double min = 0, max = 1;  // inclusive
  bool integer = false;     // values rounded to whole numbers
  bool float32 = false;     // values rounded to 32-bit floats (what a float key's shader gets)
  double start = 0;         // the untuned value (evaluated first)
};

struct TuneMeasure {
  double objective = 0;  // lower is better
  double cost = 0;       // what --budget-ms bounds (GPU ms); 0 when there is no budget
};

struct TuneEvaluation {
  std::vector<double> values;  // one per dimension, integers rounded
  TuneMeasure measure;
  std::string phase;           // "start", "grid", "local"
  bool withinBudget = true;
};

struct TuneProblem {
  std::vector<TuneDimension> dimensions;
  std::function<TuneMeasure(const std::vector<double>& values)> evaluate;
  int maxEvaluations = 40;      // distinct configurations, the start included
  int gridPoints = 3;           // per dimension, fewer when the grid would take over half the evaluations
  std::optional<double> budget; // configurations whose cost exceeds it are never the best
  std::function<void(const std::vector<TuneEvaluation>& done, int best, int max)> progress;
};

struct TuneResult {
  std::vector<TuneEvaluation> evaluations;  // in the order they ran
  int best = -1;                            // index of the lowest objective within the budget; -1: none
  int gridPointsUsed = 0;
};

// Throws std::invalid_argument for an empty or inverted box.
TuneResult tune(const TuneProblem& problem);

// Grid points per dimension so that the grid takes at most half of `maxEvaluations` (at least 2
// per dimension when that fits, else 1: the start alone).
int gridPointsWithin(int requested, size_t dimensions, int maxEvaluations);

}  // namespace aor
