#include "smooth/restore_topology.h"

#include <algorithm>
#include <vector>

#include "occ/split_solid.h"

namespace vorohex::smooth {

using core::EdgeId;
using core::FaceId;
using core::NodeClass;
using core::VertexId;

namespace {

// Distance from p to the original entity of a (non-interior) class.
double distance_to(const occ::Solid& original, NodeClass c, const core::Vec3& p) {
  return c.dim == 0   ? original.distance_to_vertex(VertexId(c.id), p)
         : c.dim == 1 ? original.distance_to_edge(EdgeId(c.id), p)
                      : original.distance_to_face(FaceId(c.id), p);
}

}  // namespace

RestoreStats restore_topology(core::HexMesh& mesh, const occ::Solid& pieces,
                              const occ::Solid& original, double tolerance) {
  // Faces: a shared (decomposition) face is inside; any other lies on an original face.
  std::vector<NodeClass> face_class(pieces.num_faces() + 1, NodeClass::interior());
  for (const occ::FaceSample& s : occ::sample_faces(pieces))
    if (!pieces.face_is_interface(s.face))
      face_class[s.face.value()] = NodeClass::on(original.nearest_face(s.point));
  // A face of the pieces can span several original faces: coplanar faces that the union of
  // two pieces made one (HexMe i06: Face29 and Face30, both on x = -41). Such a face has
  // points of its boundary off the original face it was given; only its nodes are looked
  // at one by one below.
  std::vector<char> spans(pieces.num_faces() + 1, 0);
  for (FaceId f : pieces.faces()) {
    const NodeClass c = face_class[f.value()];
    if (c.is_interior()) continue;
    for (const auto& wire : pieces.face_wires(f))
      for (const core::OrientedEdge& oe : wire) {
        if (spans[f.value()] || pieces.edge_is_degenerated(oe.edge)) continue;
        for (const core::Vec3& p : pieces.edge_points_by_length(oe.edge, 4))
          if (original.distance_to_face(FaceId(c.id), p) > tolerance) spans[f.value()] = 1;
      }
  }

  // Edges: along an original edge (two inner points on it), else in the original face of a
  // boundary face it bounds (all such faces lie on one original face, or the edge would be
  // on the original edge between them), else inside.
  std::vector<NodeClass> edge_class(pieces.num_edges() + 1, NodeClass::interior());
  for (EdgeId e : pieces.edges()) {
    NodeClass on_face = NodeClass::interior();
    for (FaceId f : pieces.edge_faces(e))
      if (!face_class[f.value()].is_interior()) on_face = face_class[f.value()];
    if (on_face.is_interior()) continue;
    edge_class[e.value()] = on_face;
    if (pieces.edge_is_degenerated(e)) continue;
    const std::vector<core::Vec3> p = pieces.edge_points_by_length(e, 3);
    const EdgeId near = original.nearest_edge(p[1]);
    if (!near.valid() || original.distance_to_edge(near, p[1]) > tolerance) continue;
    if (original.distance_to_edge(near, p[2]) <= tolerance) {
      edge_class[e.value()] = NodeClass::on(near);
      continue;
    }
    // Along two original edges (a circle the union of two pieces made one edge, over the
    // original's two half circles: HexMe i22's boss rim at x = 45, between its end face and
    // its round top): on the first, spanning (below), so that each node goes to the edge it
    // lies on. Given a face instead, its nodes slid off the rim while smoothing and the mesh
    // cut the corner off (0.8 % of i22's volume, within the check's chord allowance).
    const EdgeId other = original.nearest_edge(p[2]);
    if (!other.valid() || original.distance_to_edge(other, p[2]) > tolerance) continue;
    bool along_both = true;
    for (const core::Vec3& q : pieces.edge_points_by_length(e, 8))
      along_both = along_both && std::min(original.distance_to_edge(near, q),
                                          original.distance_to_edge(other, q)) <= tolerance;
    if (along_both) edge_class[e.value()] = NodeClass::on(near);
  }

  // An edge of the pieces can span several original entities too: a hole's circle that the
  // union of two pieces made one edge lies on the original's two half circles (HexMe i22's
  // bore), so its class (the face of one half) holds only half of it; its nodes too are
  // looked at one by one below.
  std::vector<char> edge_spans(pieces.num_edges() + 1, 0);
  for (EdgeId e : pieces.edges()) {
    const NodeClass c = edge_class[e.value()];
    if (c.is_interior() || pieces.edge_is_degenerated(e)) continue;
    for (const core::Vec3& p : pieces.edge_points_by_length(e, 4))
      if (distance_to(original, c, p) > tolerance) {
        edge_spans[e.value()] = 1;
        break;
      }
  }

  // Vertices: an original vertex, else the class of a boundary edge through it (an
  // original edge first), else inside.
  std::vector<NodeClass> vertex_class(pieces.num_vertices() + 1, NodeClass::interior());
  for (EdgeId e : pieces.edges()) {
    const NodeClass c = edge_class[e.value()];
    if (c.is_interior()) continue;
    for (VertexId v : {pieces.edge_first_vertex(e), pieces.edge_last_vertex(e)}) {
      NodeClass& vc = vertex_class[v.value()];
      if (vc.is_interior() || (vc.dim == 2 && c.dim == 1)) vc = c;
    }
  }
  for (VertexId v : pieces.vertices()) {
    if (vertex_class[v.value()].is_interior()) continue;
    const core::Vec3 p = pieces.vertex_point(v);
    for (VertexId w : original.vertices())
      if (original.distance_to_vertex(w, p) <= tolerance) {
        vertex_class[v.value()] = NodeClass::on(w);
        break;
      }
  }

  RestoreStats stats;
  for (std::size_t i = 0; i < mesh.num_nodes(); ++i) {
    const core::NodeId n(static_cast<std::int32_t>(i));
    const NodeClass c = mesh.node_class(n);
    if (c.is_interior()) continue;
    NodeClass r = c.dim == 0   ? vertex_class[c.id]
                  : c.dim == 1 ? edge_class[c.id]
                               : face_class[c.id];
    // A node of a face or an edge spanning several original entities, or of a vertex that
    // is none of the original's, off the one it was given, goes to the original entity it
    // lies on.
    const bool spanning = c.dim == 2   ? r.dim == 2 && spans[c.id]
                          : c.dim == 1 ? edge_spans[c.id] != 0
                                       : r.dim != 0;
    if (!r.is_interior() && spanning && distance_to(original, r, mesh.point(n)) > tolerance) {
      const core::Vec3 p = mesh.point(n);
      const EdgeId near = original.nearest_edge(p);
      if (near.valid() && original.distance_to_edge(near, p) <= tolerance)
        r = NodeClass::on(near);
      else
        r = NodeClass::on(original.nearest_face(p));
      ++stats.reclassified;
    }
    mesh.set_node_class(n, r);
    if (r.is_interior())
      ++stats.interior;
    else
      ++(r.dim == 0 ? stats.on_vertices : r.dim == 1 ? stats.on_edges : stats.on_faces);
  }
  return stats;
}

}  // namespace vorohex::smooth
