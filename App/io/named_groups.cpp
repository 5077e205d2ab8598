#include "io/named_groups.h"

#include <algorithm>
#include <map>
#include <set>

namespace vorohex::io {
namespace {

using IdSet = std::vector<std::int32_t>;  // sorted, unique

IdSet intersect(const IdSet& a, const IdSet& b) {
  IdSet out;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

void sort_unique(IdSet* s) {
  std::sort(s->begin(), s->end());
  s->erase(std::unique(s->begin(), s->end()), s->end());
}

// The model topology around each vertex and edge: what a node classified there also lies on.
struct Closure {
  std::vector<IdSet> vertex_edges, vertex_faces, edge_faces;  // index = id

  explicit Closure(const core::MeshDomain& d)
      : vertex_edges(d.num_vertices() + 1),
        vertex_faces(d.num_vertices() + 1),
        edge_faces(d.num_edges() + 1) {
    for (int e = 1; e <= d.num_edges(); ++e) {
      for (core::FaceId f : d.edge_faces(core::EdgeId(e))) edge_faces[e].push_back(f.value());
      sort_unique(&edge_faces[e]);
      for (core::VertexId v :
           {d.edge_first_vertex(core::EdgeId(e)), d.edge_last_vertex(core::EdgeId(e))}) {
        if (v.value() < 1 || v.value() > d.num_vertices()) continue;
        vertex_edges[v.value()].push_back(e);
        vertex_faces[v.value()].insert(vertex_faces[v.value()].end(), edge_faces[e].begin(),
                                       edge_faces[e].end());
      }
    }
    for (auto& s : vertex_edges) sort_unique(&s);
    for (auto& s : vertex_faces) sort_unique(&s);
  }

  bool valid(core::NodeClass c, int count) const { return c.id >= 1 && c.id < count; }

  // Faces a node of class c lies on.
  IdSet faces(core::NodeClass c) const {
    if (c.dim == 2) return {c.id};
    if (c.dim == 1 && valid(c, static_cast<int>(edge_faces.size()))) return edge_faces[c.id];
    if (c.dim == 0 && valid(c, static_cast<int>(vertex_faces.size()))) return vertex_faces[c.id];
    return {};
  }
  // Edges a node of class c lies on.
  IdSet edges(core::NodeClass c) const {
    if (c.dim == 1) return {c.id};
    if (c.dim == 0 && valid(c, static_cast<int>(vertex_edges.size()))) return vertex_edges[c.id];
    return {};
  }
};

}  // namespace

std::string entity_name(int dim, std::int32_t id) {
  static const char* const kKind[] = {"Vertex", "Edge", "Face"};
  return (dim >= 0 && dim <= 2 ? kKind[dim] : "Solid") + std::to_string(id);
}

std::vector<NamedGroup> named_groups(const core::HexMesh& mesh, const core::MeshDomain& domain) {
  const Closure closure(domain);
  const int counts[3] = {domain.num_vertices(), domain.num_edges(), domain.num_faces()};
  // groups[dim][id]
  std::map<std::int32_t, NamedGroup> groups[3];
  auto group = [&](int dim, std::int32_t id) -> NamedGroup& {
    NamedGroup& g = groups[dim][id];
    if (g.name.empty()) {
      g.name = entity_name(dim, id);
      g.dim = dim;
      g.id = id;
    }
    return g;
  };
  const auto& classes = mesh.node_classes();
  for (std::size_t n = 0; n < classes.size(); ++n) {
    const core::NodeClass c = classes[n];
    if (c.dim > 2 || c.id < 1 || c.id > counts[c.dim]) continue;
    const auto node = static_cast<std::int32_t>(n);
    group(c.dim, c.id).nodes.push_back(node);
    for (std::int32_t e : closure.edges(c))
      if (e != c.id || c.dim != 1) group(1, e).nodes.push_back(node);
    for (std::int32_t f : closure.faces(c))
      if (f != c.id || c.dim != 2) group(2, f).nodes.push_back(node);
  }

  const auto& hexes = mesh.hexes();
  const auto& points = mesh.points();
  std::set<std::pair<std::int32_t, std::int32_t>> seen_edges;
  for (const core::BoundaryFace& b : core::boundary_faces(mesh)) {
    const auto& quad = core::kHexFaces[b.face];
    IdSet faces = closure.faces(classes[hexes[b.hex][quad[0]]]);
    for (int i = 1; i < 4 && !faces.empty(); ++i)
      faces = intersect(faces, closure.faces(classes[hexes[b.hex][quad[i]]]));
    if (faces.size() > 1) {  // all corners on edges shared by these faces: the nearest
      core::Vec3 centre = core::Vec3::Zero();
      for (int i = 0; i < 4; ++i) centre += points[hexes[b.hex][quad[i]]] / 4.0;
      std::int32_t best = faces[0];
      double best_d = domain.distance_to_face(core::FaceId(best), centre);
      for (std::size_t k = 1; k < faces.size(); ++k) {
        const double d = domain.distance_to_face(core::FaceId(faces[k]), centre);
        if (d < best_d) best = faces[k], best_d = d;
      }
      faces = {best};
    }
    if (faces.size() == 1 && faces[0] <= counts[2])
      group(2, faces[0]).faces.push_back({b.hex, b.face});

    // The quad's sides along model edges (each mesh edge once).
    for (int i = 0; i < 4; ++i) {
      const int la = quad[i], lb = quad[(i + 1) % 4];
      const std::int32_t a = hexes[b.hex][la], c = hexes[b.hex][lb];
      if (!seen_edges.insert({std::min(a, c), std::max(a, c)}).second) continue;
      IdSet edges = intersect(closure.edges(classes[a]), closure.edges(classes[c]));
      const core::Vec3 mid = (points[a] + points[c]) / 2.0;
      const double length = (points[a] - points[c]).norm();
      // Both ends on an edge's closure but the side is a chord across a face: not along it.
      std::int32_t best = 0;
      double best_d = 0.3 * length;
      for (std::int32_t e : edges) {
        if (e > counts[1]) continue;
        const double d = domain.distance_to_edge(core::EdgeId(e), mid);
        if (d <= best_d) best = e, best_d = d;
      }
      if (best == 0) continue;
      int local = 0;
      for (int k = 0; k < 12; ++k) {
        const auto& ed = core::kHexEdges[k];
        if ((ed[0] == la && ed[1] == lb) || (ed[0] == lb && ed[1] == la)) local = k;
      }
      group(1, best).edges.push_back({b.hex, static_cast<std::int8_t>(local)});
    }
  }

  std::vector<NamedGroup> out;
  for (int dim : {2, 1, 0})
    for (auto& [id, g] : groups[dim]) {
      sort_unique(&g.nodes);
      out.push_back(std::move(g));
    }
  return out;
}

}  // namespace vorohex::io
