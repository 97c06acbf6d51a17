#include "tune/tuner.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <stdexcept>

#include <nlopt.hpp>

namespace aor {
namespace {

// The search runs in the unit box, so one trust-region radius fits every dimension.
struct UnitBox {
  const std::vector<TuneDimension>& dims;
  std::vector<double> toValues(const std::vector<double>& unit) const {
    std::vector<double> v(dims.size());
    for (size_t i = 0; i < dims.size(); ++i) {
      double x = dims[i].min + std::clamp(unit[i], 0.0, 1.0) * (dims[i].max - dims[i].min);
      v[i] = dims[i].integer ? std::round(x) : dims[i].float32 ? double(float(x)) : x;
    }
    return v;
  }
  std::vector<double> toUnit(const std::vector<double>& values) const {
    std::vector<double> u(dims.size());
    for (size_t i = 0; i < dims.size(); ++i) {
      double span = dims[i].max - dims[i].min;
      u[i] = span > 0 ? (values[i] - dims[i].min) / span : 0.5;
    }
    return u;
  }
};

struct BudgetStop {};  // thrown through NLopt when the evaluations are spent

class Search {
 public:
  explicit Search(const TuneProblem& p) : problem_(p), box_{p.dimensions} {}

  // The measure of `values`, evaluated once: rounding integer dimensions maps many unit points to
  // one configuration, and a repeated one costs nothing.
  double penalised(const std::vector<double>& values, const char* phase) {
    auto it = seen_.find(values);
    if (it == seen_.end()) {
      if (int(result_.evaluations.size()) >= problem_.maxEvaluations) throw BudgetStop{};
      TuneEvaluation e{values, problem_.evaluate(values), phase, true};
      e.withinBudget = !problem_.budget || e.measure.cost <= *problem_.budget;
      result_.evaluations.push_back(e);
      it = seen_.emplace(values, int(result_.evaluations.size()) - 1).first;
      updateBest(it->second);
      if (problem_.progress) problem_.progress(result_.evaluations, result_.best, problem_.maxEvaluations);
    }
    const TuneEvaluation& e = result_.evaluations[size_t(it->second)];
    // Over the budget: worse than anything within it, and the further over, the worse, so the local
    // search is pushed back inside.
    return e.withinBudget ? e.measure.objective : 1e3 + e.measure.cost / *problem_.budget;
  }

  void runGrid(int points) {
    result_.gridPointsUsed = points;
    if (points < 2) return;
    size_t n = problem_.dimensions.size();
    std::vector<int> index(n, 0);
    for (;;) {
      std::vector<double> unit(n);
      for (size_t i = 0; i < n; ++i) unit[i] = (index[i] + 0.5) / points;  // cell centres
      penalised(box_.toValues(unit), "grid");
      size_t d = 0;
      while (d < n && ++index[d] == points) index[d++] = 0;
      if (d == n) return;
    }
  }

  void runLocal(int gridPoints) {
    int remaining = problem_.maxEvaluations - int(result_.evaluations.size());
    if (remaining <= 0) return;
    size_t n = problem_.dimensions.size();
    std::vector<double> x = box_.toUnit(result_.evaluations[size_t(startOfLocal())].values);
    nlopt::opt opt(n >= 2 ? nlopt::LN_BOBYQA : nlopt::LN_COBYLA, unsigned(n));  // BOBYQA needs two or more
    opt.set_lower_bounds(std::vector<double>(n, 0.0));
    opt.set_upper_bounds(std::vector<double>(n, 1.0));
    opt.set_initial_step(0.5 / std::max(gridPoints, 2));
    opt.set_xtol_abs(1e-3);
    opt.set_maxeval(remaining * 20);  // repeats are free; BudgetStop ends it at `remaining` new ones
    opt.set_min_objective(
        [](unsigned, const double* unit, double*, void* self) {
          auto* search = static_cast<Search*>(self);
          std::vector<double> u(unit, unit + search->problem_.dimensions.size());
          try {
            return search->penalised(search->box_.toValues(u), "local");
          } catch (const BudgetStop&) {
          } catch (...) {  // the objective's own error (a lost device, bad input): rethrown below
            search->error_ = std::current_exception();
          }
          throw nlopt::forced_stop();
        },
        this);
    double value = 0;
    try {
      opt.optimize(x, value);
    } catch (const nlopt::forced_stop&) {
    } catch (const nlopt::roundoff_limited&) {  // converged as far as doubles allow
    }
    if (error_) std::rethrow_exception(error_);
  }

  TuneResult take() { return std::move(result_); }

 private:
  void updateBest(int i) {
    const auto& e = result_.evaluations[size_t(i)];
    if (!e.withinBudget) return;
    if (result_.best < 0 || e.measure.objective < result_.evaluations[size_t(result_.best)].measure.objective)
      result_.best = i;
  }
  int startOfLocal() const {
    if (result_.best >= 0) return result_.best;
    // Nothing within the budget yet: start from the cheapest.
    int cheapest = 0;
    for (size_t i = 1; i < result_.evaluations.size(); ++i)
      if (result_.evaluations[i].measure.cost < result_.evaluations[size_t(cheapest)].measure.cost) cheapest = int(i);
    return cheapest;
  }

  const TuneProblem& problem_;
  UnitBox box_;
  TuneResult result_;
  std::map<std::vector<double>, int> seen_;
  std::exception_ptr error_;
};

}  // namespace

int gridPointsWithin(int requested, size_t dimensions, int maxEvaluations) {
  for (int points = requested; points >= 2; --points)
    if (std::pow(double(points), double(dimensions)) <= maxEvaluations / 2.0) return points;
  return 1;
}

TuneResult tune(const TuneProblem& problem) {
  if (problem.dimensions.empty()) throw std::invalid_argument("nothing to tune: no dimensions");
  for (const auto& d : problem.dimensions)
    if (!(d.min <= d.max) || !(d.start >= d.min && d.start <= d.max))
      throw std::invalid_argument("dimension " + d.name + ": need min <= start <= max");
  if (problem.maxEvaluations < 1) throw std::invalid_argument("maxEvaluations must be at least 1");
  Search search(problem);
  std::vector<double> start;
  for (const auto& d : problem.dimensions)
    start.push_back(d.integer ? std::round(d.start) : d.float32 ? double(float(d.start)) : d.start);
  int points = gridPointsWithin(problem.gridPoints, problem.dimensions.size(), problem.maxEvaluations - 1);
  try {
    search.penalised(start, "start");
    search.runGrid(points);
  } catch (const BudgetStop&) {
  }
  search.runLocal(points);
  return search.take();
}

}  // namespace aor
