#include "grid/detail/grid_frame.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vorohex::grid::detail {
namespace {

using core::Vec3;

struct Direction {
  Vec3 d;
  double weight = 0;
};

// Adds `d` (up to sign) to the clusters, weighted.
void add_direction(std::vector<Direction>& dirs, Vec3 d, double w) {
  if (!(d.norm() > 0.5)) return;
  d.normalize();
  for (Direction& c : dirs)
    if (std::abs(c.d.dot(d)) > std::cos(5 * M_PI / 180)) {
      c.weight += w;
      return;
    }
  dirs.push_back({d, w});
}

Vec3 heaviest(const std::vector<Direction>& dirs, const Vec3* perpendicular_to) {
  double best = -1;
  Vec3 out = Vec3::Zero();
  for (const Direction& c : dirs) {
    if (perpendicular_to && std::abs(c.d.dot(*perpendicular_to)) > std::sin(5 * M_PI / 180))
      continue;
    if (c.weight > best) best = c.weight, out = c.d;
  }
  return out;
}

// A unit vector perpendicular to a, as close to a world axis as possible.
Vec3 any_perpendicular(const Vec3& a) {
  Vec3 best = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    Vec3 e = Vec3::Unit(i);
    Vec3 p = e - a * a.dot(e);
    if (p.norm() > best.norm()) best = p;
  }
  return best.normalized();
}

}  // namespace

GridFrame grid_frame(const core::MeshDomain& solid, const std::vector<Vec3>& boundary_points,
                     double size, double min_gap) {
  GridFrame frame;
  std::vector<Direction> planes, axes;
  struct PlaneOffset {
    Vec3 normal, origin;
    double area;
  };
  std::vector<PlaneOffset> offsets;
  for (core::FaceId f : solid.faces()) {
    const core::SurfaceInfo s = solid.surface_info(f);
    const double area = std::abs(solid.area(f));
    if (s.kind == core::SurfaceKind::plane) {
      add_direction(planes, s.direction, area);
      offsets.push_back({s.direction.normalized(), s.origin, area});
    } else if (s.kind == core::SurfaceKind::cylinder || s.kind == core::SurfaceKind::cone ||
               s.kind == core::SurfaceKind::revolution || s.kind == core::SurfaceKind::torus) {
      add_direction(axes, s.direction, area);
    }
  }
  Vec3 a0 = heaviest(planes, nullptr), a1 = Vec3::Zero();
  if (a0.norm() > 0.5) {
    frame.how = "planar faces";
    a1 = heaviest(planes, &a0);
    if (a1.norm() < 0.5) {
      // One plane direction: a turned part's axis, if any, is perpendicular to it or along it.
      const Vec3 ax = heaviest(axes, &a0);
      a1 = ax.norm() > 0.5 ? ax : any_perpendicular(a0);
    }
  } else {
    a0 = heaviest(axes, nullptr);
    if (a0.norm() > 0.5) {
      frame.how = "axis of revolution";
      a1 = any_perpendicular(a0);
    } else {
      frame.how = "world axes";
      a0 = Vec3::UnitX();
      a1 = Vec3::UnitY();
    }
  }
  a1 = (a1 - a0 * a0.dot(a1)).normalized();
  frame.axes = {a0, a1, a0.cross(a1)};

  for (int a = 0; a < 3; ++a) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Vec3& p : boundary_points) {
      const double t = p.dot(frame.axes[a]);
      lo = std::min(lo, t), hi = std::max(hi, t);
    }
    if (!(hi > lo)) lo = -0.5 * size, hi = 0.5 * size;
    // Planes normal to this axis, largest first; one per min_gap * size.
    std::vector<std::pair<double, double>> cand;  // (area, offset)
    for (const PlaneOffset& o : offsets)
      if (std::abs(o.normal.dot(frame.axes[a])) > 1 - 1e-9)
        cand.emplace_back(o.area, o.origin.dot(frame.axes[a]));
    std::sort(cand.begin(), cand.end(), [](auto& x, auto& y) { return x.first > y.first; });
    std::vector<double> accepted;
    const double tight = 1e-9 * (hi - lo + size);
    for (const auto& [area, t] : cand) {
      bool ok = t > lo - tight && t < hi + tight;
      for (double s : accepted) ok = ok && std::abs(s - t) > min_gap * size;
      if (ok) accepted.push_back(t);
    }
    for (double t : {lo, hi}) {
      bool ok = true;
      for (double s : accepted) ok = ok && std::abs(s - t) > tight;
      if (ok) accepted.push_back(t);
    }
    std::sort(accepted.begin(), accepted.end());
    std::vector<double>& lines = frame.lines[a];
    lines.push_back(accepted.front());
    for (std::size_t i = 1; i < accepted.size(); ++i) {
      const double len = accepted[i] - accepted[i - 1];
      const int n = std::max(1, int(std::lround(len / size)));
      for (int k = 1; k <= n; ++k)
        lines.push_back(k == n ? accepted[i] : accepted[i - 1] + len * k / n);
    }
  }
  return frame;
}

}  // namespace vorohex::grid::detail
