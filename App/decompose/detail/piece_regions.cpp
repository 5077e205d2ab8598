#include "decompose/detail/piece_regions.h"

#include <algorithm>
#include <cmath>

#include "decompose/detail/cut_surfaces.h"

namespace vorohex::decompose::detail {

using core::FaceId;
using core::Vec3;

// Whether a face of the piece lies on one of the holes' cylinders.
bool on_a_hole(const occ::Solid& piece, const std::vector<occ::CutCylinder>& holes) {
  const double tol = 1e-7 * piece.diagonal();
  for (FaceId f : piece.faces()) {
    occ::CutCylinder c;
    if (!occ::face_cylinder(piece, f, &c)) continue;
    for (const occ::CutCylinder& h : holes)
      if (same_cylinder(c, h, std::max(tol, 1e-9 * h.radius))) return true;
  }
  return false;
}

// Whether every vertex of the piece lies in the band.
bool within(const occ::Solid& piece, const Band& b) {
  const double tol = 1e-6 * piece.diagonal();
  for (core::VertexId v : piece.vertices()) {
    const double h = b.normal.dot(piece.vertex_point(v));
    if (h < b.lo - tol || h > b.hi + tol) return false;
  }
  return true;
}

// Whether the piece's box meets the band's fillet's.
bool beside_fillet(const occ::Solid& piece, const Band& b) {
  const double tol = 1e-6 * piece.diagonal();
  const core::BoundingBox box = piece.bounding_box();
  for (int i = 0; i < 3; ++i)
    if (box.max[i] < b.along.min[i] - tol || box.min[i] > b.along.max[i] + tol) return false;
  return true;
}

// A piece of the boss a cylinder through a fillet's foot cut out of its plate.
bool within(const occ::Solid& piece, const occ::CutCylinder& c) {
  const double tol = 1e-6 * piece.diagonal() + 1e-9 * c.radius;
  for (core::VertexId v : piece.vertices()) {
    const Vec3 d = piece.vertex_point(v) - c.origin;
    if ((d - d.dot(c.axis) * c.axis).norm() > c.radius + tol) return false;
  }
  return true;
}

}  // namespace vorohex::decompose::detail
