#include "mesh/quad_face.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/option_checks.h"
#include "mesh/detail/quad_mesh_2d.h"
#include "occ/face_chart.h"

namespace vorohex::mesh {

using core::Vec3;
using detail::Vec2;

void QuadFaceOptions::validate() const {
  core::require_positive("QuadFaceOptions.size", size);
  core::require_at_least("QuadFaceOptions.smoothing_passes", smoothing_passes, 0);
}

QuadFaceMesh quad_face(const occ::Solid& solid, core::FaceId face,
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
    const occ::FaceChart chart(solid, face);
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
    const detail::QuadMesh2d m =
        detail::quad_mesh_2d(loops2, options.size, options.smoothing_passes);
    if (!m.error.empty()) return fail(m.error);

    for (const auto& loop : loops) out.points.insert(out.points.end(), loop.begin(), loop.end());
    out.num_boundary = out.points.size();
    for (std::size_t i = out.num_boundary; i < m.points.size(); ++i) {
      Vec2 q = m.points[i];
      if (mirror) q.x() = -q.x();
      out.points.push_back(chart.to_surface(q));
    }
    out.quads = m.quads;
    double sum = 0, lo = 1;
    for (const auto& q : m.quads) {
      const double x =
          detail::quad_quality(m.points[q[0]], m.points[q[1]], m.points[q[2]], m.points[q[3]]);
      sum += x;
      lo = std::min(lo, x);
    }
    out.min_quality = lo;
    out.mean_quality = m.quads.empty() ? 0 : sum / m.quads.size();
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  out.ok = true;
  return out;
}

}  // namespace vorohex::mesh
