#include "mesh/interval_assignment.h"

#include <CbcModel.hpp>
#include <CglGomory.hpp>
#include <CoinPackedMatrix.hpp>
#include <CoinPackedVector.hpp>
#include <OsiClpSolverInterface.hpp>
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/option_checks.h"

namespace vorohex::mesh {

int IntervalProblem::add_curve(double length, std::string name, double target) {
  lengths.push_back(length);
  names.push_back(std::move(name));
  if (target > 0 || !targets.empty()) {
    targets.resize(lengths.size() - 1, 0.0);
    targets.push_back(target);
  }
  return int(lengths.size()) - 1;
}

double IntervalProblem::target(int c, double size) const {
  if (c < int(targets.size()) && targets[c] > 0) return targets[c];
  return lengths[c] / size;
}

void IntervalOptions::validate() const {
  core::require_positive("IntervalOptions.size", size);
  core::require_at_least("IntervalOptions.max_intervals", max_intervals, 1);
  core::require_positive("IntervalOptions.time_limit", time_limit);
}

namespace {

// How much more a refined curve's missing segment costs than an extra one (see solve()).
constexpr double kRefinedWeight = 1000;

// Which constraints take part in one solve (all, or a subset while looking for a conflict).
struct Selection {
  std::vector<char> equal, even, at_least;
};

struct Solution {
  IntervalStatus status = IntervalStatus::infeasible;
  std::vector<int> intervals;
  double deviation = 0;
};

Solution solve(const IntervalProblem& p, const IntervalOptions& o, const Selection& use) {
  const int nc = int(p.lengths.size());
  int ne = 0;
  for (std::size_t j = 0; j < p.even.size(); ++j) ne += use.even[j] ? 1 : 0;
  // Columns: n_c (integer), over_c, under_c (continuous), then one half-count per even row.
  const int ncols = 3 * nc + ne;
  std::vector<double> col_lb(ncols, 0.0), col_ub(ncols, COIN_DBL_MAX), obj(ncols, 0.0);
  CoinPackedMatrix rows(false, 0, 0);
  rows.setDimensions(0, ncols);
  std::vector<double> row_lb, row_ub;
  auto add_row = [&](const std::map<int, double>& coefs, double rhs) {
    CoinPackedVector v;
    for (const auto& [col, c] : coefs)
      if (c != 0) v.insert(col, c);
    rows.appendRow(v);
    row_lb.push_back(rhs);
    row_ub.push_back(rhs);
  };
  for (int c = 0; c < nc; ++c) {
    const double target = p.target(c, o.size);
    col_lb[c] = 1;
    col_ub[c] = o.max_intervals;
    if (c < int(p.fixed.size()) && p.fixed[c] > 0) col_lb[c] = col_ub[c] = p.fixed[c];
    const double w = 1.0 / std::max(1.0, target);
    obj[nc + c] = obj[2 * nc + c] = w;
    // A curve a local size refines: too few segments cost far more than too many, so that
    // an equality with unrefined curves (the parallel edges of a block, of a row of glued
    // blocks, a sweep's layers) keeps the refinement the user asked for instead of the
    // majority's count: in effect a lower bound that stays soft.
    if (p.target(c, o.size) > p.lengths[c] / o.size * (1 + 1e-9))
      obj[2 * nc + c] = kRefinedWeight * w;
    // n - over + under = target
    add_row({{c, 1.0}, {nc + c, -1.0}, {2 * nc + c, 1.0}}, target);
  }
  for (std::size_t j = 0; j < p.equal.size(); ++j) {
    if (!use.equal[j]) continue;
    std::map<int, double> coefs;
    for (int c : p.equal[j].lhs) coefs[c] += 1;
    for (int c : p.equal[j].rhs) coefs[c] -= 1;
    add_row(coefs, 0);
  }
  int k = 3 * nc;
  for (std::size_t j = 0; j < p.even.size(); ++j) {
    if (!use.even[j]) continue;
    std::map<int, double> coefs;
    for (int c : p.even[j].curves) coefs[c] += 1;
    coefs[k] = -double(p.even[j].multiple);
    add_row(coefs, 0);
    ++k;
  }
  for (std::size_t j = 0; j < p.at_least.size(); ++j) {
    if (!use.at_least[j]) continue;
    std::map<int, double> coefs;
    for (int c : p.at_least[j].curves) coefs[c] += 1;
    CoinPackedVector v;
    for (const auto& [col, c] : coefs) v.insert(col, c);
    rows.appendRow(v);
    row_lb.push_back(p.at_least[j].minimum);
    row_ub.push_back(COIN_DBL_MAX);
  }
  OsiClpSolverInterface solver;
  solver.messageHandler()->setLogLevel(0);
  solver.setHintParam(OsiDoReducePrint, true, OsiHintTry);
  solver.loadProblem(rows, col_lb.data(), col_ub.data(), obj.data(), row_lb.data(), row_ub.data());
  for (int c = 0; c < nc; ++c) solver.setInteger(c);
  for (int c = 3 * nc; c < ncols; ++c) solver.setInteger(c);
  CbcModel model(solver);
  model.setLogLevel(0);
  model.messageHandler()->setLogLevel(0);
  model.setMaximumSeconds(o.time_limit);
  // Gomory cuts close the gap the even sums' integer halves leave in the LP relaxation:
  // without them CBC's strong branching took 3.8-5.8 s to prove the optimum of HexMe i18's
  // ten sub-volumes (188 curves, 149 equal and 58 even sums), with them 0.15 s, the same
  // deviation (bench/results/hexme.md).
  CglGomory gomory;
  model.addCutGenerator(&gomory, -1, "Gomory");
  model.setNumberThreads(0);
  model.branchAndBound();
  Solution s;
  const double* x = model.bestSolution();
  if (x == nullptr) return s;
  s.status = model.isProvenOptimal() ? IntervalStatus::optimal : IntervalStatus::feasible;
  s.intervals.resize(nc);
  for (int c = 0; c < nc; ++c) {
    s.intervals[c] = int(std::lround(x[c]));
    const double target = p.target(c, o.size);
    s.deviation += std::abs(s.intervals[c] - target) / std::max(1.0, target);
  }
  return s;
}

void check_indices(const std::vector<int>& curves, int nc, const std::string& why) {
  for (int c : curves)
    if (c < 0 || c >= nc)
      throw std::invalid_argument("interval constraint \"" + why + "\" names curve " +
                                  std::to_string(c) + " of " + std::to_string(nc));
}

}  // namespace

IntervalResult assign_intervals(const IntervalProblem& problem, const IntervalOptions& options) {
  options.validate();
  const int nc = int(problem.lengths.size());
  if (problem.names.size() != problem.lengths.size())
    throw std::invalid_argument("IntervalProblem: one name per curve is required");
  for (int c = 0; c < nc; ++c)
    if (!std::isfinite(problem.lengths[c]) || problem.lengths[c] <= 0)
      throw std::invalid_argument("IntervalProblem: curve " + problem.names[c] +
                                  " has no positive length");
  for (const auto& e : problem.equal)
    check_indices(e.lhs, nc, e.why), check_indices(e.rhs, nc, e.why);
  for (const auto& e : problem.even) {
    check_indices(e.curves, nc, e.why);
    if (e.multiple < 2)
      throw std::invalid_argument("interval constraint '" + e.why + "': multiple " +
                                  std::to_string(e.multiple) + " is below 2");
  }
  for (const auto& e : problem.at_least) check_indices(e.curves, nc, e.why);

  IntervalResult r;
  if (nc == 0) {
    r.status = IntervalStatus::optimal;
    return r;
  }
  Selection all{std::vector<char>(problem.equal.size(), 1),
                std::vector<char>(problem.even.size(), 1),
                std::vector<char>(problem.at_least.size(), 1)};
  Solution s = solve(problem, options, all);
  if (s.status != IntervalStatus::infeasible) {
    r.status = s.status;
    r.intervals = std::move(s.intervals);
    r.deviation = s.deviation;
    return r;
  }
  // Infeasible: a deletion filter leaves a set of constraints that conflict although any
  // one of them could go (an irreducible subset), which is what the user has to look at.
  Selection conflict = all;
  const std::size_t total = problem.equal.size() + problem.even.size() + problem.at_least.size();
  if (total <= 300) {
    for (std::size_t j = 0; j < problem.equal.size(); ++j) {
      conflict.equal[j] = 0;
      if (solve(problem, options, conflict).status != IntervalStatus::infeasible)
        conflict.equal[j] = 1;
    }
    for (std::size_t j = 0; j < problem.even.size(); ++j) {
      conflict.even[j] = 0;
      if (solve(problem, options, conflict).status != IntervalStatus::infeasible)
        conflict.even[j] = 1;
    }
    for (std::size_t j = 0; j < problem.at_least.size(); ++j) {
      conflict.at_least[j] = 0;
      if (solve(problem, options, conflict).status != IntervalStatus::infeasible)
        conflict.at_least[j] = 1;
    }
  }
  std::vector<std::string> whys;
  std::vector<std::string> entities;
  auto add_names = [&](const std::vector<int>& curves) {
    for (int c : curves) entities.push_back(problem.names[c]);
  };
  for (std::size_t j = 0; j < problem.equal.size(); ++j)
    if (conflict.equal[j]) {
      whys.push_back(problem.equal[j].why);
      add_names(problem.equal[j].lhs);
      add_names(problem.equal[j].rhs);
    }
  for (std::size_t j = 0; j < problem.even.size(); ++j)
    if (conflict.even[j]) {
      whys.push_back(problem.even[j].why);
      add_names(problem.even[j].curves);
    }
  for (std::size_t j = 0; j < problem.at_least.size(); ++j)
    if (conflict.at_least[j]) {
      whys.push_back(problem.at_least[j].why);
      add_names(problem.at_least[j].curves);
    }
  std::sort(entities.begin(), entities.end());
  entities.erase(std::unique(entities.begin(), entities.end()), entities.end());
  std::ostringstream m;
  m << "No interval counts satisfy the meshing constraints together (each curve at least one "
       "segment): ";
  for (std::size_t i = 0; i < whys.size() && i < 12; ++i) m << (i ? "; " : "") << whys[i];
  if (whys.size() > 12) m << "; ... (" << whys.size() << " constraints)";
  m << ".";
  r.diagnostics.push_back(core::make_error("intervals_infeasible", m.str(), entities));
  return r;
}

}  // namespace vorohex::mesh
