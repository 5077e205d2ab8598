#include "quality/sharp_edges.h"

#include <algorithm>
#include <cmath>

namespace vorohex::quality {

using core::EdgeId;
using core::FaceId;
using core::Vec3;

double SharpEdges::bound() const {
  double b = 1;
  for (const SharpEdge& e : edges) b = std::min(b, e.bound);
  return b;
}

namespace {

// The angle inside the part between the two faces of edge e at its point m (tangent t), in
// radians: below pi at a convex edge, above at a concave one.
// `eps`: a step into the face (a small fraction of the part's size).
double inside_angle(const occ::Solid& s, FaceId f0, FaceId f1, const Vec3& m, const Vec3& t,
                    double eps) {
  const Vec3 n0 = s.face_normal(f0, m), n1 = s.face_normal(f1, m);
  // The direction from the edge into f0, across the edge.
  Vec3 d0 = n0.cross(t).normalized();
  if (s.distance_to_face(f0, m + eps * d0) > s.distance_to_face(f0, m - eps * d0)) d0 = -d0;
  const double between = std::acos(std::clamp(n0.dot(n1), -1.0, 1.0));
  return d0.dot(n1) > 0 ? M_PI + between : M_PI - between;
}

}  // namespace

SharpEdges sharp_edges(const occ::Solid& solid, double below) {
  SharpEdges out;
  const double eps = 1e-4 * solid.diagonal();  // the optimal bounding box: computed once
  for (EdgeId e : solid.edges()) {
    if (solid.edge_is_degenerated(e)) continue;
    const std::vector<FaceId> faces = solid.edge_faces(e);
    if (faces.size() != 2 || faces[0] == faces[1]) continue;  // a seam
    // At its middle first (OCCT's projections cost: HexMe i07's 300 edges took 2.3 s at
    // seven points each); an edge sharper than 100 degrees there is measured along it.
    const std::vector<Vec3> p = solid.edge_points_by_length(e, 16);
    auto angle_at = [&](int k) {
      const Vec3 t = (p[k + 1] - p[k - 1]).normalized();
      return t.allFinite() ? inside_angle(solid, faces[0], faces[1], p[k], t, eps) : M_PI;
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
