#include "decompose/detail/rules.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>

namespace vorohex::decompose::detail {

using core::EdgeId;
using core::FaceId;
using core::VertexId;

// ModelRelations ------------------------------------------------------------------------

bool ModelRelations::unconnected(EntityRef a, EntityRef b) const {
  return model_.unconnected(a, b);
}

std::optional<EntityRef> ModelRelations::shared_edge(EntityRef a, EntityRef b) const {
  if (a.kind != EntityKind::face || b.kind != EntityKind::face || a == b) return std::nullopt;
  const auto& eb = model_.face(FaceId(b.id)).edges;
  for (EdgeId e : model_.face(FaceId(a.id)).edges)
    if (std::find(eb.begin(), eb.end(), e) != eb.end()) return model::ref(e);
  return std::nullopt;
}

bool ModelRelations::bounds(EntityRef edge, EntityRef face) const {
  if (edge.kind != EntityKind::edge || face.kind != EntityKind::face) return false;
  const auto& fe = model_.face(FaceId(face.id)).edges;
  return std::find(fe.begin(), fe.end(), EdgeId(edge.id)) != fe.end();
}

bool ModelRelations::common_vertex(const std::vector<EntityRef>& entities) const {
  std::vector<int> common;
  bool first = true;
  for (const EntityRef& e : entities) {
    std::vector<int> vs;
    if (e.kind == EntityKind::vertex) vs = {e.id};
    if (e.kind == EntityKind::edge) {
      const auto& me = model_.edge(EdgeId(e.id));
      vs = {me.first.value(), me.last.value()};
    }
    if (e.kind == EntityKind::face)
      for (VertexId v : model_.face(FaceId(e.id)).vertices) vs.push_back(v.value());
    std::sort(vs.begin(), vs.end());
    if (first) {
      common = vs;
      first = false;
      continue;
    }
    std::vector<int> out;
    std::set_intersection(common.begin(), common.end(), vs.begin(), vs.end(),
                          std::back_inserter(out));
    common.swap(out);
  }
  return !first && !common.empty();
}

double ModelRelations::dihedral(EntityRef edge) const {
  return model_.edge(EdgeId(edge.id)).dihedral;
}

// Classification ------------------------------------------------------------------------

const char* edge_type_name(EdgeType t) {
  switch (t) {
    case EdgeType::none:
      return "none";
    case EdgeType::t0:
      return "[0]";
    case EdgeType::t1:
      return "[1]";
    case EdgeType::t1s:
      return "[1s]";
    case EdgeType::t2:
      return "[2]";
    case EdgeType::t3:
      return "[3]";
    case EdgeType::t1e:
      return "[1e]";
    case EdgeType::t0e:
      return "[0e]";
    case EdgeType::tc:
      return "[C]";
    case EdgeType::degenerate:
      return "degenerate";
  }
  return "?";
}

namespace {

bool is_forced(const std::vector<std::pair<EntityRef, EntityRef>>& pairs, EntityRef a,
               EntityRef b) {
  for (const auto& p : pairs)
    if ((p.first == a && p.second == b) || (p.first == b && p.second == a)) return true;
  return false;
}

}  // namespace

EdgeClass classify_edge(const std::vector<EntityRef>& governors, const Relations& rel,
                        double sharp_angle,
                        const std::vector<std::pair<EntityRef, EntityRef>>& force_sharp) {
  EdgeClass out;
  std::vector<EntityRef> faces, others;
  for (const EntityRef& g : governors) (g.kind == EntityKind::face ? faces : others).push_back(g);
  if (governors.size() < 3) return out;
  if (rel.common_vertex(governors)) {
    out.type = EdgeType::tc;
    return out;
  }
  const int n = int(faces.size());
  for (int i = 0; i < n && !out.interest; ++i)
    for (int j = i + 1; j < n; ++j)
      if (rel.unconnected(faces[i], faces[j])) out.interest = true;

  // The share-an-edge graph of the face governors and its components.
  std::vector<int> comp(n), degree(n, 0);
  std::iota(comp.begin(), comp.end(), 0);
  auto root = [&](int i) {
    while (comp[i] != i) i = comp[i];
    return i;
  };
  int arcs = 0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (rel.shared_edge(faces[i], faces[j])) {
        ++arcs, ++degree[i], ++degree[j];
        comp[root(i)] = root(j);
      }
  std::map<int, std::vector<int>> components;
  for (int i = 0; i < n; ++i) components[root(i)].push_back(i);

  // The type label (the paper's names for three governors).
  const bool three = governors.size() == 3;
  if (three && n == 3) {
    const EdgeType by_arcs[] = {EdgeType::t0, EdgeType::t1, EdgeType::t2, EdgeType::t3};
    out.type = by_arcs[arcs];
  } else if (three && n == 2) {
    const EntityRef g = others[0];
    const bool bounding =
        g.kind == EntityKind::edge && (rel.bounds(g, faces[0]) || rel.bounds(g, faces[1]));
    out.type = bounding ? EdgeType::t1e : EdgeType::t0e;
  } else {
    out.type = EdgeType::degenerate;
  }
  if (!out.interest && out.type != EdgeType::t3) {
    out.type = EdgeType::none;
    return out;
  }

  // A face is projected onto an edge governor bounding it ([1e]), else onto itself.
  auto face_target = [&](EntityRef f) {
    for (const EntityRef& g : others)
      if (g.kind == EntityKind::edge && rel.bounds(g, f)) return Target{g, {f}};
    return Target{f, {f}};
  };
  if (components.size() == 1) {
    // All faces chained by shared edges: a cycle is [3] (projected as [0]), a chain is
    // [2] (not projected: the sub-volumes extend to the boundary).
    const bool cycle =
        n >= 3 && std::all_of(degree.begin(), degree.end(), [](int d) { return d >= 2; });
    if (cycle)
      for (const EntityRef& f : faces) out.targets.push_back(face_target(f));
    return out;
  }
  bool sharpened = false;
  for (const auto& [r, members] : components) {
    if (members.size() == 2) {
      const EntityRef b = faces[members[0]], c = faces[members[1]];
      const EntityRef e = *rel.shared_edge(b, c);
      const bool sharp = rel.dihedral(e) < sharp_angle || is_forced(force_sharp, b, c);
      if (!sharp) {
        out.targets.push_back(Target{e, {b, c}});
        continue;
      }
      sharpened = true;
    }
    for (int i : members) out.targets.push_back(face_target(faces[i]));
  }
  if (sharpened && out.type == EdgeType::t1) out.type = EdgeType::t1s;
  return out;
}

// Vertex treatment ----------------------------------------------------------------------

std::optional<EntityRef> VertexTreatment::point_of(EntityRef f) const {
  for (const auto& [face, target] : points)
    if (face == f) return target;
  return std::nullopt;
}

VertexTreatment treat_vertex(const std::vector<EntityRef>& governors,
                             const std::vector<IncidentEdge>& edges, const Relations& rel) {
  VertexTreatment out;
  std::vector<std::string> names;
  for (const IncidentEdge& e : edges) names.push_back(edge_type_name(e.cls.type));
  std::sort(names.begin(), names.end());
  out.row = "[";
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::string s = names[i];
    if (s.front() == '[') s = s.substr(1, s.size() - 2);
    out.row += (i ? "," : "") + s;
  }
  out.row += "]";

