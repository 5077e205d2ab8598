#include "mesh/detail/cad_lookup.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace vorohex::mesh::detail {

using core::NodeClass;

NodeClass cad_entity_at(const core::MeshDomain& solid, const core::Vec3& p, double tol,
                        NodeClass hint) {
  for (core::VertexId v : solid.vertices())
    if (solid.distance_to_vertex(v, p) <= tol) return NodeClass::on(v);
  if (hint.dim == 1 && solid.distance_to_edge(core::EdgeId(hint.id), p) <= tol) return hint;
  const core::EdgeId e = solid.nearest_edge(p);
  if (e.valid() && solid.distance_to_edge(e, p) <= tol) return NodeClass::on(e);
  if (hint.dim == 2 && solid.distance_to_face(core::FaceId(hint.id), p) <= tol) return hint;
  const core::FaceId f = solid.nearest_face(p);
  if (f.valid() && solid.distance_to_face(f, p) <= tol) return NodeClass::on(f);
  return NodeClass::interior();
}

core::Vec3 onto_face_along(const core::MeshDomain& solid, core::FaceId f, core::Vec3 p,
                           const core::Vec3& d) {
  for (int k = 0; k < 8 && d.norm() > 0; ++k) {
    // Onto the face's tangent plane at the nearest point, along d (Newton's step: exact on a
    // plane); where the face turns almost along d, only the nearest point's part along d.
    const core::Vec3 q = solid.project_to_face(f, p);
    const core::Vec3 n = solid.face_normal(f, q);
    const double across = n.dot(d);
    const core::Vec3 step = std::isfinite(across) && std::abs(across) > 0.2
                                ? ((q - p).dot(n) / across) * d
                                : (q - p).dot(d) * d;
    p += step;
    if (step.norm() <= 1e-12 * (1 + p.norm())) break;
  }
  return solid.project_to_face(f, p);
}

std::vector<core::VertexId> apex_vertices(const core::MeshDomain& solid, core::FaceId f) {
  // A face's corners: the ends of its edges other than degenerated ones and seams (an edge
  // that bounds only this face, met twice along its wire).
  std::set<int> corners;
  for (const auto& w : solid.face_wires(f))
    for (const core::OrientedEdge& oe : w) {
      if (solid.edge_is_degenerated(oe.edge)) continue;
      const std::vector<core::FaceId> faces = solid.edge_faces(oe.edge);
      if (std::all_of(faces.begin(), faces.end(), [&](core::FaceId g) { return g == f; })) continue;
      corners.insert(solid.edge_first_vertex(oe.edge).value());
      corners.insert(solid.edge_last_vertex(oe.edge).value());
    }
  std::vector<core::VertexId> out;
  for (const auto& w : solid.face_wires(f))
    for (const core::OrientedEdge& oe : w)
      if (solid.edge_is_degenerated(oe.edge) &&
          !corners.count(solid.edge_first_vertex(oe.edge).value()))
        out.push_back(solid.edge_first_vertex(oe.edge));
  return out;
}

}  // namespace vorohex::mesh::detail
