#include "occ/solid.h"

#include <gtest/gtest.h>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <Bnd_Box.hxx>
#include <TopoDS.hxx>
#include <gp_Ax2.hxx>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <random>

#include "occ/primitives.h"
#include "occ/shape_io.h"
#include "occ/solid_impl.h"

namespace vorohex::occ {
namespace {

VertexId start_of(const Solid& s, const OrientedEdge& e) {
  return e.forward ? s.edge_first_vertex(e.edge) : s.edge_last_vertex(e.edge);
}
VertexId end_of(const Solid& s, const OrientedEdge& e) {
  return e.forward ? s.edge_last_vertex(e.edge) : s.edge_first_vertex(e.edge);
}

// The face all of whose vertices satisfy pred.
FaceId find_face(const Solid& s, const std::function<bool(const Vec3&)>& pred) {
  for (FaceId f : s.faces()) {
    bool all = true;
    const auto wires = s.face_wires(f);
    for (const auto& e : wires[0]) all = all && pred(s.vertex_point(start_of(s, e)));
    if (all) return f;
  }
  return FaceId();
}

EdgeId find_edge(const Solid& s, const Vec3& a, const Vec3& b) {
  for (EdgeId e : s.edges()) {
    const Vec3 p = s.vertex_point(s.edge_first_vertex(e)),
               q = s.vertex_point(s.edge_last_vertex(e));
    if (((p - a).norm() < 1e-12 && (q - b).norm() < 1e-12) ||
        ((p - b).norm() < 1e-12 && (q - a).norm() < 1e-12))
      return e;
  }
  return EdgeId();
}

TEST(Solid, BoxTopologyCounts) {
  const Solid box = make_box(1, 2, 3);
  EXPECT_EQ(box.num_faces(), 6);
  EXPECT_EQ(box.num_edges(), 12);
  EXPECT_EQ(box.num_vertices(), 8);
  EXPECT_EQ(box.faces().front(), FaceId(1));
  EXPECT_EQ(box.edges().back(), EdgeId(12));
  for (EdgeId e : box.edges()) {
    EXPECT_EQ(box.edge_faces(e).size(), 2u);
    EXPECT_FALSE(box.edge_is_degenerated(e));
    EXPECT_NE(box.edge_first_vertex(e), box.edge_last_vertex(e));
  }
}

TEST(Solid, FaceWiresAreClosedCyclesWithMaterialOnTheLeft) {
  for (const Solid& s : {make_box(1, 2, 3), make_tapered_brick(3, 2, 1, 0.5)}) {
    for (FaceId f : s.faces()) {
      const auto wires = s.face_wires(f);
      ASSERT_EQ(wires.size(), 1u);
      const auto& w = wires[0];
      ASSERT_EQ(w.size(), 4u);
      Vec3 area_vector = Vec3::Zero(), centre = Vec3::Zero();
      for (std::size_t i = 0; i < w.size(); ++i) {
        EXPECT_EQ(end_of(s, w[i]), start_of(s, w[(i + 1) % w.size()])) << "Face" << f.value();
        const Vec3 a = s.vertex_point(start_of(s, w[i])), b = s.vertex_point(end_of(s, w[i]));
        area_vector += a.cross(b) / 2;
        centre += a / 4;
      }
      // Counter-clockwise seen from outside: the loop's area vector points outwards.
      const Vec3 n = s.face_normal(f, centre);
      EXPECT_NEAR(n.norm(), 1.0, 1e-12);
      EXPECT_NEAR(area_vector.dot(n), s.area(f), 1e-9) << "Face" << f.value();
      // Outward: a step along n leaves the solid (its distance to the boundary grows).
      EXPECT_NEAR(s.distance_to_boundary(centre + 0.01 * n), 0.01, 1e-12);
    }
  }
}

TEST(Solid, BoxFaceNormalsPointOutwards) {
  const Solid box = make_box(1, 2, 3);
  const FaceId x1 = find_face(box, [](const Vec3& p) { return p.x() == 1; });
  const FaceId z0 = find_face(box, [](const Vec3& p) { return p.z() == 0; });
  ASSERT_TRUE(x1.valid() && z0.valid());
  EXPECT_LT((box.face_normal(x1, Vec3(0.5, 1, 1)) - Vec3(1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((box.face_normal(z0, Vec3(0.5, 1, 1)) - Vec3(0, 0, -1)).norm(), 1e-12);
}

TEST(Solid, EdgePointsByLengthEndAtVerticesWithEqualSpacing) {
  const Solid box = make_box(1, 2, 3);
  for (EdgeId e : box.edges()) {
    const auto pts = box.edge_points_by_length(e, 5);
    ASSERT_EQ(pts.size(), 6u);
    EXPECT_EQ(pts.front(), box.vertex_point(box.edge_first_vertex(e)));
    EXPECT_EQ(pts.back(), box.vertex_point(box.edge_last_vertex(e)));
    for (int i = 0; i < 5; ++i)
      EXPECT_NEAR((pts[i + 1] - pts[i]).norm(), box.edge_length(e) / 5, 1e-12);
  }
  EXPECT_THROW(box.edge_points_by_length(EdgeId(1), 0), std::invalid_argument);
  EXPECT_THROW(box.edge_points_by_length(EdgeId(13), 2), std::out_of_range);
}

TEST(Solid, ArcPointsByLengthAreEquallySpacedOnTheCircle) {
  const double r = 2, angle = 2.0;
  const Solid ring = make_ring_sector(1, r, angle, 1);
  int arcs = 0;
  for (EdgeId e : ring.edges()) {
    const auto pts = ring.edge_points_by_length(e, 8);
    const double len = ring.edge_length(e);
    const Vec3 a = pts.front();
    if (std::abs(std::hypot(a.x(), a.y()) - r) > 1e-9 || std::abs(len - r * angle) > 1e-9)
      continue;  // not an outer arc
    ++arcs;
    EXPECT_EQ(pts.front(), ring.vertex_point(ring.edge_first_vertex(e)));
    EXPECT_EQ(pts.back(), ring.vertex_point(ring.edge_last_vertex(e)));
    const double chord = 2 * r * std::sin(angle / 16);
    for (int i = 0; i < 8; ++i) {
      EXPECT_NEAR(std::hypot(pts[i].x(), pts[i].y()), r, 1e-9);
      EXPECT_NEAR((pts[i + 1] - pts[i]).norm(), chord, 1e-8);
    }
  }
  EXPECT_EQ(arcs, 2);
}

TEST(Solid, DistancesOnABoxMatchHandComputedValues) {
  const Solid box = make_box(1, 2, 3);
  const FaceId x1 = find_face(box, [](const Vec3& p) { return p.x() == 1; });
  const EdgeId ey = find_edge(box, Vec3(1, 0, 0), Vec3(1, 2, 0));
  ASSERT_TRUE(x1.valid() && ey.valid());
  const Vec3 inside(0.5, 1, 1.5), outside(2, 3, 4);
  EXPECT_NEAR(box.distance_to_face(x1, inside), 0.5, 1e-12);
  EXPECT_LT((box.project_to_face(x1, inside) - Vec3(1, 1, 1.5)).norm(), 1e-12);
  EXPECT_NEAR(box.distance_to_face(x1, outside), std::sqrt(3.0), 1e-12);
  EXPECT_LT((box.project_to_face(x1, outside) - Vec3(1, 2, 3)).norm(), 1e-12);
  EXPECT_NEAR(box.distance_to_edge(ey, inside), std::sqrt(0.25 + 2.25), 1e-12);
  EXPECT_NEAR(box.distance_to_edge(ey, Vec3(1, 5, 0)), 3.0, 1e-12);
  EXPECT_LT((box.project_to_edge(ey, Vec3(3, 1, -1)) - Vec3(1, 1, 0)).norm(), 1e-12);
  EXPECT_NEAR(box.distance_to_vertex(box.edge_first_vertex(ey), Vec3(1, 1, 0)), 1.0, 1e-12);
  EXPECT_NEAR(box.distance_to_boundary(inside), 0.5, 1e-12);
  EXPECT_NEAR(box.distance_to_boundary(Vec3(0.9, 1.95, 1.5)), 0.05, 1e-12);
  EXPECT_NEAR(box.distance_to_boundary(outside), std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(box.distance_to_boundary(Vec3(0.5, 1, 1.5 + 10)), 8.5, 1e-12);
}

TEST(Solid, BoxVolumeAndBoundingBox) {
  const Solid box = make_box(1, 2, 3);
  EXPECT_NEAR(box.volume(), 6.0, 1e-12);
  const auto b = box.bounding_box();
  EXPECT_LT((b.min - Vec3(0, 0, 0)).norm(), 1e-6);
  EXPECT_LT((b.max - Vec3(1, 2, 3)).norm(), 1e-6);
  EXPECT_NEAR(box.diagonal(), std::sqrt(14.0), 1e-6);
  const Solid copy = box.clone();
  EXPECT_NEAR(copy.volume(), 6.0, 1e-12);
  EXPECT_EQ(copy.num_edges(), 12);
}

// The solid's box is the union of its faces' boxes made with it (not OCCT's optimal box of
// the whole solid computed again on each call, which took 20 of the 37 s of HexMe i08's
// decomposition): the same box, on curved, B-spline and many-faced solids.
TEST(Solid, BoundingBoxIsOcctsOptimalBoxOfTheSolid) {
  for (const char* model : {"i02o_m2.step", "i09o_m9.step", "s05o_cube_sphere.step",
                            "s10o_cyl_cutsphere.step", "n15o_icosahedron.step"}) {
    const ReadResult in = read_solid(std::string(VOROHEX_HEXME_DIR) + "/" + model);
    ASSERT_TRUE(in.ok()) << model;
    const Solid& s = *in.solid;
    Bnd_Box occt;
    BRepBndLib::AddOptimal(s.impl().solid, occt, false, false);
    double x0, y0, z0, x1, y1, z1;
    occt.Get(x0, y0, z0, x1, y1, z1);
    const core::BoundingBox b = s.bounding_box();
    EXPECT_LE((b.min - Vec3(x0, y0, z0)).norm(), 1e-12 * s.diagonal()) << model;
    EXPECT_LE((b.max - Vec3(x1, y1, z1)).norm(), 1e-12 * s.diagonal()) << model;
    EXPECT_GT(s.diagonal(), 0) << model;
  }
}

TEST(Solid, TaperedBrickVolumeIsThePrismatoidFormula) {
  const double dx = 3, dy = 2, h = 1, t = 0.5;
  const Solid brick = make_tapered_brick(dx, dy, h, t);
  EXPECT_EQ(brick.num_faces(), 6);
  EXPECT_EQ(brick.num_vertices(), 8);
  const double bottom = dx * dy, top = (dx - 2 * t) * (dy - 2 * t), mid = (dx - t) * (dy - t);
  EXPECT_NEAR(brick.volume(), h / 6 * (bottom + 4 * mid + top), 1e-12);
  for (FaceId f : brick.faces()) EXPECT_TRUE(brick.face_is_planar(f));
}

TEST(Solid, CylinderHasACurvedLateralFace) {
  const double r = 1, h = 4;
  const Solid cyl = make_cylinder(r, h);
  EXPECT_EQ(cyl.num_faces(), 3);
  int curved = 0;
  FaceId lateral;
  for (FaceId f : cyl.faces())
    if (!cyl.face_is_planar(f)) ++curved, lateral = f;
  ASSERT_EQ(curved, 1);
  EXPECT_NEAR(cyl.volume(), M_PI * r * r * h, 1e-9);
  EXPECT_NEAR(cyl.area(lateral), 2 * M_PI * r * h, 1e-9);
  EXPECT_NEAR(cyl.distance_to_face(lateral, Vec3(2, 0, 2)), 1.0, 1e-9);
  EXPECT_NEAR(cyl.distance_to_face(lateral, Vec3(0, 0.5, 2)), 0.5, 1e-9);
  EXPECT_NEAR(cyl.distance_to_face(lateral, Vec3(0, 2, 8)), std::hypot(1.0, 4.0), 1e-9);
  EXPECT_LT((cyl.face_normal(lateral, Vec3(0, 3, 1)) - Vec3(0, 1, 0)).norm(), 1e-9);
  EXPECT_NEAR(cyl.distance_to_boundary(Vec3(0, 0, 2)), 1.0, 1e-9);
  EXPECT_NEAR(cyl.distance_to_boundary(Vec3(0.2, 0, 0.1)), 0.1, 1e-9);
}

TEST(Solid, PrismWithHoleAndPolyhedron) {
  const Solid plate =
      make_prism({{0, 0}, {4, 0}, {4, 4}, {0, 4}}, 1, {{{1, 1}, {1, 2}, {2, 2}, {2, 1}}});
  EXPECT_NEAR(plate.volume(), 15.0, 1e-9);
  EXPECT_EQ(plate.num_faces(), 10);
  const Solid tet = make_polyhedron({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                                    {{0, 1, 2}, {0, 1, 3}, {1, 2, 3}, {0, 2, 3}});
  EXPECT_NEAR(tet.volume(), 1.0 / 6, 1e-12);
  EXPECT_EQ(tet.num_faces(), 4);
  const Solid ring = make_ring_sector(1, 2, 1.5, 0.5);
  EXPECT_NEAR(ring.volume(), 1.5 / 2 * (4 - 1) * 0.5, 1e-9);
  EXPECT_THROW(make_box(0, 1, 1), std::invalid_argument);
}

TEST(Solid, BrepStringIsNotEmpty) {
  EXPECT_NE(make_box(1, 1, 1).to_brep_string().find("CASCADE Topology"), std::string::npos);
}

// Many queries must be cheap: the mesher and the quality checks call them per node.
TEST(Solid, BoundaryDistanceIsExactOnPlanes) {
  const Solid box = make_box(1, 2, 3);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 3.5);
  const int n = 100000;
  double worst = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < n; ++i) {
    const Vec3 p(u(rng) / 3, u(rng) * 2 / 3, u(rng));
    const Vec3 q = p.cwiseMax(Vec3(0, 0, 0)).cwiseMin(Vec3(1, 2, 3));
    const bool in = q == p;
    const double expect =
        in ? std::min({p.x(), 1 - p.x(), p.y(), 2 - p.y(), p.z(), 3 - p.z()}) : (q - p).norm();
    worst = std::max(worst, std::abs(box.distance_to_boundary(p) - expect));
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(worst, 1e-12);
  RecordProperty("microseconds_per_query", std::to_string(seconds / n * 1e6));
}

// A cylinder's face (radius r, height h, axis z from the origin) against the closed form:
// the worst error of the distance and of the normal (away from the axis and the rims) over
// n random points, and the microseconds per distance.
struct CylinderErrors {
  double distance = 0, normal = 0, microseconds = 0;
};
CylinderErrors cylinder_face_errors(const Solid& cyl, FaceId lateral, double r, double h, int n,
                                    unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-3, 3), z(-2, 6);
  CylinderErrors e;
  double seconds = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 p(u(rng), u(rng), z(rng));
    const double radial = std::hypot(p.x(), p.y()) - r;
    const double axial = std::max({0.0, -p.z(), p.z() - h});
    const auto t0 = std::chrono::steady_clock::now();
    const double d = cyl.distance_to_face(lateral, p);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    e.distance = std::max(e.distance, std::abs(d - std::hypot(radial, axial)));
    if (axial == 0 && std::abs(radial) > 0.01) {
      const Vec3 out = Vec3(p.x(), p.y(), 0).normalized();
      e.normal = std::max(e.normal, (cyl.face_normal(lateral, p) - out).norm());
    }
  }
  e.microseconds = seconds / n * 1e6;
  return e;
}

TEST(Solid, CurvedFaceDistanceIsExact) {
  const double r = 1, h = 4;
  const Solid cyl = make_cylinder(r, h);
  FaceId lateral;
  for (FaceId f : cyl.faces())
    if (!cyl.face_is_planar(f)) lateral = f;
  const CylinderErrors e = cylinder_face_errors(cyl, lateral, r, h, 20000, 3);
  EXPECT_LT(e.distance, 1e-9);
  EXPECT_LT(e.normal, 1e-9);
  std::printf("cylinder face distance: %.2f us per query\n", e.microseconds);
}

// The same on a cylinder given as B-splines (as STEP files from other CAD often are): OCCT's
// search for the nearest point of such a surface looks for minima only (a maximum of the
// distance is never a face's nearest point), and finds them exactly, rims included.
TEST(Solid, BSplineFaceDistanceIsExact) {
  const double r = 1, h = 4;
  BRepBuilderAPI_NurbsConvert convert(
      BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), r, h).Solid());
  const Solid cyl = make_solid(TopoDS::Solid(convert.Shape()));
  FaceId lateral;
  for (FaceId f : cyl.faces())
    if (cyl.area(f) > 2 * M_PI * r * r) lateral = f;
  ASSERT_GT(lateral.value(), 0);
  ASSERT_EQ(cyl.surface_info(lateral).kind, core::SurfaceKind::other);
  const CylinderErrors e = cylinder_face_errors(cyl, lateral, r, h, 5000, 5);
  EXPECT_LT(e.distance, 1e-7);
  EXPECT_LT(e.normal, 1e-7);
  std::printf("B-spline cylinder face distance: %.2f us per query\n", e.microseconds);
}

}  // namespace
}  // namespace vorohex::occ
