#include "mesh/multisweep.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "fixtures/machined.h"
#include "occ/detail/fixtures.h"
#include "occ/prismatic.h"
#include "occ/shape_io.h"
#include "pipeline/generate_mesh.h"
#include "quality/check_mesh.h"

namespace vorohex::mesh {
namespace {

using core::Vec3;

struct Named {
  std::string name;
  occ::Solid solid;
  bool planar;
};

std::vector<Named> prismatic_parts() {
  std::vector<Named> out;
  out.push_back({"stepped extrusion", testing::make_stepped_extrusion(), true});
  out.push_back({"stepped plate with holes", testing::make_stepped_plate_with_holes(), false});
  out.push_back({"plate with boss and holes", testing::make_plate_with_boss_and_holes(), false});
  out.push_back({"flanged pipe", testing::make_flanged_pipe(), false});
  out.push_back({"stepped shaft", testing::make_stepped_shaft(), false});
  out.push_back({"hexagonal wheel with rod", testing::make_hex_wheel_with_rod(), false});
  out.push_back({"block with a pyramid pocket", testing::make_block_with_pyramid_pocket(), true});
  occ::ReadResult i15 = occ::read_solid(std::string(VOROHEX_HEXME_DIR) + "/i15o_s8.step");
  if (i15.ok()) out.push_back({"HexMe i15", i15.solid->clone(), false});
  // A NURBS export (every face and edge a B-spline): the faces are read as the planes and
  // cylinders they are, the edges stay B-splines, which the arrangement traces through
  // samples; its nodes on the flange's circles lay 2.4e-4 off them before they were put on.
  const std::string nurbs = ::testing::TempDir() + "/bspline_flanged_pipe.brep";
  if (occ::detail::write_fixture(occ::detail::Fixture::bspline_flanged_pipe, nurbs)) {
    occ::ReadResult r = occ::read_solid(nurbs);
    if (r.ok()) out.push_back({"NURBS flanged pipe", r.solid->clone(), false});
  }
  std::remove(nurbs.c_str());
  return out;
}

// Every invariant of a multiswept mesh before smoothing: evaluate() predicts compute()
// exactly, and the mesh is valid against the CAD (positive, conforming, closed, volume,
// nodes on their entities).
void expect_valid_multisweep(const Named& part, double size) {
  SCOPED_TRACE(part.name + " at size " + std::to_string(size));
  MultisweepOptions o;
  o.size = size;
  const MultisweepEstimate e = multisweep_evaluate(part.solid, o);
  const MultisweepResult r = multisweep(part.solid, o);
  ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
  EXPECT_EQ(e.hexes, r.mesh.num_hexes());
  EXPECT_EQ(e.nodes, r.mesh.num_nodes());
  EXPECT_EQ(e.layers, r.layers);
  quality::CheckOptions co;
  const quality::CheckReport c = quality::check_mesh(r.mesh, &part.solid, co);
  EXPECT_TRUE(c.valid) << (c.diagnostics.empty() ? "" : core::format(c.diagnostics[0]));
  EXPECT_EQ(c.non_positive, 0u);
  EXPECT_EQ(c.folded_quads, 0u);
  EXPECT_EQ(c.open_boundary_edges, 0u);
  EXPECT_LE(c.max_boundary_distance_rel, 1e-6);
  if (part.planar) {
    EXPECT_NEAR(c.mesh_volume, part.solid.volume(), 1e-9 * part.solid.volume());
  }
}

TEST(Multisweep, MachinedPartsAreValidBeforeSmoothing) {
  for (const Named& part : prismatic_parts()) {
    ASSERT_TRUE(multisweep_applicable(part.solid).ok)
        << part.name << ": " << multisweep_applicable(part.solid).reason;
    expect_valid_multisweep(part, part.solid.diagonal() / 20);
    expect_valid_multisweep(part, part.solid.diagonal() / 25);
  }
}

// Through the pipeline, with the multisweep as the only scheme: valid and structured at the
// default size and at diagonal / 25, min scaled Jacobian >= 0.3 (issue 20), mean >= 0.85 on
// the planar ones.
TEST(Multisweep, MachinedPartsMeshStructuredAbove03) {
  for (const Named& part : prismatic_parts()) {
    for (double divisions : {20.0, 25.0}) {
      SCOPED_TRACE(part.name + " at diagonal / " + std::to_string(int(divisions)));
      pipeline::MeshOptions opt;
      opt.size = part.solid.diagonal() / divisions;
      opt.schemes = {"multisweep"};
      opt.fallback = false;
      opt.decompose = false;
      const pipeline::MeshResult r = pipeline::generate_mesh(part.solid, opt);
      ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
      EXPECT_EQ(r.stats.scheme, "multisweep");
      EXPECT_GE(r.check.scaled_jacobian.min, 0.3);
      if (part.planar) {
        EXPECT_GE(r.check.scaled_jacobian.mean, 0.85);
      }
      EXPECT_GE(r.check.scaled_jacobian.min, r.stats.min_sj_before_smoothing);
    }
  }
}

// The structure of a stepped extrusion along z: three levels, the caps' outlines overlaid
// into two regions, one inside both slabs, the other in the lower one only.
// HexMe i16 stores each of its turned faces as a revolved line: the solid reports them as
// cylinders (a line parallel to the axis), so the part is prismatic along that axis and is
// multiswept (it was the fallback's, with inverted hexahedra, before).
TEST(Multisweep, RevolvedLinesAreCylindersSoTurnedExportsAreSwept) {
  occ::ReadResult in = occ::read_solid(std::string(VOROHEX_HEXME_DIR) + "/i16o_s9.step");
  ASSERT_TRUE(in.ok()) << "HexMe model i16 not found in " << VOROHEX_HEXME_DIR;
  const occ::Solid& solid = *in.solid;
  int cylinders = 0;
  for (core::FaceId f : solid.faces()) {
    const core::SurfaceInfo info = solid.surface_info(f);
    EXPECT_NE(info.kind, core::SurfaceKind::revolution) << core::entity_name(f);
    if (info.kind != core::SurfaceKind::cylinder) continue;
    ++cylinders;
    EXPECT_NEAR(std::abs(info.direction.x()), 1.0, 1e-12);
    // Every point of the face lies at the reported radius from the axis.
    const core::Vec3 p =
        solid.vertex_point(solid.edge_first_vertex(solid.face_wires(f)[0][0].edge));
    const core::Vec3 d = p - info.origin;
    EXPECT_NEAR((d - d.dot(info.direction) * info.direction).norm(), info.radius,
                1e-6 * solid.diagonal());
  }
  EXPECT_EQ(cylinders, 13);
  const MultisweepApplicability a = multisweep_applicable(solid);
  ASSERT_TRUE(a.ok) << a.reason;
  EXPECT_NEAR(std::abs(a.axis.x()), 1.0, 1e-12);
  expect_valid_multisweep({"HexMe i16", solid.clone(), false}, solid.diagonal() / 20);
}

TEST(Multisweep, StructureOfAStepAlongAnAxis) {
  const occ::Solid part = testing::make_stepped_extrusion();
  const occ::PrismaticStructure s = occ::prismatic_structure(part, Vec3::UnitZ());
  ASSERT_TRUE(s.ok) << s.reason;
  ASSERT_EQ(s.levels.size(), 3u);
  EXPECT_NEAR(s.levels[1] - s.levels[0], 10, 1e-9);
  EXPECT_NEAR(s.levels[2] - s.levels[1], 10, 1e-9);
  ASSERT_EQ(s.arrangement->num_faces(), 2);
  int both = 0, lower = 0;
  for (int f = 1; f <= 2; ++f) {
    both += s.inside[f][0] && s.inside[f][1];
    lower += s.inside[f][0] && !s.inside[f][1];
  }
  EXPECT_EQ(both, 1);
  EXPECT_EQ(lower, 1);
  // Unforced, the axis with the fewest regions wins: the L profile along y is one region.
  const occ::PrismaticStructure best = occ::prismatic_structure(part);
  ASSERT_TRUE(best.ok);
  EXPECT_EQ(best.arrangement->num_faces(), 1);
  EXPECT_NEAR(std::abs(best.axis.y()), 1, 1e-12);
}

// Sloped caps: HexMe n06's pentagonal pyramid pocket (a 3 x 3 x 2.5 block) is one slab whose
// floor climbs the pyramid's five faces to their apex (no level of its own); the ridges'
// nodes lie on the ridges. A roof's apex above the top level is none either.
TEST(Multisweep, PyramidPocketsAndRoofsAreSlopedCaps) {
  occ::ReadResult n06 =
      occ::read_solid(std::string(VOROHEX_HEXME_DIR) + "/n06o_anti_pentapyr.step");
  ASSERT_TRUE(n06.ok()) << "HexMe model n06 not found in " << VOROHEX_HEXME_DIR;
  const occ::PrismaticStructure s = occ::prismatic_structure(*n06.solid);
  ASSERT_TRUE(s.ok) << s.reason;
  EXPECT_NEAR(std::abs(s.axis.z()), 1, 1e-12);
  EXPECT_EQ(s.levels.size(), 2u);
  int sloped = 0;
  for (std::size_t k = 0; k < s.caps.size(); ++k) {
    sloped += s.cap_sloped[k];
    if (s.cap_sloped[k]) EXPECT_EQ(s.cap_level[k], 0) << core::entity_name(s.caps[k]);
  }
  EXPECT_EQ(sloped, 5);
  EXPECT_EQ(s.arrangement->num_faces(), 6);  // the pentagon's five triangles and the rest
  // A ridge (from a corner of the pentagon up to the apex) lies over one arrangement edge.
  int ridges = 0;
  for (core::EdgeId e : n06.solid->edges()) {
    const auto p = n06.solid->edge_points_by_length(e, 2);
    if (std::abs(s.height(p[0]) - s.height(p[2])) < 1e-6 ||
        (p[0] - p[2] - (p[0] - p[2]).dot(s.axis) * s.axis).norm() < 1e-6)
      continue;
    ++ridges;
    EXPECT_EQ(occ::edge_in_structure(*n06.solid, s, e).arrangement_edges.size(), 1u)
        << core::entity_name(e);
  }
  EXPECT_EQ(ridges, 5);
  expect_valid_multisweep({"HexMe n06", n06.solid->clone(), true}, n06.solid->diagonal() / 20);

  // The roof: every column's layers lean as its top does (mean 0.83 at diagonal / 20).
  const occ::Solid roof = testing::make_block_with_hip_roof();
  const occ::PrismaticStructure r = occ::prismatic_structure(roof);
  ASSERT_TRUE(r.ok) << r.reason;
  ASSERT_EQ(r.levels.size(), 2u);
  EXPECT_NEAR(r.levels[1] - r.levels[0], 10, 1e-9);  // the apex at 18 is no level
  expect_valid_multisweep({"block under a hip roof", roof.clone(), true}, roof.diagonal() / 20);
  pipeline::MeshOptions opt;
  opt.size = roof.diagonal() / 20;
  opt.schemes = {"multisweep"};
  opt.fallback = false;
  opt.decompose = false;
  const pipeline::MeshResult m = pipeline::generate_mesh(roof, opt);
  ASSERT_TRUE(m.ok) << (m.diagnostics.empty() ? "" : core::format(m.diagnostics.back()));
  EXPECT_GE(m.check.scaled_jacobian.min, 0.3);
}

// Sloped faces the multisweep does not take, with the reason naming the face: a pyramid
// steeper than 60 degrees from the axis, and a pocket whose apex comes within a twentieth
// of the slab's thickness of the top.
TEST(Multisweep, SteepOrNearlyPiercingSlopesAreRefused) {
  const occ::Solid steep = testing::cut(occ::make_box(30, 30, 20),
                                        testing::make_pyramid(13, 17, 13, 17, -1, {15, 15, 12}));
  // Refused along every axis, the reason is the one along z, the axis of its largest caps
  // (along x the pit's faces are sloped caps too, and come near the next level).
  const MultisweepApplicability a = multisweep_applicable(steep);
  EXPECT_FALSE(a.ok);
  EXPECT_NE(a.reason.find("degrees to the axis"), std::string::npos) << a.reason;
  // 56 degrees, its apex 0.5 under the top of a block 20 high.
  const occ::Solid deep = testing::cut(occ::make_box(30, 30, 20),
                                       testing::make_pyramid(1, 29, 1, 29, -1, {15, 15, 19.5}));
  const MultisweepApplicability b = multisweep_applicable(deep);
  EXPECT_FALSE(b.ok);
  EXPECT_NE(b.reason.find("twentieth"), std::string::npos) << b.reason;
}

// Not prismatic, with the reason naming the face: a plane at an angle to every axis of the
// solid (a wedge cut off a box), and a cone.
TEST(Multisweep, SlantedFacesAndConesAreRefusedWithTheirName) {
  const occ::Solid tapered = occ::make_tapered_brick(4, 3, 2, 0.5);
  const MultisweepApplicability a = multisweep_applicable(tapered);
  EXPECT_FALSE(a.ok);
  EXPECT_NE(a.reason.find("degrees to the axis"), std::string::npos) << a.reason;
  const MultisweepApplicability c =
      multisweep_applicable(occ::make_cone(3, 1, 4, Vec3::Zero(), Vec3::UnitZ()));
  EXPECT_FALSE(c.ok);
  EXPECT_NE(c.reason.find("cone"), std::string::npos) << c.reason;
  MultisweepOptions o;
  const MultisweepResult r = multisweep(tapered, o);
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics[0].code, "not_applicable");
  EXPECT_EQ(r.mesh.num_hexes(), 0u);
}

// The scheme depends on the geometry, not on how the part was built: the stepped plate with
// holes built in another order, and read back from STEP, gives the same structure and mesh.
TEST(Multisweep, TheSamePartBuiltTwoWaysMeshesTheSame) {
  const occ::Solid a = testing::make_stepped_plate_with_holes();
  using testing::cut;
  using testing::fuse;
  const Vec3 z = Vec3::UnitZ();
  // The lower plate from two halves, fused in the other order, the holes cut the other way.
  occ::Solid b = fuse(occ::make_box(40, 50, 6, {40, 0, 6}), occ::make_box(40, 50, 6, {40, 0, 0}));
  b = fuse(b, occ::make_box(40, 50, 6));
  b = cut(b, occ::make_cylinder(5, 30, {60, 25, 20}, -z));
  b = cut(b, occ::make_cylinder(5, 30, {20, 25, 20}, -z));
  EXPECT_NEAR(b.volume(), a.volume(), 1e-9 * a.volume());
  const std::string path = ::testing::TempDir() + "vorohex_multisweep_two_ways.step";
  std::string error;
  ASSERT_TRUE(occ::write_solid(a, path, &error)) << error;
  const occ::ReadResult c = occ::read_solid(path);
  ASSERT_TRUE(c.ok());
  MultisweepOptions o;
  o.size = 4;
  const MultisweepResult ra = multisweep(a, o), rb = multisweep(b, o), rc = multisweep(*c.solid, o);
  ASSERT_TRUE(ra.ok && rb.ok && rc.ok);
  for (const MultisweepResult* r : {&rb, &rc}) {
    EXPECT_EQ(r->levels, ra.levels);
    EXPECT_EQ(r->regions, ra.regions);
    EXPECT_EQ(r->layers, ra.layers);
    EXPECT_EQ(r->mesh.num_hexes(), ra.mesh.num_hexes());
    EXPECT_EQ(r->mesh.num_nodes(), ra.mesh.num_nodes());
  }
}

}  // namespace
}  // namespace vorohex::mesh

