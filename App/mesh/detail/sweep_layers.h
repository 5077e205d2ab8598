// Where a sweep puts the inner nodes of its layers (mesh/sweep.h). The boundary nodes of
// every layer come from the linking faces; the inner nodes from the source face's mesh:
//  - by affine maps (AffineFit): each layer's boundary fitted from the source's and the
//    target's, the inner nodes carried by both and blended (the default);
//  - or by deforming the layer below to the layer's boundary (smooth_layer_interiors),
//    where the affine maps fold: a layer whose boundary does not change by one affine map
//    (a countersunk hole's slab: the hole grows from layer to layer, the block's outline
//    stays) carries the nodes by the small hole into the large one.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include "core/geometry.h"

namespace vorohex::mesh::detail {

// Least-squares affine map between two point sets, well posed for (near-)planar sources:
// in-plane coordinates of x in its principal frame are mapped by a 3x2 matrix, the
// out-of-plane offset along the image normal scaled like the in-plane lengths.
class AffineFit {
 public:
  // Frame of the source points (computed once per source set).
  explicit AffineFit(const std::vector<core::Vec3>& x);
  // Fits the map onto y (same order as x).
  void fit(const std::vector<core::Vec3>& y);
  core::Vec3 operator()(const core::Vec3& p) const;

 private:
  core::Vec3 cx_, e1_, e2_, n_, cy_, ny_;
  std::vector<Eigen::Vector2d> a_;
  Eigen::Matrix2d ginv_;
  Eigen::Matrix<double, 3, 2> m_;
};

// Layers [first, last] (first >= 1) of the sweep's nodes P (layer k's node j at k * M + j;
// the first nb of each layer on its boundary, given): each layer's inner nodes are the layer
// below's, deformed in a few steps to the layer's boundary - per step the boundary moves a
// step's share and the inner nodes go where the mean value weights (Floater) of the step
// before put them (Gauss-Seidel sweeps until no node moves more than `tolerance`, at most
// `max_sweeps`). `onto(k, p)`, when given, puts a point of layer k back on its surface (the
// target face) in the last step. Returns the most sweeps one step took, or -1 where
// `cancelled()` said so between steps (P then half done).
int smooth_layer_interiors(std::vector<core::Vec3>& P, std::size_t M, std::size_t nb, int first,
                           int last, const std::vector<std::array<int, 4>>& quads, double tolerance,
                           int max_sweeps,
                           const std::function<core::Vec3(int, const core::Vec3&)>& onto = {},
                           const std::function<bool()>& cancelled = {});

}  // namespace vorohex::mesh::detail
