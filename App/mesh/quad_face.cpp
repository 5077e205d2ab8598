#include "mesh/quad_face.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/face_cusp.h"
#include "core/option_checks.h"
#include "mesh/detail/quad_mesh_2d.h"
#include "mesh/detail/sizing.h"

namespace vorohex::mesh {

using core::Vec3;
using detail::Vec2;

void QuadFaceOptions::validate() const {
  core::require_positive("QuadFaceOptions.size", size);
  core::require_at_least("QuadFaceOptions.smoothing_passes", smoothing_passes, 0);
  core::require_at_least("QuadFaceOptions.ring_layers", ring_layers, 0);
}

namespace {

// The 2-D scaled Jacobians of the mesher's quads, in its chart.
void set_quality(const detail::QuadMesh2d& m, QuadFaceMesh& out) {
  double sum = 0, lo = 1;
  for (const auto& q : m.quads) {
    const double x =
        detail::quad_quality(m.points[q[0]], m.points[q[1]], m.points[q[2]], m.points[q[3]]);
    sum += x;
    lo = std::min(lo, x);
  }
  out.min_quality = lo;
  out.mean_quality = m.quads.empty() ? 0 : sum / m.quads.size();
}

double loops_area(const std::vector<std::vector<Vec2>>& loops) {
  double area = 0;
  for (const auto& l : loops)
    for (std::size_t i = 0; i < l.size(); ++i) {
      const Vec2& a = l[i];
      const Vec2& b = l[(i + 1) % l.size()];
      area += a.x() * b.y() - a.y() * b.x();
    }
  return area;
}

// Planar faces are meshed in a frame that depends only on the plane, not on the face's
// orientation or parametrisation: the normal with its largest component positive, the
// world axis most nearly in the plane as the first direction, each loop run
// counter-clockwise from its lowest node. Two congruent faces facing opposite ways (the two
// ends of a post and of the column under it, swept onto the face they share) then get the
// same quads, so their projections onto a shared face coincide.
// The quad mesher's error, with where the face comes to a point when it does: the cause
// of such a failure (a boundary that crosses itself at the point, or a folded quad there).
std::string with_cusp(const core::MeshDomain& solid, core::FaceId face, const std::string& error) {
  const std::string cusp = core::face_cusp(solid, face);
  if (cusp.empty()) return error;
  return error + " (it comes to a point: " + cusp + "; no quad there has a positive angle)";
}

QuadFaceMesh planar_quad_face(const core::MeshDomain& solid, core::FaceId face,
                              const std::vector<std::vector<Vec3>>& loops,
                              const QuadFaceOptions& options, const std::string& name) {
  QuadFaceMesh out;
  const std::unique_ptr<core::SurfaceChart> chart_ptr = solid.face_chart(face);
  const core::SurfaceChart& chart = *chart_ptr;
  const Vec3 o3 = chart.to_surface(Vec2(0, 0));
  Vec3 n = (chart.to_surface(Vec2(1, 0)) - o3).cross(chart.to_surface(Vec2(0, 1)) - o3);
  n.normalize();
  int big = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) > std::abs(n[big]) + 1e-12) big = k;
  if (n[big] < 0) n = -n;
  int flat = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) < std::abs(n[flat]) - 1e-12) flat = k;
  Vec3 u = Vec3::Unit(flat) - n[flat] * n;
  u.normalize();
  const Vec3 v = n.cross(u);
  const double offset = n.dot(o3);
  auto to2 = [&](const Vec3& p) { return Vec2(p.dot(u), p.dot(v)); };
  std::vector<std::vector<Vec2>> loops2;
  for (const auto& loop : loops) {
    loops2.emplace_back();
    for (const Vec3& p : loop) loops2.back().push_back(to2(p));
  }
  // Clockwise in this frame (the face looks the other way): each loop reversed from its
  // first node, and the quads turned back at the end.
  const bool reversed = loops_area(loops2) < 0;
  // Each loop then starts at its lowest node (smallest u, then v, to a relative 1e-9):
  // where a loop starts shapes the mesh, and two congruent faces' loops need not start at
  // the same node (a circle's vertex lies at its face's seam).
  double extent = 0;
  for (const auto& l : loops2)
    for (const Vec2& q : l) extent = std::max(extent, q.norm());
  const double tie = 1e-9 * std::max(extent, 1.0);
  std::vector<int> given;  // mesher boundary index -> index in `loops` order
  int start = 0;
  for (auto& l : loops2) {
    const int m = int(l.size());
    std::vector<int> order(m);
    for (int i = 0; i < m; ++i) order[i] = reversed ? (m - i) % m : i;
    int first = 0;
    for (int i = 1; i < m; ++i) {
      const Vec2 &a = l[order[i]], &b = l[order[first]];
      if (a.x() < b.x() - tie || (a.x() <= b.x() + tie && a.y() < b.y() - tie)) first = i;
    }
    std::rotate(order.begin(), order.begin() + first, order.end());
    // Rounded to the tie tolerance: the same loop computed from two faces' own curves
    // differs in the last bits, which can tip the mesher's decisions.
    std::vector<Vec2> canonical(m);
    for (int i = 0; i < m; ++i) {
      const Vec2& q = l[order[i]];
      canonical[i] = Vec2(std::round(q.x() / tie) * tie, std::round(q.y() / tie) * tie);
      given.push_back(start + order[i]);
    }
    l = std::move(canonical);
    start += m;
  }
  detail::SizeAt size_at;
  if (detail::graded(options.size_field))
    size_at = [&](const Vec2& q) {
      return options.size_field->at(offset * n + q.x() * u + q.y() * v);
    };
  const detail::QuadMesh2d m = detail::quad_mesh_2d(loops2, options.size, options.smoothing_passes,
                                                    options.ring_layers, size_at);
  if (!m.error.empty()) {
    out.diagnostics.push_back(core::make_error(
        "quad_face_failed",
        "Quad meshing of " + name + " failed: " + with_cusp(solid, face, m.error) + ".", {name}));
    return out;
  }
  for (const auto& loop : loops) out.points.insert(out.points.end(), loop.begin(), loop.end());
  out.num_boundary = out.points.size();
  for (std::size_t i = out.num_boundary; i < m.points.size(); ++i)
    out.points.push_back(offset * n + m.points[i].x() * u + m.points[i].y() * v);
  auto index = [&](int k) { return k < int(given.size()) ? given[k] : k; };
  for (const auto& q : m.quads)
    out.quads.push_back(
        reversed ? std::array<int, 4>{index(q[0]), index(q[3]), index(q[2]), index(q[1])}
                 : std::array<int, 4>{index(q[0]), index(q[1]), index(q[2]), index(q[3])});
  set_quality(m, out);
  out.ok = true;
  return out;
}

}  // namespace

