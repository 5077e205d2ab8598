#include "mesh/detail/cad_lookup.h"

namespace vorohex::mesh::detail {

using core::NodeClass;

NodeClass cad_entity_at(const occ::Solid& solid, const core::Vec3& p, double tol, NodeClass hint) {
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

}  // namespace vorohex::mesh::detail
