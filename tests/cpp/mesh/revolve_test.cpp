#include "mesh/revolve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "fixtures/machined.h"
#include "occ/revolution.h"
#include "pipeline/generate_mesh.h"
#include "quality/check_mesh.h"

namespace vorohex::mesh {
namespace {

using core::Vec3;

struct Named {
  std::string name;
  occ::Solid solid;
  int cores;
};

std::vector<Named> turned_parts() {
  std::vector<Named> out;
  out.push_back({"pulley with a V-groove and a bore", testing::make_pulley(), 0});
  out.push_back({"stepped shaft", testing::make_stepped_shaft(), 1});
  out.push_back({"chamfered shaft", testing::make_chamfered_shaft(), 1});
  return out;
}

// Valid before smoothing, evaluate() == compute(), one core where the section lies on the
// axis, nodes on their CAD entities (the revolved nodes on the cones exactly).
TEST(Revolve, TurnedPartsAreValidBeforeSmoothing) {
  for (const Named& part : turned_parts()) {
    for (double divisions : {20.0, 25.0}) {
      SCOPED_TRACE(part.name + " at diagonal / " + std::to_string(int(divisions)));
      const RevolveApplicability a = revolve_applicable(part.solid);
      ASSERT_TRUE(a.ok) << a.reason;
      EXPECT_EQ(a.cores, part.cores);
      EXPECT_NEAR(std::abs(a.axis.z()), 1, 1e-12);
      RevolveOptions o;
      o.size = part.solid.diagonal() / divisions;
      const RevolveEstimate e = revolve_evaluate(part.solid, o);
      const RevolveResult r = revolve(part.solid, o);
      ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics[0]));
      EXPECT_EQ(r.sectors % 4, 0);
      EXPECT_EQ(e.sectors, r.sectors);
      EXPECT_EQ(e.hexes, r.mesh.num_hexes());
      EXPECT_EQ(e.nodes, r.mesh.num_nodes());
      const quality::CheckReport c = quality::check_mesh(r.mesh, &part.solid, {});
      EXPECT_TRUE(c.valid) << (c.diagnostics.empty() ? "" : core::format(c.diagnostics[0]));
      EXPECT_EQ(c.non_positive, 0u);
      EXPECT_EQ(c.open_boundary_edges, 0u);
      EXPECT_LE(c.max_boundary_distance_rel, 1e-6);
      EXPECT_GE(c.scaled_jacobian.min, 0.3);
    }
  }
}

// Through the pipeline with its default schemes: the pulley (cones) is no prism, so the
// revolve meshes it; min scaled Jacobian >= 0.3 after smoothing.
TEST(Revolve, PipelineRevolvesWhatNoPrismTakes) {
  for (const Named& part : turned_parts()) {
    SCOPED_TRACE(part.name);
    pipeline::MeshOptions opt;
    opt.fallback = false;
    opt.decompose = false;
    const pipeline::MeshResult r = pipeline::generate_mesh(part.solid, opt);
    ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
    // The stepped shaft is also prismatic (cylinders and shoulders): the multisweep comes
    // first in the default order.
    EXPECT_EQ(r.stats.scheme, part.name == "stepped shaft" ? "multisweep" : "revolve");
    EXPECT_GE(r.check.scaled_jacobian.min, 0.3);
  }
}

TEST(Revolve, WhatIsNotOfRevolutionIsRefusedWithTheReason) {
  const RevolveApplicability box = revolve_applicable(occ::make_box(1, 2, 3));
  EXPECT_FALSE(box.ok);
  EXPECT_NE(box.reason.find("no cylinder"), std::string::npos) << box.reason;
  // A cross hole: a cylinder about another axis.
  const occ::Solid drilled = testing::cut(occ::make_cylinder(10, 40, Vec3::Zero(), Vec3::UnitZ()),
                                          occ::make_cylinder(3, 30, {-15, 0, 20}, Vec3::UnitX()));
  const RevolveApplicability d = revolve_applicable(drilled);
  EXPECT_FALSE(d.ok);
  EXPECT_NE(d.reason.find("another axis"), std::string::npos) << d.reason;
  // A cone's apex on the axis: no core can end on it.
  const RevolveApplicability tip =
      revolve_applicable(occ::make_cone(5, 0, 10, Vec3::Zero(), Vec3::UnitZ()));
  EXPECT_FALSE(tip.ok);
  EXPECT_NE(tip.reason.find("at an angle"), std::string::npos) << tip.reason;
  const RevolveResult r = revolve(occ::make_box(1, 2, 3), RevolveOptions{});
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.diagnostics.empty());
  EXPECT_EQ(r.diagnostics[0].code, "not_applicable");
}

// The section and its core: the shaft's section minus a core of half the end radius.
TEST(Revolve, SectionAndCoreOfAShaft) {
  const occ::RevolutionStructure s = occ::revolution_structure(testing::make_stepped_shaft());
  ASSERT_TRUE(s.ok) << s.reason;
  ASSERT_EQ(s.cores.size(), 1u);
  EXPECT_NEAR(s.cores[0].z1 - s.cores[0].z0, 75, 1e-6);
  EXPECT_NEAR(s.core_radius, 4, 1e-9);  // half of the smaller end radius, 8
  EXPECT_NEAR(s.max_radius, 15, 1e-6);
  int sides = 0;
  for (bool b : s.core_side) sides += b;
  EXPECT_GE(sides, 1);
}