  // Requests: face -> target entities asked for by the projected edges.
  std::map<EntityRef, std::set<EntityRef>> requests;
  std::map<EntityRef, int> branches;  // cut branches ending at each face's point
  bool projected = false;
  for (const IncidentEdge& e : edges)
    for (const Target& t : e.cls.targets) {
      projected = true;
      for (const EntityRef& f : t.faces) {
        requests[f].insert(t.entity);
        if (t.entity.kind != EntityKind::edge || rel.bounds(t.entity, f) == false ||
            t.faces.size() == 1)
          ++branches[f];
      }
    }
  auto is_governor = [&](EntityRef x) {
    return std::find(governors.begin(), governors.end(), x) != governors.end();
  };
  // One point per face: an edge governor bounding the face wins (it is where the face's
  // region ends); otherwise a face asked for both itself and a shared edge, or for two
  // shared edges, makes the [1] edges involved [1s] (projected on the faces).
  for (const auto& [f, targets] : requests) {
    if (targets.size() == 1) {
      out.points.emplace_back(f, *targets.begin());
      continue;
    }
    std::optional<EntityRef> governor_edge;
    for (const EntityRef& t : targets)
      if (t.kind == EntityKind::edge && is_governor(t)) governor_edge = t;
    if (governor_edge) {
      out.points.emplace_back(f, *governor_edge);
      continue;
    }
    for (const IncidentEdge& e : edges)
      for (const Target& t : e.cls.targets)
        if (t.faces.size() == 2 && std::find(t.faces.begin(), t.faces.end(), f) != t.faces.end())
          out.sharpen.emplace_back(t.faces[0], t.faces[1]);
  }
  if (!out.sharpen.empty()) {
    std::sort(out.sharpen.begin(), out.sharpen.end());
    out.sharpen.erase(std::unique(out.sharpen.begin(), out.sharpen.end()), out.sharpen.end());
    out.points.clear();
    return out;
  }

