#include "quality/scaled_jacobian.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "quality/detail/scaled_jacobian_terms.h"
#include "quality/grid_fixture.h"

namespace vorohex::quality {
namespace {

using core::Vec3;
using Corners = std::array<Vec3, 8>;
using testing::box_corners;

Corners permuted(const Corners& c, const std::array<int, 8>& order) {
  Corners out;
  for (int i = 0; i < 8; ++i) out[i] = c[order[i]];
  return out;
}

// Point of the trilinear map of c at reference coordinates (u, v, w).
Vec3 trilinear(const Corners& c, double u, double v, double w) {
  return (1 - u) * (1 - v) * (1 - w) * c[0] + u * (1 - v) * (1 - w) * c[1] +
         u * v * (1 - w) * c[2] + (1 - u) * v * (1 - w) * c[3] + (1 - u) * (1 - v) * w * c[4] +
         u * (1 - v) * w * c[5] + u * v * w * c[6] + (1 - u) * v * w * c[7];
}

TEST(ScaledJacobian, UnitCubeHasAllNineTermsOne) {
  const auto t = detail::scaled_jacobian_terms(box_corners());
  EXPECT_FALSE(t.collapsed);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(t.det[i], 1.0, 1e-15) << "term " << i;
  EXPECT_DOUBLE_EQ(scaled_jacobian(box_corners()), 1.0);
}

TEST(ScaledJacobian, ScaledRotatedTranslatedBoxIsOne) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  Corners c = box_corners(2.0, 0.3, 5.0);
  for (auto& p : c) p = r * p + Vec3(10, -4, 7);
  const auto t = detail::scaled_jacobian_terms(c);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(t.det[i], 1.0, 1e-12) << "term " << i;
  EXPECT_NEAR(scaled_jacobian(c), 1.0, 1e-12);
}

TEST(ScaledJacobian, ShearGivesOneOverSqrtOnePlusSSquared) {
  // x += s z: every corner has two unit axes and the unit vector (s, 0, 1)/sqrt(1 + s^2),
  // whose det with e_x, e_y is 1/sqrt(1 + s^2); the centre axes are the same directions.
  const double s = 0.75;  // 1/sqrt(1.5625) = 0.8
  Corners c = box_corners();
  for (auto& p : c) p.x() += s * p.z();
  const auto t = detail::scaled_jacobian_terms(c);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(t.det[i], 0.8, 1e-14) << "term " << i;
  EXPECT_NEAR(scaled_jacobian(c), 0.8, 1e-14);
}

TEST(ScaledJacobian, MirroredCubeIsMinusOne) {
  Corners c = box_corners();
  for (auto& p : c) p.z() = -p.z();
  EXPECT_DOUBLE_EQ(scaled_jacobian(c), -1.0);
}

TEST(ScaledJacobian, CollapsedEdgeIsZeroNotPerfect) {
  Corners c = box_corners();
  c[1] = c[0];  // edge 0-1 collapsed: a wedge
  EXPECT_TRUE(detail::scaled_jacobian_terms(c).collapsed);
  EXPECT_EQ(scaled_jacobian(c), 0.0);
  Corners all = box_corners();
  for (auto& p : all) p = Vec3(1, 1, 1);  // a point
  EXPECT_EQ(scaled_jacobian(all), 0.0);
}

TEST(ScaledJacobian, InvertingPermutationsAreNegative) {
  const Corners c = box_corners(1.0, 2.0, 0.5);
  // Swapping the two quads or reversing both turns the hex inside out.
  EXPECT_LT(scaled_jacobian(permuted(c, {4, 5, 6, 7, 0, 1, 2, 3})), 0.0);
  EXPECT_LT(scaled_jacobian(permuted(c, {0, 3, 2, 1, 4, 7, 6, 5})), 0.0);
  EXPECT_LT(scaled_jacobian(permuted(c, {1, 0, 3, 2, 5, 4, 7, 6})), 0.0);
  // Relabelling that keeps the orientation (rotate both quads, or turn the hex over
  // with reversed quads) stays perfect.
  EXPECT_NEAR(scaled_jacobian(permuted(c, {1, 2, 3, 0, 5, 6, 7, 4})), 1.0, 1e-15);
  EXPECT_NEAR(scaled_jacobian(permuted(c, {4, 7, 6, 5, 0, 3, 2, 1})), 1.0, 1e-15);
}

TEST(ScaledJacobian, DentingACornerInvertsIt) {
  // Corner 6 moved along the diagonal: convex while beyond the plane x + y + z = 2 through
  // its neighbours 2, 5, 7, a re-entrant (inverted) corner once inside it.
  Corners c = box_corners();
  c[6] = Vec3(0.8, 0.8, 0.8);
  const double poor = scaled_jacobian(c);
  EXPECT_GT(poor, 0.0);
  EXPECT_LT(poor, 1.0);
  c[6] = Vec3(0.6, 0.6, 0.6);
  EXPECT_LT(detail::scaled_jacobian_terms(c).det[6], 0.0);
  EXPECT_LT(scaled_jacobian(c), 0.0);
}

TEST(ScaledJacobian, MeshValuesMatchPerElementValues) {
  core::HexMesh m = testing::structured_grid(50, 30, 20, 0.1);  // 30000 hexes: threaded
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  for (std::size_t n = 0; n < m.num_nodes(); ++n) {
    const core::NodeId id(static_cast<std::int32_t>(n));
    m.set_point(id, m.point(id) + Vec3(jitter(rng), jitter(rng), jitter(rng)));
  }
  const std::vector<double> v = scaled_jacobians(m);
  ASSERT_EQ(v.size(), m.num_hexes());
  for (std::size_t h = 0; h < v.size(); h += 997)
    EXPECT_EQ(v[h], scaled_jacobian(m.corners(core::HexId(static_cast<std::int32_t>(h)))));
  for (double x : v) {
    ASSERT_GT(x, 0.0);
    ASSERT_LE(x, 1.0);
  }
}

TEST(HexVolume, BoxIsProductOfSidesAndMirrorIsNegative) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(1.1, Vec3(0, 1, 1).normalized()).toRotationMatrix();
  Corners c = box_corners(2.0, 3.0, 0.5);
  for (auto& p : c) p = r * p + Vec3(1, 2, 3);
  EXPECT_NEAR(hex_volume(c), 3.0, 1e-13);
  EXPECT_NEAR(hex_volume(permuted(c, {4, 5, 6, 7, 0, 1, 2, 3})), -3.0, 1e-13);
}

