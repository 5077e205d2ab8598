#include "mesh/map_block.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include "occ/primitives.h"

namespace vorohex::mesh {
namespace {

using core::EdgeId;
using core::FaceId;
using core::HexId;
using core::NodeId;
using core::Vec3;
using core::VertexId;

// Exact volume of a trilinear hex in VTK order by 2x2x2 Gauss quadrature of det J, and the
// smallest det J at its corners (positive for a valid hex).
struct HexMeasure {
  double volume = 0;
  double min_corner_det = 0;
};

HexMeasure measure(const std::array<Vec3, 8>& vtk) {
  // VTK order -> lattice order c[i + 2j + 4k].
  const std::array<Vec3, 8> c = {vtk[0], vtk[1], vtk[3], vtk[2], vtk[4], vtk[5], vtk[7], vtk[6]};
  auto jacobian_det = [&](double u, double v, double w) {
    const double U[2] = {1 - u, u}, V[2] = {1 - v, v}, W[2] = {1 - w, w};
    Vec3 du = Vec3::Zero(), dv = Vec3::Zero(), dw = Vec3::Zero();
    for (int n = 0; n < 8; ++n) {
      const int i = n & 1, j = (n >> 1) & 1, k = n >> 2;
      du += (i ? 1.0 : -1.0) * V[j] * W[k] * c[n];
      dv += (j ? 1.0 : -1.0) * U[i] * W[k] * c[n];
      dw += (k ? 1.0 : -1.0) * U[i] * V[j] * c[n];
    }
    return du.cross(dv).dot(dw);
  };
  HexMeasure m;
  const double g[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  for (double u : g)
    for (double v : g)
      for (double w : g) m.volume += jacobian_det(u, v, w) / 8;
  m.min_corner_det = std::numeric_limits<double>::infinity();
  for (int n = 0; n < 8; ++n)
    m.min_corner_det = std::min(m.min_corner_det, jacobian_det(n & 1, (n >> 1) & 1, n >> 2));
  return m;
}

// Checks every invariant of a mapped mesh of `solid`; returns the mesh volume.
double check_mesh(const occ::Solid& solid, const MapBlockResult& r) {
  EXPECT_TRUE(r.ok);
  const auto& n = r.intervals;
  EXPECT_EQ(r.mesh.num_nodes(), std::size_t(n[0] + 1) * (n[1] + 1) * (n[2] + 1));
  EXPECT_EQ(r.mesh.num_hexes(), std::size_t(n[0]) * n[1] * n[2]);
  const double tol = 1e-9 * solid.diagonal();
  std::array<std::size_t, 4> per_dim{};
  for (std::size_t i = 0; i < r.mesh.num_nodes(); ++i) {
    const NodeId id(static_cast<std::int32_t>(i));
    const Vec3& p = r.mesh.point(id);
    const core::NodeClass c = r.mesh.node_class(id);
    ++per_dim[c.dim];
    if (c.dim == 0) EXPECT_LT(solid.distance_to_vertex(VertexId(c.id), p), tol) << i;
    if (c.dim == 1) EXPECT_LT(solid.distance_to_edge(EdgeId(c.id), p), tol) << i;
    if (c.dim == 2) EXPECT_LT(solid.distance_to_face(FaceId(c.id), p), tol) << i;
  }
  EXPECT_EQ(per_dim[0], 8u);
  EXPECT_EQ(per_dim[1], 4u * (n[0] - 1 + n[1] - 1 + n[2] - 1));
  EXPECT_EQ(per_dim[2],
            2u * ((n[0] - 1) * (n[1] - 1) + (n[1] - 1) * (n[2] - 1) + (n[0] - 1) * (n[2] - 1)));
  EXPECT_EQ(per_dim[3], std::size_t(n[0] - 1) * (n[1] - 1) * (n[2] - 1));
  double volume = 0;
  int inverted = 0;
  for (std::size_t h = 0; h < r.mesh.num_hexes(); ++h) {
    const HexMeasure m = measure(r.mesh.corners(HexId(static_cast<std::int32_t>(h))));
    volume += m.volume;
    if (m.min_corner_det <= 0) ++inverted;
    EXPECT_EQ(r.mesh.sub_volume(HexId(static_cast<std::int32_t>(h))), 0);
  }
  EXPECT_EQ(inverted, 0);
  return volume;
}

TEST(MapBlock, BoxGivesIntervalsFromTheSize) {
  const occ::Solid box = occ::make_box(3, 2, 1);
  ASSERT_TRUE(map_block_applicable(box).ok);
  MapBlockOptions opt;
  opt.size = 0.25;
  const MapBlockResult r = map_block(box, opt);
  std::array<int, 3> sorted = r.intervals;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, (std::array<int, 3>{4, 8, 12}));
  const double volume = check_mesh(box, r);
  EXPECT_NEAR(volume, box.volume(), 1e-9 * box.volume());
  const MapBlockEstimate e = map_block_evaluate(box, opt);
  EXPECT_EQ(e.intervals, r.intervals);
  EXPECT_EQ(e.nodes, r.mesh.num_nodes());
  EXPECT_EQ(e.hexes, r.mesh.num_hexes());
  EXPECT_EQ(e.nodes, 13u * 9u * 5u);
  EXPECT_EQ(e.hexes, 12u * 8u * 4u);
}

TEST(MapBlock, TaperedBrickVolumeIsExact) {
  const occ::Solid brick = occ::make_tapered_brick(3, 2, 1, 0.5);
  MapBlockOptions opt;
  opt.size = 0.2;
  const MapBlockResult r = map_block(brick, opt);
  const double volume = check_mesh(brick, r);
  EXPECT_NEAR(volume, brick.volume(), 1e-9 * brick.volume());
  const MapBlockEstimate e = map_block_evaluate(brick, opt);
  EXPECT_EQ(e.intervals, r.intervals);
  EXPECT_EQ(e.nodes, r.mesh.num_nodes());
  EXPECT_EQ(e.hexes, r.mesh.num_hexes());
}

TEST(MapBlock, SkewedPolyhedronIsPositive) {
  // A general hexahedron with planar faces (a frustum, sheared), built with reversed faces.
  const double s = 0.3;
  const std::vector<Vec3> p = {{0, 0, 0},   {2, 0, 0},       {2, 1, 0},       {0, 1, 0},
                               {s, 0.1, 1}, {1 + s, 0.1, 1}, {1 + s, 0.6, 1}, {s, 0.6, 1}};
  const occ::Solid solid = occ::make_polyhedron(
      p, {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}});
  MapBlockOptions opt;
  opt.size = 0.1;
  const MapBlockResult r = map_block(solid, opt);
  EXPECT_NEAR(check_mesh(solid, r), solid.volume(), 1e-9 * solid.volume());
}

TEST(MapBlock, CurvedFacesCarryTheirNodes) {
  const double ri = 1, ro = 2, angle = 1.5, depth = 0.5;
  const occ::Solid ring = occ::make_ring_sector(ri, ro, angle, depth);
  ASSERT_TRUE(map_block_applicable(ring).ok) << map_block_applicable(ring).reason;
  MapBlockOptions opt;
  opt.size = 0.1;
  const MapBlockResult r = map_block(ring, opt);
  const double volume = check_mesh(ring, r);
  // Chords cut the arcs: the mesh is slightly smaller than the solid, converging as h^2.
  EXPECT_LT(volume, ring.volume());
  EXPECT_NEAR(volume, ring.volume(), 2e-3 * ring.volume());
  // Nodes on the cylindrical faces lie on the cylinders.
  int on_curved = 0;
  for (std::size_t i = 0; i < r.mesh.num_nodes(); ++i) {
    const core::NodeClass c = r.mesh.node_class(NodeId(static_cast<std::int32_t>(i)));
    if (c.dim != 2 || ring.face_is_planar(FaceId(c.id))) continue;
    const Vec3& q = r.mesh.point(NodeId(static_cast<std::int32_t>(i)));
    const double rad = std::hypot(q.x(), q.y());
    EXPECT_LT(std::min(std::abs(rad - ri), std::abs(rad - ro)), 1e-9);
    ++on_curved;
  }
  EXPECT_GT(on_curved, 0);
  int curved_faces = 0;
  for (FaceId f : ring.faces()) curved_faces += !ring.face_is_planar(f);
  EXPECT_EQ(curved_faces, 2);
}

// A half ring (its eight corners in one plane: the hexahedron through them is flat, and its
// sign said nothing) and three quarters of one (that hexahedron inside out): the mesh was
// mapped inside out, every hexahedron inverted (a pillow block's bore chamfer slab, half a
// ring 1 thick, was). The lattice's own volume decides the orientation.
TEST(MapBlock, RingSectorsOfHalfATurnAndMoreAreNotMappedInsideOut) {
  for (double angle : {M_PI, 1.5 * M_PI}) {
    SCOPED_TRACE(angle);
    const occ::Solid ring = occ::make_ring_sector(16, 25, angle, 1);
    ASSERT_TRUE(map_block_applicable(ring).ok) << map_block_applicable(ring).reason;
    MapBlockOptions opt;
    opt.size = 7.5;
    const MapBlockResult r = map_block(ring, opt);
    EXPECT_GT(check_mesh(ring, r), 0.9 * ring.volume());
  }
}

TEST(MapBlock, NonBlocksAreRefusedWithAReason) {
  const Applicability cyl = map_block_applicable(occ::make_cylinder(1, 2));
  EXPECT_FALSE(cyl.ok);
  EXPECT_NE(cyl.reason.find("the solid has 3 faces"), std::string::npos) << cyl.reason;
  const occ::Solid l_prism = occ::make_prism({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, 1);
  const Applicability l = map_block_applicable(l_prism);
  EXPECT_FALSE(l.ok);
  EXPECT_NE(l.reason.find("the solid has 8 faces"), std::string::npos) << l.reason;
  // A prism of a pentagon has 7 faces; a wedge made with 6 faces of which one is a
  // pentagon is caught by the edge count of that face.
  const occ::Solid house = occ::make_prism({{0, 0}, {2, 0}, {2, 1}, {1, 2}, {0, 1}}, 1);
  EXPECT_NE(map_block_applicable(house).reason.find("7 faces"), std::string::npos);
  const occ::Solid plate =
      occ::make_prism({{0, 0}, {4, 0}, {4, 4}, {0, 4}}, 1, {{{1, 1}, {2, 1}, {2, 2}, {1, 2}}});
  EXPECT_FALSE(map_block_applicable(plate).ok);
  MapBlockOptions opt;
  opt.size = 0.5;
  const MapBlockResult r = map_block(l_prism, opt);
  EXPECT_FALSE(r.ok);
  ASSERT_EQ(r.diagnostics.size(), 1u);
  EXPECT_EQ(r.diagnostics[0].code, "not_applicable");
  EXPECT_EQ(r.mesh.num_nodes(), 0u);
  EXPECT_EQ(map_block_evaluate(l_prism, opt).hexes, 0u);
}

TEST(MapBlock, FaceWithFiveEdgesIsNamed) {
  // Six faces, but the bottom is a pentagon (a vertex in the middle of one bottom edge).
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0},
                               {0, 0, 1}, {2, 0, 1}, {2, 1, 1}, {0, 1, 1}};
  const occ::Solid s = occ::make_polyhedron(
      p,
      {{0, 1, 2, 3, 4}, {5, 6, 7, 8}, {0, 1, 2, 6, 5}, {2, 3, 7, 6}, {3, 4, 8, 7}, {4, 0, 5, 8}});
  ASSERT_EQ(s.num_faces(), 6);
  const Applicability a = map_block_applicable(s);
  EXPECT_FALSE(a.ok);
  EXPECT_NE(a.reason.find("has 5 edges"), std::string::npos) << a.reason;
  EXPECT_EQ(a.reason.rfind("Face", 0), 0u) << a.reason;
}

