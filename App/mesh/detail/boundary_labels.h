// The model face of each boundary facet of the tet split's tetrahedra, and through them of
// their boundary edges and nodes (which model face the split's boundary nodes go onto).
// CGAL names the facets of its surface (each with its patch, the model face), but these are
// not always the boundary of the tetrahedra it keeps: at thin walls a tetrahedron of the
// complex can lie beyond a surface facet (HexMe i04, i07, i09, i19, n10: up to 122 surface
// facets inside the mesh, and boundary facets without a name). The labels follow the
// tetrahedra's own boundary: a surface facet inside is none, and a boundary facet CGAL did
// not name takes the model face nearest its centre.
#pragma once

#include <array>
#include <map>
#include <vector>

#include "core/geometry.h"
#include "occ/solid.h"

namespace vorohex::mesh::detail {

struct BoundaryLabels {
  std::map<std::array<int, 3>, int> facet_face;  // sorted nodes -> model face
  std::map<std::array<int, 2>, int> edge_face;   // sorted nodes -> model face
  std::vector<int> node_face;                    // per point; 0: not on the boundary
};

// The sorted nodes of tetrahedron t's facet opposite its corner `skip` (0-3).
std::array<int, 3> facet_of(const std::array<int, 4>& t, int skip);

// tets: node indices into points; surface_facets (sorted nodes) with surface_patch, the
// model face of each (out-of-range patches are ignored). Where a node or edge lies on
// facets of several faces, the last facet named wins (CGAL's order, then the unnamed ones).
BoundaryLabels boundary_labels(const std::vector<std::array<int, 4>>& tets,
                               const std::vector<core::Vec3>& points,
                               const std::vector<std::array<int, 3>>& surface_facets,
                               const std::vector<int>& surface_patch, const occ::Solid& solid);

}  // namespace vorohex::mesh::detail
