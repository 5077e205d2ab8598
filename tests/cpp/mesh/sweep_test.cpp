#include "mesh/sweep.h"

#include <gtest/gtest.h>
#include <BRepAlgoAPI_Common.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Ax2.hxx>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "occ/primitives.h"
#include "occ/solid_impl.h"
#include "occ/split_solid.h"
#include "quality/check_mesh.h"

namespace vorohex::mesh {
namespace {

using core::FaceId;
using core::Vec3;
using Outline = std::vector<std::array<double, 2>>;

struct Figures {
  double min = 0, mean = 0;
};

// Every invariant of a swept mesh: applicable, evaluate == compute, check_mesh valid
// against the CAD (positive, conforming, closed, volume, nodes on their entities).
Figures sweep_and_check(const std::string& label, const occ::Solid& solid, double size,
                        bool planar) {
  const SweepApplicability a = sweep_applicable(solid);
  EXPECT_TRUE(a.ok) << label << ": " << a.reason;
  SweepOptions o;
  o.size = size;
  const SweepEstimate e = sweep_evaluate(solid, o);
  const SweepResult r = sweep(solid, o);
  EXPECT_TRUE(r.ok) << label << ": "
                    << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
  EXPECT_EQ(r.source, a.source);
  EXPECT_EQ(r.target, a.target);
  EXPECT_EQ(e.layers, r.layers);
  EXPECT_EQ(e.nodes, r.mesh.num_nodes());
  EXPECT_EQ(e.hexes, r.mesh.num_hexes());
  EXPECT_GT(r.mesh.num_hexes(), 0u);
  const quality::CheckReport c = quality::check_mesh(r.mesh, &solid);
  EXPECT_TRUE(c.valid) << label << ": "
                       << (c.diagnostics.empty() ? "" : core::format(c.diagnostics[0]));
  EXPECT_EQ(c.non_positive, 0u);
  EXPECT_EQ(c.unused_nodes, 0u);
  if (planar) {
    EXPECT_LE(c.volume_rel_error, 1e-9) << label;
    EXPECT_GE(c.scaled_jacobian.min, 0.3) << label;
    EXPECT_GE(c.scaled_jacobian.mean, 0.85) << label;
  } else {
    EXPECT_GE(c.scaled_jacobian.min, 0.3) << label;
  }
  std::printf("[sweep] %-22s %s->%s layers %3d hexes %7zu  SJ min %.3f mean %.3f  vol err %.1e\n",
              label.c_str(), core::entity_name(r.source).c_str(),
              core::entity_name(r.target).c_str(), r.layers, r.mesh.num_hexes(),
              c.scaled_jacobian.min, c.scaled_jacobian.mean, c.volume_rel_error);
  return {c.scaled_jacobian.min, c.scaled_jacobian.mean};
}

const Outline kL = {{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}};

TEST(Sweep, LShapedExtrusionsThickAndThin) {
  sweep_and_check("L depth 3", occ::make_prism(kL, 3), 0.25, true);
  sweep_and_check("L depth 0.4", occ::make_prism(kL, 0.4), 0.25, true);
  sweep_and_check("L depth 3, size 0.3", occ::make_prism(kL, 3), 0.3, true);
}

TEST(Sweep, TAndUExtrusions) {
  sweep_and_check(
      "T", occ::make_prism({{2, 0}, {3, 0}, {3, 2}, {5, 2}, {5, 3}, {0, 3}, {0, 2}, {2, 2}}, 2),
      0.25, true);
  sweep_and_check(
      "U", occ::make_prism({{0, 0}, {5, 0}, {5, 4}, {4, 4}, {4, 1}, {1, 1}, {1, 4}, {0, 4}}, 1.5),
      0.25, true);
}

TEST(Sweep, PlatesWithHoles) {
  const Outline plate = {{0, 0}, {10, 0}, {10, 6}, {0, 6}};
  sweep_and_check(
      "plate, 2 square holes",
      occ::make_prism(plate, 1,
                      {{{2, 2}, {4, 2}, {4, 4}, {2, 4}}, {{6, 2}, {8, 2}, {8, 4}, {6, 4}}}),
      0.25, true);
  Outline round;  // a 24-gon: make_prism takes polygonal holes
  for (int i = 0; i < 24; ++i)
    round.push_back({5 + 1.5 * std::cos(2 * M_PI * i / 24), 3 + 1.5 * std::sin(2 * M_PI * i / 24)});
  sweep_and_check("plate, round hole", occ::make_prism(plate, 1, {round}), 0.25, true);
}

TEST(Sweep, SteppedPrismAndBox) {
  sweep_and_check(
      "stepped prism",
      occ::make_prism({{0, 0}, {6, 0}, {6, 1}, {4, 1}, {4, 2}, {2, 2}, {2, 3}, {0, 3}}, 2), 0.25,
      true);
  const occ::Solid box = occ::make_box(2, 3, 1);
  sweep_and_check("box", box, 0.25, true);
  // The box is swept through its shortest direction (z).
  const auto a = sweep_applicable(box);
  EXPECT_NEAR(std::abs(box.face_normal(a.source, box.vertex_point(core::VertexId(1))).z()), 1,
              1e-9);
}

TEST(Sweep, CylinderIsADiscSwept) {
  const occ::Solid cyl = occ::make_cylinder(1, 2);
  const Figures f = sweep_and_check("cylinder", cyl, 0.15, false);
  EXPECT_GE(f.mean, 0.85);
  const auto a = sweep_applicable(cyl);
  EXPECT_TRUE(cyl.face_is_planar(a.source));
}

// A block of a ball's octant, between a face of an inner cube at the centre and the sphere
// (the corner of a box whose top and vertical edges are filleted, parted like a cube's
// corner): the sphere's pole is a corner of the block's round face, where OCCT puts a
// degenerated edge beside two arcs. That is no apex inside the target (as a drill point's
// is), and no inner node of the target goes to it: it was taken for one, and the node of the
// target nearest the pole put on it folded the layers.
TEST(Sweep, ASpherePoleAtACornerOfTheTargetIsNoApex) {
  const double r = 2, a = 0.64, far = 3;
  const TopoDS_Shape octant =
      BRepAlgoAPI_Common(
          BRepPrimAPI_MakeSphere(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), r).Shape(),
          BRepPrimAPI_MakeBox(r, r, r).Shape())
          .Shape();
  TopExp_Explorer ex(octant, TopAbs_SOLID);
  ASSERT_TRUE(ex.More());
  const occ::Solid ball_octant = occ::make_solid(TopoDS::Solid(ex.Current()));
  // The block along z: under the inner cube's top face, between the planes x = z and y = z.
  const std::vector<std::vector<core::Vec3>> parting = {
      {{0, 0, a}, {a, 0, a}, {a, a, a}, {0, a, a}},
      {{a, 0, a}, {far, 0, far}, {far, far, far}, {a, a, a}},
      {{0, a, a}, {0, far, far}, {far, far, far}, {a, a, a}}};
  const occ::SplitResult split = occ::split_solid(ball_octant, parting, 1e-7);
  ASSERT_TRUE(split.ok);
  const occ::Solid* block = nullptr;
  for (const occ::Solid& p : split.pieces)
    if (p.num_faces() == 6) block = &p;
  ASSERT_NE(block, nullptr);
  int degenerated = 0;
  for (core::EdgeId e : block->edges()) degenerated += block->edge_is_degenerated(e);
  EXPECT_EQ(degenerated, 1);  // the pole's, at a corner of the round face
  for (double size : {0.3, 0.7}) {
    const Figures f = sweep_and_check("pole at a corner", *block, size, false);
    EXPECT_GT(f.min, 0.3) << size;
  }
  // Two intervals on every edge (as the interval assignment gives it beside the fillets'
  // strips) at a size larger than the block: the target's one inner node, about 1 from the
  // pole, is where the mapping puts it.
  SweepOptions o;
  o.size = 2;
  o.edge_intervals.assign(std::size_t(block->num_edges()) + 1, 2);
  const SweepResult two = sweep(*block, o);
  ASSERT_TRUE(two.ok) << (two.diagnostics.empty() ? "" : core::format(two.diagnostics[0]));
  EXPECT_EQ(two.mesh.num_hexes(), 8u);
  const quality::CheckReport c = quality::check_mesh(two.mesh, block);
  EXPECT_TRUE(c.valid) << (c.diagnostics.empty() ? "" : core::format(c.diagnostics[0]));
  EXPECT_GT(c.scaled_jacobian.min, 0.3);
}

// The column under a drilled blind hole (the plane cuts cut it off along the hole's
// cylinder): a disc swept up to the drill point's cone, whose apex (a degenerated edge) and
// seam bound no linking face. The disc's centre goes to the apex.
TEST(Sweep, ADiscIsSweptToADrillPointsCone) {
  const double tip = 4 / std::tan(59 * 3.14159265358979323846 / 180);
  const occ::Solid column = [&] {
    auto c = occ::cut_solids(occ::make_cylinder(4, 8, {0, 0, 0}, {0, 0, 1}),
                             occ::make_cone(4, 0, tip, {0, 0, 8}, {0, 0, -1}));
    if (!c) throw std::runtime_error("the cut failed");
    return std::move(*c);
  }();
  const SweepApplicability a = sweep_applicable(column);
  ASSERT_TRUE(a.ok) << a.reason;
  EXPECT_TRUE(column.face_is_planar(a.source));
  EXPECT_EQ(column.surface_info(a.target).kind, core::SurfaceKind::cone);
  sweep_and_check("drill point", column, 0.7, false);
  SweepOptions o;
  o.size = 0.7;
  const SweepResult r = sweep(column, o);
  ASSERT_TRUE(r.ok);
  double nearest = 1e9;
  for (const Vec3& p : r.mesh.points())
    nearest = std::min(nearest, (p - Vec3(0, 0, 8 - tip)).norm());
  EXPECT_LT(nearest, 1e-6) << "a node at the apex";
}

TEST(Sweep, CurvedSourceFace) {
  // Radial edges (1) are shorter than the axial ones (2): swept from the outer cylindrical
  // face to the inner one, the source meshed in its (u, v) chart.
  const occ::Solid ring = occ::make_ring_sector(2, 3, 1.2, 2);
  const auto a = sweep_applicable(ring);
  ASSERT_TRUE(a.ok) << a.reason;
  EXPECT_FALSE(ring.face_is_planar(a.source));
  EXPECT_FALSE(ring.face_is_planar(a.target));
  const Figures f = sweep_and_check("ring sector (curved)", ring, 0.2, false);
  EXPECT_GE(f.mean, 0.85);
}

TEST(Sweep, TaperedBrickTolerated) {
  sweep_and_check("tapered brick", occ::make_tapered_brick(4, 3, 2, 0.5), 0.25, true);
}

TEST(Sweep, RefusesSolidsWithoutASweepDirection) {
  const occ::Solid tet = occ::make_polyhedron({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                                              {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
  const SweepApplicability a = sweep_applicable(tet);
  EXPECT_FALSE(a.ok);
  EXPECT_NE(a.reason.find("Face"), std::string::npos) << a.reason;
  const SweepResult r = sweep(tet, SweepOptions{});
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics[0].code, "not_applicable");
  EXPECT_EQ(sweep_evaluate(tet, SweepOptions{}).hexes, 0u);
  std::printf("[sweep] tetrahedron refused: %s\n", a.reason.c_str());
}

TEST(Sweep, OptionsValidateAndCancel) {
  SweepOptions o;
  o.size = -1;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  EXPECT_THROW(sweep(occ::make_box(1, 1, 1), o), std::invalid_argument);
  o.size = 0.1;
  o.max_intervals = 5;
  const SweepResult r = sweep(occ::make_box(1, 1, 1), o);
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics[0].code, "too_many_intervals");
  std::atomic<bool> cancel{true};
  o.max_intervals = 1000;
  const SweepResult c = sweep(occ::make_box(1, 1, 1), o, core::Progress({}, &cancel));
  EXPECT_FALSE(c.ok);
  EXPECT_EQ(c.mesh.num_hexes(), 0u);
}

long peak_rss_kb() {
  std::ifstream s("/proc/self/status");
  std::string line;
  while (std::getline(s, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stol(line.substr(6));
  return 0;
}

TEST(Sweep, MillionHexPlateWithHolesTiming) {
  const occ::Solid plate =
      occ::make_prism({{0, 0}, {10, 0}, {10, 6}, {0, 6}}, 1,
                      {{{2, 2}, {4, 2}, {4, 4}, {2, 4}}, {{6, 2}, {8, 2}, {8, 4}, {6, 4}}});
  SweepOptions o;
  o.size = 0.037;  // about 38,000 quads x 27 layers
  const auto t0 = std::chrono::steady_clock::now();
  const SweepResult r = sweep(plate, o);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(r.ok);
  EXPECT_GT(r.mesh.num_hexes(), 900000u);
  std::printf("[sweep] plate with holes: %zu hexes in %.2f s, peak RSS %.0f MB\n",
              r.mesh.num_hexes(), seconds, peak_rss_kb() / 1024.0);
}

}  // namespace
}  // namespace vorohex::mesh

namespace vorohex::mesh {
namespace {

// Intervals given per edge (from an interval assignment) are used as given: the layers
// are the linking edges' count, source edges their own; counts that do not fit the sweep
// are an error naming the edges, not silently changed.
TEST(SweepGivenIntervals, UsesThemAndRefusesCountsThatDoNotFit) {
  const occ::Solid l = occ::make_prism({{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 3}, {0, 3}}, 0.5);
  const SweepStructure s = sweep_structure(l);
  ASSERT_TRUE(s.source.valid());
  ASSERT_EQ(s.loops.size(), 1u);
  ASSERT_EQ(s.loops[0].size(), 6u);
  EXPECT_EQ(s.linking.size(), 6u);
  SweepOptions o;
  o.size = 0.25;
  o.edge_intervals.assign(l.num_edges() + 1, 0);
  for (const auto& side : s.linking) o.edge_intervals[side.at(0).value()] = 3;
  for (const auto& [src, tgt] : s.loops[0]) {
    const int n = 2 * int(std::lround(l.edge_length(src) / 0.5));
    o.edge_intervals[src.value()] = o.edge_intervals[tgt.at(0).value()] = n;
  }
  const SweepResult r = sweep(l, o);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.layers, 3);
  EXPECT_EQ(sweep_evaluate(l, o).hexes, r.mesh.num_hexes());

  SweepOptions bad = o;
  bad.edge_intervals[s.linking[1].at(0).value()] = 4;  // layers disagree
  SweepResult rb = sweep(l, bad);
  EXPECT_FALSE(rb.ok);
  ASSERT_FALSE(rb.diagnostics.empty());
  EXPECT_EQ(rb.diagnostics[0].code, "intervals_mismatch");
  bad = o;
  bad.edge_intervals[s.loops[0][0].second.at(0).value()] += 2;  // target edge differs from source
  rb = sweep(l, bad);
  EXPECT_FALSE(rb.ok);
  EXPECT_EQ(rb.diagnostics[0].code, "intervals_mismatch");
  bad = o;
  bad.edge_intervals[s.loops[0][0].first.value()] += 1;  // odd source loop
  bad.edge_intervals[s.loops[0][0].second.at(0).value()] += 1;
  rb = sweep(l, bad);
  EXPECT_FALSE(rb.ok);
  EXPECT_EQ(rb.diagnostics[0].code, "intervals_mismatch");
}

// A four-sided source with given intervals is a structured grid, and so is the target.
TEST(SweepGivenIntervals, FourSidedSourceIsAGrid) {
  const occ::Solid t = occ::make_prism({{0, 0}, {3, 0}, {2.5, 1}, {0.5, 1}}, 2);
  const SweepStructure s = sweep_structure(t);
  ASSERT_TRUE(s.source.valid());
  SweepOptions o;
  o.size = 0.25;
  o.edge_intervals.assign(t.num_edges() + 1, 5);
  const SweepResult r = sweep(t, o);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.mesh.num_hexes(), std::size_t(5 * 5 * 5));
  EXPECT_EQ(r.mesh.num_nodes(), std::size_t(6 * 6 * 6));
}

}  // namespace
}  // namespace vorohex::mesh
