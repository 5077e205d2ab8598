#include "mesh/detail/boundary_labels.h"

#include <gtest/gtest.h>

#include "occ/primitives.h"

namespace vorohex::mesh::detail {
namespace {

using core::Vec3;

// Two tetrahedra on the floor of a unit box, sharing the facet {1, 2, 3}. CGAL's surface
// facets as at HexMe i04's thin walls: the shared facet named (it lies inside the mesh) and
// one of the boundary facets not named. The labels follow the tetrahedra's boundary.
TEST(BoundaryLabels, FollowTheTetrahedrasOwnBoundaryNotCgalsSurfaceFacets) {
  const occ::Solid box = occ::make_box(1, 1, 1);
  const std::vector<Vec3> points{
      {0.2, 0.2, 0}, {0.8, 0.2, 0}, {0.5, 0.8, 0}, {0.5, 0.4, 0.3}, {0.9, 0.9, 0.05}};
  const std::vector<std::array<int, 4>> tets{{0, 1, 2, 3}, {1, 2, 3, 4}};
  const int floor = box.nearest_face(Vec3(0.5, 0.4, 0)).value();
  const std::vector<std::array<int, 3>> surface{{1, 2, 3}, {0, 1, 2}};
  const std::vector<int> patch{floor, floor};
  const BoundaryLabels labels = boundary_labels(tets, points, surface, patch, box);

  EXPECT_EQ(labels.facet_face.count({1, 2, 3}), 0u);  // inside: no face
  ASSERT_EQ(labels.facet_face.count({0, 1, 2}), 1u);
  EXPECT_EQ(labels.facet_face.at({0, 1, 2}), floor);  // named by CGAL, kept
  // The six boundary facets all have a face; the ones CGAL did not name the nearest one.
  EXPECT_EQ(labels.facet_face.size(), 6u);
  for (const std::array<int, 3> k :
       {std::array<int, 3>{0, 1, 3}, {0, 2, 3}, {1, 2, 4}, {1, 3, 4}, {2, 3, 4}}) {
    ASSERT_EQ(labels.facet_face.count(k), 1u);
    const Vec3 c = (points[k[0]] + points[k[1]] + points[k[2]]) / 3.0;
    EXPECT_EQ(labels.facet_face.at(k), box.nearest_face(c).value());
  }
  // Edges and nodes through the facets: the edge {2, 3} of the inside facet is on the
  // boundary through {0, 2, 3} and {2, 3, 4}; every node is on the boundary.
  EXPECT_EQ(labels.edge_face.count({2, 3}), 1u);
  for (int v = 0; v < 5; ++v) EXPECT_GT(labels.node_face[v], 0) << v;
  // A patch out of range is ignored (the facet is then labelled as an unnamed one).
  const BoundaryLabels other = boundary_labels(tets, points, {{0, 1, 2}}, {99}, box);
  EXPECT_EQ(other.facet_face.at({0, 1, 2}), box.nearest_face(Vec3(0.5, 0.4, 0)).value());
}

}  // namespace
}  // namespace vorohex::mesh::detail
