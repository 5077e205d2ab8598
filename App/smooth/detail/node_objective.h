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

namespace vorohex::smooth::detail {

// Untangling (after Knupp): every determinant of a frame containing the node - the corner
// frames and the centre frame of each incident hex - is affine in the node position, so
// det(y) = value + gradient . (y - x) exactly. Each is weighted by the product of its edge
// lengths at x (frozen), and U(y) = sum max(0, b - det(y) / weight)^2 is a convex piecewise
// quadratic whose minimum lifts every scaled corner determinant towards b.
struct AffineFrame {
  double value = 0;                          // determinant at x
  core::Vec3 gradient = core::Vec3::Zero();  // its (constant) gradient
  double weight = 1;                         // product of the frame's edge lengths at x
};

std::vector<AffineFrame> affine_frames(const std::vector<IncidentHex>& hexes, const core::Vec3& x);

// U at x + d.
double untangle_value(const std::vector<AffineFrame>& frames, const core::Vec3& d, double b);

// A displacement d = basis * z (basis: 3 x k, k = 1..3 orthonormal columns) that decreases U
// (Gauss-Newton on the active terms, backtracking), at most max_step long; zero if none.
core::Vec3 untangle_step(const std::vector<AffineFrame>& frames, double b,
                         const Eigen::Matrix<double, 3, Eigen::Dynamic>& basis, double max_step);

}  // namespace vorohex::smooth::detail