// The section comes from the faces' traces, not from a boolean: a whole torus (one face,
// its wire along a parallel seam) is a disc; a torus with a toroidal cavity an annulus; a
// ring with a torus-shaped groove has an arc in its outline. Each turns into its volume
// (Pappus, checked by the structure) and meshes valid.
TEST(Revolve, SectionsFromTheFacesTraces) {
  const occ::Solid torus = occ::make_torus(10, 3, Vec3::Zero(), Vec3::UnitZ());
  const occ::Solid hollow = testing::cut(occ::make_torus(10, 3, Vec3::Zero(), Vec3::UnitZ()),
                                         occ::make_torus(10, 1.5, Vec3::Zero(), Vec3::UnitZ()));
  const occ::Solid grooved =
      testing::cut(testing::cut(occ::make_cylinder(20, 10, Vec3::Zero(), Vec3::UnitZ()),
                                occ::make_cylinder(8, 10, Vec3::Zero(), Vec3::UnitZ())),
                   occ::make_torus(20, 3, {0, 0, 5}, Vec3::UnitZ()));
  for (const auto& [name, solid, loops] : {std::tuple{"torus", &torus, 1},
                                           {"hollow torus", &hollow, 2},
                                           {"grooved ring", &grooved, 1}}) {
    SCOPED_TRACE(name);
    const core::MeshDomain& domain = *solid;
    const occ::RevolutionStructure s = occ::revolution_structure(domain);
    ASSERT_TRUE(s.ok) << s.reason;
    EXPECT_TRUE(s.cores.empty());
    ASSERT_EQ(s.section->num_faces(), 1);
    EXPECT_EQ(int(s.section->face_wires(core::FaceId(1)).size()), loops);
    RevolveOptions o;
    o.size = 0.75;  // a quarter of the tube radius: polygonal volume within 2 %
    const RevolveResult r = revolve(domain, o);
    ASSERT_TRUE(r.ok) << (r.diagnostics.empty() ? "" : core::format(r.diagnostics.back()));
    const quality::CheckReport c = quality::check_mesh(r.mesh, solid, {});
    EXPECT_TRUE(c.valid) << (c.diagnostics.empty() ? "" : core::format(c.diagnostics[0]));
    EXPECT_LE(c.max_boundary_distance_rel, 1e-6);
    EXPECT_GT(c.scaled_jacobian.min, 0);
    EXPECT_NEAR(c.mesh_volume, solid->volume(), 0.02 * solid->volume());
  }
}

// Beside neighbours (mesh_sub_volumes): the sectors' count given, the first sector through a
// given point, a meridian edge's count given to the section; a count that is no multiple of
// 4 is refused by name.
TEST(Revolve, SectorsAndTheirStartAndSeamCountsCanBeGiven) {
  const occ::Solid shaft = testing::make_stepped_shaft();
  const occ::RevolutionStructure s = occ::revolution_structure(shaft);
  ASSERT_TRUE(s.ok) << s.reason;
  RevolveOptions o;
  o.size = 3;
  o.sectors = 28;
  o.has_start = true;
  // A point a quarter of a turn and a little from the section's own half-plane.
  const core::Vec3 across = s.axis.cross(s.radial);
  o.start = s.origin + 10 * (std::cos(1.0) * s.radial + std::sin(1.0) * across);
  const RevolveResult r = revolve(shaft, o);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.sectors, 28);
  // Every revolved node off the axis lies at an angle 1 + 2 pi k / 28 about the axis.
  std::size_t off_axis = 0;
  for (std::size_t i = 0; i < r.mesh.num_nodes(); ++i) {
    const core::Vec3 d = r.mesh.points()[i] - s.origin;
    const core::Vec3 radial = d - d.dot(s.axis) * s.axis;
    if (radial.norm() < s.core_radius + 1e-6) continue;  // the O-grid core's own nodes
    ++off_axis;
    const double turns =
        (std::atan2(radial.dot(across), radial.dot(s.radial)) - 1.0) / (2 * M_PI) * 28;
    EXPECT_NEAR(turns, std::round(turns), 1e-9) << "node " << i;
  }
  EXPECT_GT(off_axis, 0u);
  EXPECT_TRUE(quality::check_mesh(r.mesh, &shaft, {}).valid);
  // A seam's count: the section's edge along it takes it.
  int seam = 0;
  for (core::EdgeId e : shaft.edges())
    if (!shaft.edge_is_degenerated(e) && shaft.edge_first_vertex(e) != shaft.edge_last_vertex(e) &&
        shaft.curve_info(e).kind == core::CurveKind::line)
      seam = e.value();
  ASSERT_GT(seam, 0);
  RevolveOptions counted = o;
  counted.edge_intervals.assign(shaft.num_edges() + 1, 0);
  const double length = shaft.edge_length(core::EdgeId(seam));
  counted.edge_intervals[seam] = 2 * int(std::ceil(length / o.size)) + 2;
  const RevolveResult finer = revolve(shaft, counted);
  ASSERT_TRUE(finer.ok);
  EXPECT_GT(finer.mesh.num_hexes(), r.mesh.num_hexes());
  RevolveOptions bad;
  bad.sectors = 10;
  EXPECT_THROW(revolve(shaft, bad), std::invalid_argument);
}

}  // namespace
}  // namespace vorohex::mesh