  auto add_rectangle = [&](EntityRef a, EntityRef b) {
    if (a.kind != EntityKind::face || b.kind != EntityKind::face) return;
    const auto e = rel.shared_edge(a, b);
    if (!e) return;
    if (b < a) std::swap(a, b);
    const Rectangle r{a, b, *e};
    if (std::find(out.rectangles.begin(), out.rectangles.end(), r) != out.rectangles.end()) return;
    out.rectangles.push_back(r);
    for (EntityRef f : {a, b}) {
      if (!out.point_of(f)) out.points.emplace_back(f, f);
      ++branches[f];
    }
  };

  // [2] edges: when the vertex also bounds other f_s faces (a projected edge, or four [2]
  // edges), separate them by rectangles between the middle face and the two others.
  const bool all_two = edges.size() >= 4 && std::all_of(edges.begin(), edges.end(), [](auto& e) {
                         return e.cls.type == EdgeType::t2;
                       });
  if (projected || all_two) {
    for (const IncidentEdge& e : edges) {
      if (!e.cls.interest || !e.cls.targets.empty()) continue;
      std::vector<EntityRef> faces;
      for (const EntityRef& g : e.governors)
        if (g.kind == EntityKind::face) faces.push_back(g);
      for (std::size_t i = 0; i < faces.size(); ++i)
        for (std::size_t j = i + 1; j < faces.size(); ++j)
          if (rel.shared_edge(faces[i], faces[j])) add_rectangle(faces[i], faces[j]);
    }
  }

  // Gaps ([C] edges and others not projected): a face whose point ends a single cut branch
  // leaves the cut open inside its region; close it by a rectangle to a neighbouring
  // governor across a non-projected edge, preferring one that is open as well.
  for (int round = 0; round < 8; ++round) {
    std::optional<EntityRef> open;
    for (const auto& [f, count] : branches)
      if (count == 1 && f.kind == EntityKind::face && is_governor(f)) {
        open = f;
        break;
      }
    if (!open) break;
    std::optional<EntityRef> best;
    int best_score = -1;
    for (const IncidentEdge& e : edges) {
      if (!e.cls.targets.empty()) continue;
      if (std::find(e.governors.begin(), e.governors.end(), *open) == e.governors.end()) continue;
      for (const EntityRef& y : e.governors) {
        if (y == *open || y.kind != EntityKind::face || !rel.shared_edge(*open, y)) continue;
        EntityRef a = *open, b = y;
        if (b < a) std::swap(a, b);
        const auto e2 = rel.shared_edge(a, b);
        if (std::find(out.rectangles.begin(), out.rectangles.end(), Rectangle{a, b, *e2}) !=
            out.rectangles.end())
          continue;
        const int score = branches.count(y) && branches[y] == 1 ? 2 : 1;
        if (score > best_score) best = y, best_score = score;
      }
    }
    if (!best) {
      branches[*open] = -1;  // cannot be closed here; reported by the caller
      continue;
    }
    add_rectangle(*open, *best);
  }
  for (const auto& [f, count] : branches)
    if ((count == 1 || count == -1) && f.kind == EntityKind::face && is_governor(f))
      out.open.push_back(f);
  return out;
}

}  // namespace vorohex::decompose::detail