TEST(MapBlock, BadOptionsThrowNamingTheField) {
  const occ::Solid box = occ::make_box(1, 1, 1);
  for (double size : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    MapBlockOptions opt;
    opt.size = size;
    try {
      map_block(box, opt);
      ADD_FAILURE() << "size " << size << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("size"), std::string::npos);
    }
    EXPECT_THROW(map_block_evaluate(box, opt), std::invalid_argument);
  }
  MapBlockOptions opt;
  opt.max_intervals = 0;
  EXPECT_THROW(opt.validate(), std::invalid_argument);
}

TEST(MapBlock, TooManyIntervalsAreRefused) {
  const occ::Solid box = occ::make_box(10, 1, 1);
  MapBlockOptions opt;
  opt.size = 0.1;
  opt.max_intervals = 50;
  const MapBlockResult r = map_block(box, opt);
  EXPECT_FALSE(r.ok);
  ASSERT_EQ(r.diagnostics.size(), 1u);
  EXPECT_EQ(r.diagnostics[0].code, "too_many_intervals");
  EXPECT_EQ(r.diagnostics[0].entities.size(), 4u);
  EXPECT_EQ(map_block_evaluate(box, opt).nodes, 0u);
}

TEST(MapBlock, CancelStopsWithADiagnostic) {
  std::atomic<bool> cancel{false};
  int reports = 0;
  const core::Progress progress(
      [&](std::string_view, double fraction) {
        EXPECT_GE(fraction, 0.0);
        EXPECT_LE(fraction, 1.0);
        if (++reports == 3) cancel = true;
      },
      &cancel);
  MapBlockOptions opt;
  opt.size = 0.05;
  const MapBlockResult r = map_block(occ::make_box(1, 1, 1), opt, progress);
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics.back().code, "cancelled");
  EXPECT_EQ(reports, 3);
}

