// The local objective a single node descends in the untangling and optimisation phases:
// the sum, over the hex corners whose frame contains the node, of the inverse mean ratio
// |A|_F^2 / (3 h(det A)^(2/3)) with Escobar et al.'s regularised determinant
// h(s) = (s + sqrt(s^2 + 4 delta^2)) / 2, which stays positive (so the objective finite) for
// inverted corners and equals det A when delta = 0 and det A > 0.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include "core/geometry.h"

namespace vorohex::smooth::detail {

// One incident hex: its corner points with the moving node at local index `corner`
// (whose stored value is ignored; the trial position is passed separately).
struct IncidentHex {
  std::array<core::Vec3, 8> points;
  int corner = 0;
};

struct ObjectiveValue {
  double value = 0;
  core::Vec3 gradient = core::Vec3::Zero();
  double min_det = 0;    // smallest corner determinant among the frames containing the node
  double mean_edge = 0;  // mean length of the frame edges
};

// Value, gradient with respect to the node position x and corner statistics.
ObjectiveValue node_objective(const std::vector<IncidentHex>& hexes, const core::Vec3& x,
                              double delta);

// Value only (for line searches).
double node_objective_value(const std::vector<IncidentHex>& hexes, const core::Vec3& x,
                            double delta);

// Regularisation for a neighbourhood whose smallest corner determinant is min_det and
// whose edges are about mean_edge long: 0 when all corners are comfortably positive,
// growing with the inversion otherwise.
double choose_delta(double min_det, double mean_edge);

}  // namespace vorohex::smooth::detail
