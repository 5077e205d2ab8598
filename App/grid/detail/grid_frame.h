// The frame of the grid mesher's core grid: three orthonormal axes aligned with the part
// (the normals of its largest planar faces, or the axis of a turned part) and, per axis,
// the positions of the grid planes (a tensor grid: planes of model faces normal to an axis
// are grid planes, the intervals between them divided into cells of about the size).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/mesh_domain.h"

namespace vorohex::grid::detail {

struct GridFrame {
  std::array<core::Vec3, 3> axes;            // orthonormal, right-handed
  std::array<std::vector<double>, 3> lines;  // per axis: increasing plane offsets (p . axis)
  std::string how;                           // what the axes were taken from

  int nodes(int a) const { return int(lines[a].size()); }
  int cells(int a) const { return int(lines[a].size()) - 1; }
  core::Vec3 point(int i, int j, int k) const {
    return axes[0] * lines[0][i] + axes[1] * lines[1][j] + axes[2] * lines[2][k];
  }
  core::Vec3 to_frame(const core::Vec3& p) const {
    return {p.dot(axes[0]), p.dot(axes[1]), p.dot(axes[2])};
  }
};

// `boundary_points`: points on the solid's boundary (its tessellation) giving its extent.
// Planes closer than min_gap * size to a larger one are not made grid planes.
GridFrame grid_frame(const core::MeshDomain& solid, const std::vector<core::Vec3>& boundary_points,
                     double size, double min_gap = 0.5);

}  // namespace vorohex::grid::detail