namespace vorohex::mesh {
namespace {

// Faces that come to a point where a boss's circle is tangent to the outline from inside (a
// crescent): the quad at the point has the outline's first two nodes and the boss's first;
// its corner at the outline's first node turns by the chords' angle there, so the outline's
// second node goes far enough for that to reach asin(0.3) (detail::edge_points). A plate of
// radius 20 with a boss of radius 10 (as bench/run_parts.py builds it) at diagonal / 25:
// 0.159 with the second node graded up by 1.5 from the first; a tube of radius 15 with a lug
// whose round end (radius 25) is tangent to it: 0.122 at diagonal / 25, 0.199 at / 20.
TEST(Multisweep, ACrescentsPointGetsQuadsAbove02) {
  const occ::Solid plate = testing::fuse(occ::make_cylinder(20, 4, Vec3::Zero(), testing::kZ),
                                         occ::make_cylinder(10, 12, Vec3(10, 0, 0), testing::kZ));
  const Vec3 kX(1, 0, 0);
  const occ::Solid lug = testing::cut(testing::fuse(occ::make_cylinder(25, 10, Vec3(0, 10, 0), kX),
                                                    occ::make_box(10, 40, 50, Vec3(0, 10, -25))),
                                      occ::make_cylinder(6, 10, Vec3(0, 40, 0), kX));
  const occ::Solid tube =
      testing::cut(testing::fuse(occ::make_cylinder(15, 60, Vec3::Zero(), kX), lug),
                   occ::make_cylinder(9, 60, Vec3::Zero(), kX));
  for (const auto& [name, solid] :
       {std::pair<const char*, const occ::Solid*>{"plate", &plate}, {"tube with a lug", &tube}})
    for (double divisions : {20.0, 25.0}) {
      SCOPED_TRACE(std::string(name) + " at diagonal / " + std::to_string(int(divisions)));
      pipeline::MeshOptions opt;
      opt.size = solid->diagonal() / divisions;
      opt.schemes = {"multisweep"};
      opt.fallback = false;
      opt.decompose = false;
      const pipeline::MeshResult r = pipeline::generate_mesh(*solid, opt);
      ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
      EXPECT_EQ(r.stats.scheme, "multisweep");
      EXPECT_GT(r.check.scaled_jacobian.min, 0.2);
    }
}

}  // namespace
}  // namespace vorohex::mesh
