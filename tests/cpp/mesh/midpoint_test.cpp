// Midpoint subdivision of convex polyhedra: one hexahedron per vertex where every vertex
// has three edges, four per tetrahedron of the best of three cuts into tetrahedra otherwise; the
// refined mesh is valid against the CAD (positive, conforming, closed, on the surface, same
// volume).
#include "mesh/midpoint.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "occ/primitives.h"
#include "occ/shape_io.h"
#include "quality/check_mesh.h"

namespace vorohex::mesh {
namespace {

using core::Vec3;

occ::Solid tetrahedron() {
  return occ::make_polyhedron({{0, 0, 0}, {2, 0, 0}, {1, std::sqrt(3.0), 0}, {1, 0.6, 1.6}},
                              {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}});
}

occ::Solid square_pyramid() {  // the apex has four edges
  return occ::make_polyhedron({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 1.5}},
                              {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
}

occ::Solid octahedron() {
  return occ::make_polyhedron(
      {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
      {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}});
}

// min_sj: one hexahedron per vertex gives the corner angles of the solid (0.71 for a regular
// tetrahedron); through tetrahedra, those of the tetrahedra the cell is cut into (0.5 for an
// equilateral square pyramid and the octahedron, cut from one vertex; Gmsh's automatic
// all-hex gives 0.006-0.02 on HexMe's pyramids and octahedron).
void expect_valid(const occ::Solid& solid, const MidpointResult& r, double min_sj) {
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : r.diagnostics[0].message);
  quality::CheckOptions opt;
  const quality::CheckReport c = quality::check_mesh(r.mesh, &solid, opt);
  EXPECT_TRUE(c.valid) << (c.diagnostics.empty() ? "" : c.diagnostics[0].message);
  EXPECT_GT(c.scaled_jacobian.min, min_sj);
  EXPECT_NEAR(c.mesh_volume, solid.volume(), 1e-9 * solid.volume());
}

TEST(Midpoint, TetrahedronGetsOneHexPerVertex) {
  const occ::Solid s = tetrahedron();
  ASSERT_TRUE(midpoint_applicable(s).ok) << midpoint_applicable(s).reason;
  MidpointOptions opt;
  opt.size = 10;  // coarser than the solid: no refinement
  const MidpointResult coarse = midpoint_subdivide(s, opt);
  EXPECT_TRUE(coarse.per_vertex);
  EXPECT_EQ(coarse.subdivisions, 1);
  EXPECT_EQ(coarse.mesh.num_hexes(), 4u);
  // 4 vertices + 6 edge midpoints + 4 face centres + 1 centre.
  EXPECT_EQ(coarse.mesh.num_nodes(), 15u);
  expect_valid(s, coarse, 0.5);

  opt.size = 0.2;
  const MidpointEstimate e = midpoint_evaluate(s, opt);
  const MidpointResult fine = midpoint_subdivide(s, opt);
  EXPECT_GT(fine.subdivisions, 1);
  EXPECT_EQ(e.hexes, fine.mesh.num_hexes());
  EXPECT_EQ(e.nodes, fine.mesh.num_nodes());
  EXPECT_EQ(fine.mesh.num_hexes(), 4u * fine.subdivisions * fine.subdivisions * fine.subdivisions);
  expect_valid(s, fine, 0.5);
}

TEST(Midpoint, VerticesWithMoreEdgesGoThroughTheBestTetrahedra) {
  // The square pyramid is two tetrahedra along a diagonal of its base (cut by the
  // centre, the face centres and the edges, as before, its hexahedra reached only 0.17 on
  // HexMe n09), the octahedron four around the axis from one vertex to the opposite one
  // (0.29 so): cones from one vertex over the faces away from it.
  const struct {
    occ::Solid solid;
    std::size_t tetrahedra;
    double min_sj;
  } cases[] = {{square_pyramid(), 2, 0.45}, {octahedron(), 4, 0.45}};
  for (const auto& c : cases) {
    const occ::Solid& s = c.solid;
    ASSERT_TRUE(midpoint_applicable(s).ok) << midpoint_applicable(s).reason;
    MidpointOptions opt;
    opt.size = 0.15;
    const MidpointEstimate e = midpoint_evaluate(s, opt);
    const MidpointResult r = midpoint_subdivide(s, opt);
    EXPECT_FALSE(r.per_vertex);
    EXPECT_NE(r.variant.find("cones from Vertex"), std::string::npos) << r.variant;
    EXPECT_EQ(e.coarse_hexes, 4 * c.tetrahedra);
    EXPECT_EQ(e.hexes, r.mesh.num_hexes());
    EXPECT_EQ(e.nodes, r.mesh.num_nodes());
    expect_valid(s, r, c.min_sj);
  }
}

TEST(Midpoint, TheIcosahedronIsConesFromItsCentreOnHexMeN15) {
  // Twenty tetrahedra of the centre and a face: 0.69 (0.30 through face centres, 0.26 as
  // cones from a vertex).
  const occ::ReadResult in =
      occ::read_solid(std::string(VOROHEX_HEXME_DIR) + "/n15o_icosahedron.step");
  ASSERT_TRUE(in.ok()) << "HexMe model n15 not found in " << VOROHEX_HEXME_DIR;
  const occ::Solid& s = *in.solid;
  MidpointOptions opt;
  opt.size = s.diagonal() / 20;
  const MidpointEstimate e = midpoint_evaluate(s, opt);
  const MidpointResult r = midpoint_subdivide(s, opt);
  EXPECT_NE(r.variant.find("centre over each face"), std::string::npos) << r.variant;
  EXPECT_EQ(e.coarse_hexes, 4u * 20u);
  expect_valid(s, r, 0.65);
}

TEST(Midpoint, CubeIsAlsoAcceptedAndEveryNodeIsClassified) {
  const occ::Solid s = occ::make_box(1, 1, 1);
  MidpointOptions opt;
  opt.size = 0.2;
  const MidpointResult r = midpoint_subdivide(s, opt);
  EXPECT_TRUE(r.per_vertex);
  expect_valid(s, r, 0.5);
  // Nodes on the boundary carry a model entity: count those on faces of the unit cube.
  std::size_t on_boundary = 0, classified = 0;
  for (std::size_t i = 0; i < r.mesh.num_nodes(); ++i) {
    const Vec3& p = r.mesh.points()[i];
    const bool boundary = p.minCoeff() < 1e-12 || p.maxCoeff() > 1 - 1e-12;
    on_boundary += boundary;
    classified += boundary && !r.mesh.node_classes()[i].is_interior();
    EXPECT_EQ(boundary, !r.mesh.node_classes()[i].is_interior()) << i;
  }
  EXPECT_EQ(on_boundary, classified);
}

TEST(Midpoint, NonConvexOrCurvedSolidsAreRefusedWithTheReason) {
  const occ::Solid l = occ::make_prism({{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}}, 1);
  const Applicability a = midpoint_applicable(l);
  EXPECT_FALSE(a.ok);
  EXPECT_NE(a.reason.find("not convex"), std::string::npos) << a.reason;
  const Applicability c = midpoint_applicable(occ::make_cylinder(1, 2));
  EXPECT_FALSE(c.ok);
  EXPECT_FALSE(c.reason.empty());
  MidpointOptions opt;
  const MidpointResult r = midpoint_subdivide(l, opt);
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics[0].code, "midpoint_not_applicable");
  opt.size = -1;
  EXPECT_THROW(midpoint_subdivide(l, opt), std::invalid_argument);
}

}  // namespace
}  // namespace vorohex::mesh