QuadFaceMesh quad_face(const core::MeshDomain& solid, core::FaceId face,
                       const std::vector<std::vector<Vec3>>& loops,
                       const QuadFaceOptions& options) {
  options.validate();
  QuadFaceMesh out;
  const std::string name = core::entity_name(face);
  auto fail = [&](const std::string& why) {
    out.diagnostics.push_back(core::make_error(
        "quad_face_failed", "Quad meshing of " + name + " failed: " + why + ".", {name}));
    return out;
  };
  try {
    if (solid.face_is_planar(face)) return planar_quad_face(solid, face, loops, options, name);
    const std::unique_ptr<core::SurfaceChart> chart_ptr = solid.face_chart(face);
    const core::SurfaceChart& chart = *chart_ptr;
    // Chart the loops; mirror the chart if the loops run clockwise in it (signed area < 0).
    std::vector<std::vector<Vec2>> loops2;
    double area = 0;
    for (const auto& loop : loops) {
      std::vector<Vec2> l;
      l.reserve(loop.size());
      for (const Vec3& p : loop) l.push_back(chart.to_chart(p));
      for (std::size_t i = 0; i < l.size(); ++i) {
        const Vec2& a = l[i];
        const Vec2& b = l[(i + 1) % l.size()];
        area += a.x() * b.y() - a.y() * b.x();
      }
      loops2.push_back(std::move(l));
    }
    const bool mirror = area < 0;
    if (mirror)
      for (auto& l : loops2)
        for (Vec2& p : l) p.x() = -p.x();
    detail::SizeAt size_at;
    if (detail::graded(options.size_field))
      size_at = [&](const Vec2& q) {
        return options.size_field->at(chart.to_surface(mirror ? Vec2(-q.x(), q.y()) : q));
      };
    const detail::QuadMesh2d m = detail::quad_mesh_2d(
        loops2, options.size, options.smoothing_passes, options.ring_layers, size_at);
    if (!m.error.empty()) return fail(with_cusp(solid, face, m.error));

    for (const auto& loop : loops) out.points.insert(out.points.end(), loop.begin(), loop.end());
    out.num_boundary = out.points.size();
    for (std::size_t i = out.num_boundary; i < m.points.size(); ++i) {
      Vec2 q = m.points[i];
      if (mirror) q.x() = -q.x();
      out.points.push_back(chart.to_surface(q));
    }
    out.quads = m.quads;
    set_quality(m, out);
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  out.ok = true;
  return out;
}

}  // namespace vorohex::mesh