TEST(HexVolume, ShearKeepsVolume) {
  Corners c = box_corners(2.0, 3.0, 4.0);
  for (auto& p : c) p.x() += 0.9 * p.z() + 0.3 * p.y();
  EXPECT_NEAR(hex_volume(c), 24.0, 1e-12);
}

TEST(HexVolume, TaperedBrickMatchesPrismatoidFormula) {
  // Planar trapezoid sides: the trilinear hex is the polyhedron, V = h/6 (A0 + A1 + 4 Am).
  const double dx = 4, dy = 3, dz = 2, t = 0.5;
  const Corners c = {
      Vec3(0, 0, 0),  Vec3(dx, 0, 0),      Vec3(dx, dy, 0),          Vec3(0, dy, 0),
      Vec3(t, t, dz), Vec3(dx - t, t, dz), Vec3(dx - t, dy - t, dz), Vec3(t, dy - t, dz)};
  const double expected =
      dz / 6 * (dx * dy + (dx - 2 * t) * (dy - 2 * t) + 4 * (dx - t) * (dy - t));
  EXPECT_NEAR(hex_volume(c), expected, 1e-12);
}

TEST(HexVolume, IsAdditiveOverTrilinearSubdivision) {
  // Restricted to a sub-cube, a trilinear map is again trilinear: the eight children of a
  // warped hex must add up to it exactly (checks exactness on non-planar faces).
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  for (int trial = 0; trial < 20; ++trial) {
    Corners c = box_corners(1.5, 1.0, 2.0);
    for (auto& p : c) p += Vec3(jitter(rng), jitter(rng), jitter(rng));
    double sum = 0;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int d = 0; d < 2; ++d) {
          Corners child;
          const int ref[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                 {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
          for (int i = 0; i < 8; ++i)
            child[i] =
                trilinear(c, 0.5 * (a + ref[i][0]), 0.5 * (b + ref[i][1]), 0.5 * (d + ref[i][2]));
          sum += hex_volume(child);
        }
    EXPECT_NEAR(sum, hex_volume(c), 1e-12);
  }
}

TEST(HexVolume, MatchesGaussQuadratureOfJacobianDeterminant) {
  // det J of a trilinear map has degree <= 2 per coordinate: 2-point Gauss is exact.
  const double g[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  const double h = 1e-6;  // central differences are exact for the (linear) partials
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.35, 0.35);
  for (int trial = 0; trial < 20; ++trial) {
    Corners c = box_corners(1.0, 2.0, 1.5);
    for (auto& p : c) p += Vec3(jitter(rng), jitter(rng), jitter(rng)) + Vec3(100, 50, -20);
    double gauss = 0;
    for (double u : g)
      for (double v : g)
        for (double w : g) {
          Eigen::Matrix3d j;
          j.col(0) = (trilinear(c, u + h, v, w) - trilinear(c, u - h, v, w)) / (2 * h);
          j.col(1) = (trilinear(c, u, v + h, w) - trilinear(c, u, v - h, w)) / (2 * h);
          j.col(2) = (trilinear(c, u, v, w + h) - trilinear(c, u, v, w - h)) / (2 * h);
          gauss += j.determinant() / 8;
        }
    EXPECT_NEAR(hex_volume(c), gauss, 1e-6);
  }
}

}  // namespace
}  // namespace vorohex::quality
