#include "core/face_cusp.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace vorohex::core {

namespace {

// The point at arc length `l` from the vertex an oriented edge starts at (at_end: from the
// vertex it ends at), sampled at spacing about `l`.
Vec3 along(const MeshDomain& d, const OrientedEdge& oe, bool at_end, double l) {
  const double length = d.edge_length(oe.edge);
  const int n = std::clamp(int(std::lround(length / l)), 1, 1000);
  const std::vector<Vec3> p = d.edge_points_by_length(oe.edge, n);
  const bool from_last = oe.forward == at_end;
  // Between the end point and the next sample, at exactly l along the chord's length.
  const Vec3& end = from_last ? p.back() : p.front();
  const Vec3& next = from_last ? p[p.size() - 2] : p[1];
  const double t = std::min(1.0, l / std::max(length / n, 1e-300));
  return end + t * (next - end);
}

}  // namespace

namespace {

// The cusps of face f, at vertex `only` (all when invalid). The wires are walked by their
// topology; geometry is asked only at the vertices looked at.
std::vector<Cusp> cusps(const MeshDomain& d, FaceId f, double degrees, VertexId only) {
  std::vector<Cusp> found;
  const double cos_limit = std::cos(degrees * M_PI / 180);
  // Per vertex, the edges into and out of it as the wires run: one of each per wire passing,
  // more where wires touch (a hole tangent to the outline is a wire of its own).
  std::map<int, std::pair<std::vector<OrientedEdge>, std::vector<OrientedEdge>>> at;
  for (const auto& wire : d.face_wires(f)) {
    const std::size_t n = wire.size();
    for (std::size_t k = 0; k < n; ++k) {
      const OrientedEdge& in = wire[(k + n - 1) % n];
      const OrientedEdge& out = wire[k];
      if (d.edge_is_degenerated(in.edge) || d.edge_is_degenerated(out.edge)) continue;
      const VertexId v = out.forward ? d.edge_first_vertex(out.edge) : d.edge_last_vertex(out.edge);
      if (only.valid() && v != only) continue;
      at[v.value()].first.push_back(in);
      at[v.value()].second.push_back(out);
    }
  }
  for (const auto& [id, edges] : at) {
    const VertexId v(id);
    const Vec3 vertex = d.vertex_point(v);
    const Vec3 normal = d.face_normal(f, vertex);
    for (const OrientedEdge& in : edges.first)
      for (const OrientedEdge& out : edges.second) {
        const double shorter = std::min(d.edge_length(in.edge), d.edge_length(out.edge));
        if (!(shorter > 0)) continue;
        // First from chords over an eighth of each edge (cheap; an eighth of a full circle
        // turns 22.5 degrees): corners far from a point are passed over.
        const std::vector<Vec3> pi = d.edge_points_by_length(in.edge, 8);
        const std::vector<Vec3> po = d.edge_points_by_length(out.edge, 8);
        const Vec3 c_in8 = in.forward ? Vec3(pi[8] - pi[7]) : Vec3(pi[0] - pi[1]);
        const Vec3 c_out8 = out.forward ? Vec3(po[1] - po[0]) : Vec3(po[7] - po[8]);
        if (c_in8.norm() > 0 && c_out8.norm() > 0 &&
            c_in8.normalized().dot(c_out8.normalized()) > -std::cos(M_PI / 3))
          continue;
        // Directions of travel into and out of the vertex, from chords 1% of the shorter edge.
        const double l_tangent = 0.01 * shorter;
        const Vec3 t_in = vertex - along(d, in, true, l_tangent);
        const Vec3 t_out = along(d, out, false, l_tangent) - vertex;
        if (t_in.norm() <= 0 || t_out.norm() <= 0) continue;
        if (t_in.normalized().dot(t_out.normalized()) > -cos_limit) continue;
        // Going back along itself: a point when it turns towards the face (the face lies
        // between the edges), the end of a slit when it turns away; told apart by chords of
        // the same length along both edges (the one that curves more bends towards the face).
        const double l = 0.25 * shorter;
        const Vec3 c_in = vertex - along(d, in, true, l);
        const Vec3 c_out = along(d, out, false, l) - vertex;
        if (c_in.cross(c_out).dot(normal) <= 1e-9 * c_in.norm() * c_out.norm()) continue;
        found.push_back({f, v, in, out});
      }
  }
  return found;
}

}  // namespace

std::vector<Cusp> face_cusps(const MeshDomain& d, FaceId f, double degrees) {
  return cusps(d, f, degrees, VertexId());
}

std::vector<Cusp> cusps_at(const MeshDomain& d, FaceId f, VertexId v, double degrees) {
  return cusps(d, f, degrees, v);
}

double cusp_signed_angle(const MeshDomain& d, const Cusp& c, double l_in, double l_out) {
  const Vec3 vertex = d.vertex_point(c.vertex);
  // a: back along the edge the wire runs in by; b: along the edge it runs out by. The face
  // lies to the left of the wire (about its normal), so from b to a counter-clockwise.
  const Vec3 a = along(d, c.in, true, std::min(l_in, d.edge_length(c.in.edge))) - vertex;
  const Vec3 b = along(d, c.out, false, std::min(l_out, d.edge_length(c.out.edge))) - vertex;
  if (a.norm() <= 0 || b.norm() <= 0) return 0;
  const Vec3 n = d.face_normal(c.face, vertex);
  return std::atan2(b.cross(a).dot(n), b.dot(a));
}

std::string face_cusp(const MeshDomain& d, FaceId f, double degrees) {
  const std::vector<Cusp> cusps = face_cusps(d, f, degrees);
  if (cusps.empty()) return {};
  const Cusp& c = cusps.front();
  return entity_name(c.vertex) + " of " + entity_name(f) + ", where " + entity_name(c.in.edge) +
         " and " + entity_name(c.out.edge) + " meet tangentially";
}

std::string first_cusp(const MeshDomain& d, double degrees) {
  for (FaceId f : d.faces()) {
    std::string where = face_cusp(d, f, degrees);
    if (!where.empty()) return where;
  }
  return {};
}

}  // namespace vorohex::core
