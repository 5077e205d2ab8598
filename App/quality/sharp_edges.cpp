#include "quality/sharp_edges.h"

#include <algorithm>
#include <cmath>

namespace vorohex::quality {

using core::EdgeId;
using core::Vec3;

double SharpEdges::bound() const {
  double b = 1;
  for (const SharpEdge& e : edges) b = std::min(b, e.bound);
  return b;
}

SharpEdges sharp_edges(const occ::Solid& solid, double below) {
  SharpEdges out;
  for (EdgeId e : solid.edges()) {
    if (solid.edge_is_degenerated(e)) continue;
    // At its middle first (each point costs two OCCT projections), and along an edge
    // sharper than 100 degrees there.
    const std::vector<Vec3> p = solid.edge_points_by_length(e, 16);
    auto angle_at = [&](int k) {
      const Vec3 t = (p[k + 1] - p[k - 1]).normalized();
      const double a = t.allFinite() ? solid.interior_angle(e, p[k], t) : M_PI;
      return std::isnan(a) ? M_PI : a;  // a seam, or not between two faces: no bound
    };
    double smallest = angle_at(8);
    bool all_convex = smallest < M_PI - 1e-6;
    if (all_convex && smallest < 100 * M_PI / 180)
      for (int k = 2; k <= 14; k += 2) {
        if (k == 8) continue;
        const double a = angle_at(k);
        all_convex = all_convex && a < M_PI - 1e-6;
        smallest = std::min(smallest, a);
      }
    if (!all_convex || !(smallest < M_PI / 2)) continue;
    const double bound = std::sin(smallest);
    if (bound < below) out.edges.push_back({e, smallest * 180 / M_PI, bound});
  }
  std::sort(out.edges.begin(), out.edges.end(),
            [](const SharpEdge& a, const SharpEdge& b) { return a.bound < b.bound; });
  return out;
}

}  // namespace vorohex::quality