// A million hexes (the time is printed and measured in bench/, not asserted here).
TEST(MapBlock, MillionHexBox) {
  const occ::Solid box = occ::make_box(1, 1, 1);
  MapBlockOptions opt;
  opt.size = 0.01;
  const auto t0 = std::chrono::steady_clock::now();
  const MapBlockResult r = map_block(box, opt);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.mesh.num_hexes(), 1000000u);
  EXPECT_EQ(r.mesh.num_nodes(), 101u * 101u * 101u);
  RecordProperty("seconds", std::to_string(seconds));
  std::printf("map_block 100^3 box: %.3f s\n", seconds);
}

}  // namespace
}  // namespace vorohex::mesh

namespace vorohex::mesh {
namespace {

TEST(MapBlockGivenIntervals, UsesThemAndRefusesParallelEdgesThatDiffer) {
  const occ::Solid box = occ::make_box(3, 2, 1);
  const auto groups = map_block_edge_groups(box);
  for (const auto& g : groups) ASSERT_EQ(g.size(), 4u);
  MapBlockOptions o;
  o.edge_intervals.assign(box.num_edges() + 1, 0);
  const int want[3] = {7, 3, 2};
  for (int d = 0; d < 3; ++d)
    for (core::EdgeId e : groups[d]) o.edge_intervals[e.value()] = want[d];
  const MapBlockResult r = map_block(box, o);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.mesh.num_hexes(), std::size_t(7 * 3 * 2));
  o.edge_intervals[groups[1][2].value()] = 4;
  const MapBlockResult bad = map_block(box, o);
  EXPECT_FALSE(bad.ok);
  ASSERT_FALSE(bad.diagnostics.empty());
  EXPECT_EQ(bad.diagnostics[0].code, "intervals_mismatch");
  EXPECT_TRUE(map_block_edge_groups(occ::make_prism({{0, 0}, {2, 0}, {1, 1}}, 1))[0].empty());
}

}  // namespace
}  // namespace vorohex::mesh
