#include "decompose/decompose.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

#include "decompose/detail/merge.h"
#include "decompose/detail/topology.h"
#include "occ/shape_io.h"
#include "occ/split_solid.h"

namespace vorohex::decompose {

using core::EdgeId;
using core::FaceId;
using model::EntityKind;
using voronoi::ElementKind;
using voronoi::VoronoiGraph;

const char* sub_volume_type_name(SubVolumeType t) {
  return t == SubVolumeType::vs ? "Vs" : "Ve";
}

const char* scheme_name(Scheme s) {
  switch (s) {
    case Scheme::sweep:
      return "sweep";
    case Scheme::map:
      return "map";
    case Scheme::midpoint:
      return "midpoint";
    case Scheme::multisweep:
      return "multisweep";
    case Scheme::revolve:
      return "revolve";
    case Scheme::none:
      return "none";
  }
  return "?";
}

std::string DecomposeOptions::validate() const {
  if (!(sharp_angle > 0 && sharp_angle <= 180)) return "sharp_angle must be in (0, 180] degrees";
  if (!(tolerance > 0 && tolerance <= 0.01)) return "tolerance must be in (0, 0.01]";
  if (!(plane_snap >= 0 && plane_snap <= 0.05)) return "plane_snap must be in [0, 0.05]";
  if (!(polyline_tolerance >= 0 && polyline_tolerance <= 0.05))
    return "polyline_tolerance must be in [0, 0.05]";
  if (!(max_quads_per_face >= 1)) return "max_quads_per_face must be at least 1";
  if (!(split_time_limit >= 0)) return "split_time_limit must be >= 0 seconds";
  return {};
}

namespace {

constexpr double kPi = 3.14159265358979323846;

Vec3 project(const occ::Solid& solid, EntityRef target, const Vec3& p) {
  if (target.kind == EntityKind::face) return solid.project_to_face(FaceId(target.id), p);
  if (target.kind == EntityKind::edge) return solid.project_to_edge(EdgeId(target.id), p);
  return solid.vertex_point(core::VertexId(target.id));
}

std::vector<std::string> names(const std::vector<EntityRef>& refs) {
  std::vector<std::string> out;
  for (const EntityRef& r : refs) out.push_back(r.name());
  return out;
}

// Steps 1-2: classification with the [1] -> [1s] feedback of the vertex treatment.
void classify_all(const VoronoiGraph& g, const detail::Relations& rel, double sharp,
                  DecompositionResult& r) {
  std::vector<std::pair<EntityRef, EntityRef>> forced;
  const auto edge_ids = g.of_kind(ElementKind::edge);
  const auto vertex_ids = g.of_kind(ElementKind::vertex);
  std::map<int, detail::EdgeClass> cls;
  std::map<int, detail::VertexTreatment> treat;
  for (int round = 0; round < 6; ++round) {
    cls.clear();
    treat.clear();
    for (int e : edge_ids)
      cls[e] = detail::classify_edge(g.elements[e].governors, rel, sharp, forced);
    bool changed = false;
    for (int v : vertex_ids) {
      std::vector<detail::IncidentEdge> inc;
      bool relevant = false;
      for (int e : g.elements[v].incident) {
        if (g.elements[e].kind != ElementKind::edge) continue;
        inc.push_back({g.elements[e].governors, cls[e]});
        relevant = relevant || cls[e].interest;
      }
      if (!relevant) continue;
      detail::VertexTreatment t = detail::treat_vertex(g.elements[v].governors, inc, rel);
      for (const auto& p : t.sharpen)
        if (std::find(forced.begin(), forced.end(), p) == forced.end()) {
          forced.push_back(p);
          changed = true;
        }
      treat[v] = std::move(t);
    }
    if (!changed) break;
  }
  for (int e : edge_ids) {
    const auto& c = cls[e];
    r.edges.push_back({e, c.type, c.interest, c.targets});
    r.stats.edges_of_interest += c.interest;
    r.stats.projected_edges += !c.targets.empty();
  }
  for (auto& [v, t] : treat) {
    r.vertices.push_back({v, t.row, t.rectangles, t.points, t.open});
    if (!t.open.empty())
      r.diagnostics.push_back(
          core::make_warning("open_vertex_gap",
                             "Voronoi vertex " + std::to_string(v) + " (" + t.row +
                                 ") leaves the decomposition open towards some governors",
                             names(t.open)));
  }
  r.stats.vertices_treated = int(r.vertices.size());
}

// Douglas-Peucker: the polyline points needed to stay within `tol` of it. The embedding
// samples a Voronoi edge densely (a straight edge between planes can have dozens of
// points); one quad per sample gave thousands of sliver tools that the OCCT splitter
// intersects pairwise (i01: 4000 quads, > 9 GB).
std::vector<Vec3> simplified(const std::vector<Vec3>& line, double tol) {
  if (line.size() <= 2) return line;
  std::vector<bool> keep(line.size(), false);
  keep.front() = keep.back() = true;
  std::vector<std::pair<std::size_t, std::size_t>> stack{{0, line.size() - 1}};
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    const Vec3 d = line[b] - line[a];
    const double len2 = d.squaredNorm();
    double worst = -1;
    std::size_t at = a;
    for (std::size_t i = a + 1; i < b; ++i) {
      const Vec3 w = line[i] - line[a];
      const double t = len2 > 0 ? std::clamp(w.dot(d) / len2, 0.0, 1.0) : 0.0;
      const double dist = (w - t * d).norm();
      if (dist > worst) worst = dist, at = i;
    }
    if (worst <= tol) continue;
    keep[at] = true;
    stack.push_back({a, at});
    stack.push_back({at, b});
  }
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < line.size(); ++i)
    if (keep[i]) out.push_back(line[i]);
  return out;
}

// Whether an unverified polyline (cell centres) is a chain: no step longer than `jump`.
// A degenerate cluster can give centres in no usable order (i01: 539 points, 48 diagonals
// long), which would make hundreds of crossing quads.
bool chain_like(const std::vector<Vec3>& line, double jump) {
  for (std::size_t i = 0; i + 1 < line.size(); ++i)
    if ((line[i + 1] - line[i]).norm() > jump) return false;
  return true;
}

// A quad between a cut's inner side (points 0, 1) and its target (points 2, 3, on the
// target entity; `anchored` when they are exact, on an edge governor).
DecompositionQuad target_quad(const ClassifiedEdge& ce, const detail::Target& t,
                              std::vector<Vec3> points, bool anchored, const char* kind) {
  DecompositionQuad q;
  q.points = std::move(points);
  q.anchored = {false, false, anchored, anchored};
  q.supports = {EntityRef{EntityKind::face, 0}, EntityRef{EntityKind::face, 0}, t.entity, t.entity};
  q.element = ce.element;
  q.kind = kind;
  q.governors = t.faces;
  q.target = t.entity;
  return q;
}

// Extension towards the boundary (§4.3) where a vertex closes nothing. A cut whose
// polyline ends at an inner point while running along its target (a degenerate edge at a
// T-junction stops short of the end faces; its Voronoi vertices treat nothing) is
// prolonged to the boundary: the polyline's end moves on along its direction to where it
// leaves the solid (`exit`, shared by all the edge's targets so that the prolonged cuts
// meet), and the target side follows: the rectangle end, exit, pi_T(exit), pi_T(end). For
// a straight target edge this is the closing rectangle of the pair (edge, face at its end).
void extend_cut(const occ::Solid& solid, const ClassifiedEdge& ce, const detail::Target& t,
                const Vec3& end, const Vec3& before, const Vec3& projected,
                std::vector<DecompositionQuad>& quads) {
  const double diag = solid.diagonal(), tol = 1e-6 * diag;
  if ((end - before).norm() <= tol || solid.distance_to_boundary(end) <= 1e-3 * diag) return;
  const Vec3 dir = (end - before).normalized();
  const double parallel = std::sin(10 * kPi / 180);
  if (t.entity.kind == EntityKind::face) {
    const FaceId f(t.entity.id);
    if (!solid.face_is_planar(f) || std::abs(dir.dot(solid.face_normal(f, projected))) > parallel)
      return;
  } else if (t.entity.kind == EntityKind::edge) {
    const std::vector<Vec3> pts = solid.edge_points_by_length(EdgeId(t.entity.id), 2);
    const double len = (pts.back() - pts.front()).norm();
    if (len <= tol || (0.5 * (pts.front() + pts.back()) - pts[1]).norm() > 1e-3 * len)
      return;  // straight edges only
    if (std::abs(dir.dot((pts.back() - pts.front()) / len)) < std::cos(10 * kPi / 180)) return;
  } else {
    return;
  }
  // Sphere tracing from the inner end: converges to the first boundary point ahead.
  Vec3 exit = end;
  for (int i = 0; i < 500; ++i) {
    const double d = solid.distance_to_boundary(exit);
    if (d <= 1e-12 * diag) break;
    exit += d * dir;
  }
  if (solid.distance_to_boundary(exit) > 1e-4 * diag || (exit - end).norm() <= 1e-3 * diag) return;
  Vec3 far = project(solid, t.entity, exit);
  if (t.entity.kind == EntityKind::edge)
    for (core::VertexId v : {solid.edge_first_vertex(EdgeId(t.entity.id)),
                             solid.edge_last_vertex(EdgeId(t.entity.id))})
      if ((solid.vertex_point(v) - far).norm() <= 1e-3 * diag) far = solid.vertex_point(v);
  if (t.entity.kind == EntityKind::face &&
      solid.distance_to_face(FaceId(t.entity.id), far) > 1e-4 * diag)
    return;
  quads.push_back(target_quad(ce, t, {end, exit, far, projected}, t.entity.kind == EntityKind::edge,
                              "extension"));
}

// Step 3: the quadrilaterals of the projected edges and of the closing rectangles.
void build_quads(const occ::Solid& solid, const VoronoiGraph& g, double line_tol,
                 const core::Progress& progress, DecompositionResult& r) {
  std::map<int, const TreatedVertex*> treated;
  for (const TreatedVertex& t : r.vertices) treated[t.element] = &t;
  // The vertex's single point for the faces a target stands for.
  auto vertex_target = [&](int v, const detail::Target& t) {
    const auto it = treated.find(v);
    if (it != treated.end())
      for (const auto& [f, entity] : it->second->points)
        if (!t.faces.empty() && f == t.faces[0]) return entity;
    return t.entity;
  };
  // Whether the cut of `edge` onto `entity` is continued at vertex v: by a closing
  // rectangle on the entity or by another projected edge of v onto it.
  std::map<int, const ClassifiedEdge*> classified;
  for (const ClassifiedEdge& ce : r.edges) classified[ce.element] = &ce;
  auto closed_at = [&](int v, int edge, EntityRef entity) {
    const auto it = treated.find(v);
    if (it != treated.end())
      for (const auto& [f, on] : it->second->points)
        if (on == entity)
          for (const detail::Rectangle& rect : it->second->rectangles)
            if (rect.a == f || rect.b == f || rect.edge == entity) return true;
    for (int e : g.elements[v].incident) {
      const auto other = classified.find(e);
      if (e == edge || other == classified.end()) continue;
      for (const detail::Target& t : other->second->targets)
        if (t.entity == entity) return true;
    }
    return false;
  };
  // The projections take most of the decomposition's first quarter (HexMe i09: 15 s of
  // its 16): reported per Voronoi edge.
  for (std::size_t k = 0; k < r.edges.size(); ++k) {
    const ClassifiedEdge& ce = r.edges[k];
    if (ce.targets.empty()) continue;
    if (progress.cancelled()) return;  // (the caller says so)
    progress.report("decompose", 0.25 * double(k) / double(r.edges.size()));
    const auto& el = g.elements[ce.element];
    std::vector<Vec3> line = el.polyline;
    if (line.size() < 2) continue;
    if (!el.verified && !chain_like(line, 0.05 * solid.diagonal())) {
      r.diagnostics.push_back(core::make_warning(
          "unusable_voronoi_edge",
          "Voronoi edge " + std::to_string(ce.element) + " (" + detail::edge_type_name(ce.type) +
              ") is a scatter of cell centres, not a curve; its decomposition faces are left out",
          names(el.governors)));
      continue;
    }
    // Snap the polyline ends to the edge's vertices (the one point per governor face).
    std::array<int, 2> end_vertex{-1, -1};
    for (int v : g.edge_vertices(ce.element)) {
      const Vec3& p = g.elements[v].point;
      const int k = (line.front() - p).norm() <= (line.back() - p).norm() ? 0 : 1;
      end_vertex[k] = v;
      (k == 0 ? line.front() : line.back()) = p;
    }
    // Unverified edges are cell-centre chains, accurate only to the subdivision's cells:
    // simplify them more coarsely (they zig-zag by about a cell).
    line = simplified(line, el.verified ? line_tol : 5 * line_tol);
    for (const detail::Target& t : ce.targets) {
      std::vector<Vec3> proj(line.size());
      for (std::size_t i = 0; i < line.size(); ++i) proj[i] = project(solid, t.entity, line[i]);
      if (end_vertex[0] >= 0)
        proj.front() = project(solid, vertex_target(end_vertex[0], t), line.front());
      if (end_vertex[1] >= 0)
        proj.back() = project(solid, vertex_target(end_vertex[1], t), line.back());
      for (std::size_t i = 0; i + 1 < line.size(); ++i) {
        const bool on_edge = t.entity.kind == EntityKind::edge && t.faces.size() == 1;
        r.quads.push_back(
            target_quad(ce, t, {line[i], line[i + 1], proj[i + 1], proj[i]}, on_edge, "edge"));
      }
      for (int k = 0; k < 2; ++k)
        if (end_vertex[k] < 0 || !closed_at(end_vertex[k], ce.element, t.entity))
          extend_cut(solid, ce, t, k == 0 ? line[0] : line.back(),
                     k == 0 ? line[1] : line[line.size() - 2], k == 0 ? proj.front() : proj.back(),
                     r.quads);
    }
  }
  for (const TreatedVertex& tv : r.vertices) {
    const Vec3& v = g.elements[tv.element].point;
    for (const detail::Rectangle& rect : tv.rectangles) {
      // P_a and P_b: the vertex's projection for each face (an edge governor when the face
      // is replaced by one, see [1e]); the shared edge's projection closes the rectangle.
      auto entity_for = [&](EntityRef f) {
        for (const auto& [face, entity] : tv.points)
          if (face == f) return entity;
        return f;
      };
      const EntityRef ea = entity_for(rect.a), eb = entity_for(rect.b);
      DecompositionQuad q;
      q.points = {v, project(solid, ea, v), project(solid, rect.edge, v), project(solid, eb, v)};
      q.anchored = {false, ea.kind == EntityKind::edge, false, eb.kind == EntityKind::edge};
      q.supports = {EntityRef{EntityKind::face, 0}, ea, rect.edge, eb};
      q.element = tv.element;
      q.kind = "rectangle";
      q.governors = {rect.a, rect.b};
      q.target = rect.edge;
      r.quads.push_back(std::move(q));
    }
  }
  r.stats.quads = int(r.quads.size());
}

// Merging (§4.4): quads whose planes agree within `snap` (model units) and a few degrees
// are moved onto their common plane, so that the split leaves one planar face where the
// embedding's approximate positions would leave several slightly tilted ones.
void snap_coplanar(const occ::Solid& solid, std::vector<DecompositionQuad>& quads, double snap) {
  struct Plane {
    Vec3 n{0, 0, 0};
    double d = 0, area = 0;
    bool ok = false;
  };
  std::vector<Plane> planes(quads.size());
  for (std::size_t i = 0; i < quads.size(); ++i) {
    const auto& p = quads[i].points;
    Vec3 n(0, 0, 0), c(0, 0, 0);
    for (std::size_t k = 0; k < p.size(); ++k) n += p[k].cross(p[(k + 1) % p.size()]), c += p[k];
    c /= double(p.size());
    const double area = 0.5 * n.norm();
    if (area <= snap * snap) continue;
    n.normalize();
    bool flat = true;
    for (const Vec3& q : p) flat = flat && std::abs((q - c).dot(n)) <= snap;
    if (!flat) continue;
    planes[i] = {n, n.dot(c), area, true};
  }
  // The planes of the model's planar faces: a decomposition face that nearly extends one
  // (the usual cut at a concave edge) is put exactly on it.
  std::vector<std::pair<Vec3, double>> model_planes;
  for (const occ::FaceSample& f : occ::sample_faces(solid))
    if (solid.face_is_planar(f.face)) model_planes.emplace_back(f.normal, f.normal.dot(f.point));
  const double cos_max = std::cos(5 * kPi / 180);
  // Quads share corners (a vertex's point, its projections): remember them, so that a
  // corner moved with one quad's plane moves in every quad that has it.
  std::map<std::array<double, 3>, std::vector<std::pair<std::size_t, std::size_t>>> corners;
  for (std::size_t i = 0; i < quads.size(); ++i)
    for (std::size_t k = 0; k < quads[i].points.size(); ++k) {
      const Vec3& p = quads[i].points[k];
      corners[{p.x(), p.y(), p.z()}].emplace_back(i, k);
    }
  // How firmly each point was placed: 0 not moved, 1 onto a fitted plane, 2 onto a plane
  // through exact anchors, 3 onto a model face's plane, 4 kept on its straight edge. A
  // shared corner takes the firmest.
  std::vector<std::vector<int>> firmness(quads.size());
  for (std::size_t i = 0; i < quads.size(); ++i) firmness[i].assign(quads[i].points.size(), 0);
  std::vector<int> cluster(quads.size(), -1);
  for (std::size_t i = 0; i < quads.size(); ++i) {
    if (!planes[i].ok || cluster[i] >= 0) continue;
    std::vector<std::size_t> members{i};
    cluster[i] = int(i);
    Vec3 n = planes[i].n * planes[i].area;
    double d = planes[i].d * planes[i].area, w = planes[i].area;
    for (std::size_t j = i + 1; j < quads.size(); ++j) {
      if (!planes[j].ok || cluster[j] >= 0) continue;
      // Either orientation: the quads of one cut need not agree on a normal.
      const double sign = planes[i].n.dot(planes[j].n) < 0 ? -1.0 : 1.0;
      if (sign * planes[i].n.dot(planes[j].n) < cos_max ||
          std::abs(planes[i].d - sign * planes[j].d) > snap)
        continue;
      cluster[j] = int(i);
      members.push_back(j);
      n += sign * planes[j].n * planes[j].area;
      d += sign * planes[j].d * planes[j].area;
      w += planes[j].area;
    }
    n.normalize();
    d /= w;
    const std::pair<Vec3, double>* extended = nullptr;
    double best = snap;
    for (const auto& mp : model_planes) {
      const double sign = mp.first.dot(n) < 0 ? -1.0 : 1.0;
      if (sign * mp.first.dot(n) < cos_max) continue;
      double worst = 0;
      for (std::size_t m : members)
        for (const Vec3& q : quads[m].points)
          worst = std::max(worst, std::abs(q.dot(mp.first) - mp.second));
      if (worst <= best) best = worst, extended = &mp;
    }
    if (members.size() < 2 && !extended) continue;
    // Points on edge governors (concave edges) are exact: the plane goes through them.
    std::vector<Vec3> anchors;
    for (std::size_t m : members)
      for (std::size_t k = 0; k < quads[m].points.size(); ++k)
        if (k < quads[m].anchored.size() && quads[m].anchored[k])
          anchors.push_back(quads[m].points[k]);
    if (extended) {
      n = extended->first;
      d = extended->second;
    } else if (!anchors.empty()) {
      Vec3 c(0, 0, 0);
      for (const Vec3& a : anchors) c += a;
      c /= double(anchors.size());
      // The anchors' main direction; drop it from the normal if they are spread along it.
      Vec3 far = c;
      for (const Vec3& a : anchors)
        if ((a - c).norm() > (far - c).norm()) far = a;
      if ((far - c).norm() > snap) {
        const Vec3 t = (far - c).normalized();
        n = (n - n.dot(t) * t).normalized();
      }
      d = n.dot(c);
    }
    // Move each point onto the plane without leaving its support: within a planar face,
    // along a straight edge, or freely for inner points.
    for (std::size_t m : members)
      for (std::size_t k = 0; k < quads[m].points.size(); ++k) {
        Vec3& q = quads[m].points[k];
        const double off = q.dot(n) - d;
        Vec3 dir = n;
        const EntityRef sup = k < quads[m].supports.size() ? quads[m].supports[k] : EntityRef{};
        if (sup.id > 0 && sup.kind == EntityKind::face && solid.face_is_planar(FaceId(sup.id))) {
          const Vec3 fn = solid.face_normal(FaceId(sup.id), q);
          dir = n - n.dot(fn) * fn;
        } else if (sup.id > 0 && sup.kind == EntityKind::edge) {
          const auto ends = solid.edge_points_by_length(EdgeId(sup.id), 1);
          dir = (ends.back() - ends.front()).normalized();
        }
        if (std::abs(dir.dot(n)) < 0.2) {
          // A point on a straight edge that (nearly) lies in the plane is exact: moving it
          // across would put it beside the edge, and the split would leave a sliver between
          // (the Figure 6 part lost 3e-9 of its volume). It stays, and wins its corner.
          if (sup.id > 0 && sup.kind == EntityKind::edge) {
            firmness[m][k] = 4;
            continue;
          }
          dir = n;  // a face support nearly parallel to the plane
        }
        q -= off / dir.dot(n) * dir;
        firmness[m][k] = extended ? 3 : anchors.empty() ? 1 : 2;
      }
  }
  for (const auto& entry : corners) {
    const auto& uses = entry.second;
    int firmest = 0;
    Vec3 to(0, 0, 0);
    for (const auto& [i, k] : uses)
      if (firmness[i][k] > firmest) firmest = firmness[i][k], to = quads[i].points[k];
    if (firmest == 0) continue;
    for (const auto& [i, k] : uses) quads[i].points[k] = to;
  }
}

using Clock = std::chrono::steady_clock;

DecompositionResult& finish(DecompositionResult& r, Clock::time_point t0) {
  r.stats.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return r;
}

// The seconds a step may take: its own limit (0: none), or what is left before the
// deadline when that comes first (at least a little: the step then says it ran out).
double within(double own, const core::Progress& progress) {
  const double left = progress.seconds_left();
  if (!std::isfinite(left)) return own;
  const double bounded = std::max(left, 0.1);
  return own > 0 ? std::min(own, bounded) : bounded;
}

// Cancelled by the user, not (only) past the deadline: once the split has given sub-volumes,
// a deadline no longer fails the run (their checks run to the end; the merge pass stops).
bool cancelled_only(const core::Progress& progress) {
  return progress.cancelled() && !progress.timed_out();
}

// Cancelled or past the deadline: fails, naming the step it stopped in.
DecompositionResult& stopped(DecompositionResult& r, const core::Progress& progress,
                             const std::string& during, Clock::time_point t0) {
  r.status = DecompositionStatus::failed;
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.1f", s);
  if (progress.timed_out())
    r.diagnostics.push_back(
        core::make_error("time_limit", "The decomposition stopped at its time limit while " +
                                           during + " (after " + seconds + " s)"));
  else
    r.diagnostics.push_back(
        core::make_error("cancelled", "The decomposition was cancelled while " + during));
  return finish(r, t0);
}

// The Voronoi elements generating the most quads, for the too-many-quads diagnostic.
std::string most_prolific(const std::vector<DecompositionQuad>& quads) {
  std::map<int, int> count;
  for (const auto& q : quads) ++count[q.element];
  std::vector<std::pair<int, int>> by(count.begin(), count.end());
  std::sort(by.begin(), by.end(), [](auto a, auto b) { return a.second > b.second; });
  std::string s;
  for (std::size_t i = 0; i < by.size() && i < 5; ++i)
    s += (i ? ", " : "") + std::to_string(by[i].first) + " (" + std::to_string(by[i].second) + ")";
  return s;
}

}  // namespace

std::vector<ClassifiedEdge> classify_edges(const voronoi::VoronoiResult& voronoi,
                                           const DecomposeOptions& options) {
  DecompositionResult r;
  if (!options.validate().empty() || !voronoi.model || !voronoi.ok()) return {};
  const detail::ModelRelations rel(*voronoi.model);
  classify_all(voronoi.graph, rel, options.sharp_angle * kPi / 180, r);
  return r.edges;
}

double stop_grace(double time_limit) {
  return std::max(2.0, 0.1 * time_limit);
}

core::Diagnostic not_stopped_error(double time_limit) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1)
    << "The decomposition did not stop within its time limit of " << time_limit
    << " s (OCCT's split or fuse did not return in time) and was stopped " << stop_grace(time_limit)
    << " s after it";
  return core::make_error("time_limit", s.str());
}

std::string partial_reason(const DecompositionResult& r) {
  if (r.status != DecompositionStatus::partial) return {};
  // The codes that make a decomposition partial, with what one of them means.
  static const std::vector<std::pair<std::string, std::string>> kinds = {
      {"no_scheme", "sub-volume(s) no scheme accepts"},
      {"invalid_decomposition_face",
       "decomposition face(s) not a quadrilateral between two sub-volumes"},
      {"open_vertex_gap", "Voronoi vertex gap(s) the rules leave open"},
      {"unusable_voronoi_edge", "Voronoi edge(s) that could not be used"},
      {"split_check_failed", "split whose pieces failed the self-check (the solid taken whole)"}};
  std::string out;
  for (const auto& [code, what] : kinds) {
    const auto n = std::count_if(r.diagnostics.begin(), r.diagnostics.end(),
                                 [&](const core::Diagnostic& d) { return d.code == code; });
    if (n > 0)
      out += (out.empty() ? "" : "; ") + std::to_string(n) + " " + what + " (" + code + ")";
  }
  return out.empty() ? "see the warnings" : out;
}

DecompositionResult decompose(const occ::Solid& solid, const voronoi::VoronoiResult& voronoi,
                              const DecomposeOptions& options, const core::Progress& progress) {
  const auto t0 = Clock::now();
  DecompositionResult r;
  progress.report("decompose", 0.0);
  if (const std::string why = options.validate(); !why.empty()) {
    r.diagnostics.push_back(core::make_error("invalid_options", why));
    return r;
  }
  if (!voronoi.model || !voronoi.ok()) {
    r.diagnostics.push_back(core::make_error("no_voronoi_graph", "No Voronoi graph to decompose"));
    return r;
  }
  const VoronoiGraph& g = voronoi.graph;
  const double tol = options.tolerance * solid.diagonal();
  const detail::ModelRelations rel(*voronoi.model);
  classify_all(g, rel, options.sharp_angle * kPi / 180, r);
  if (options.stop_at_open_gap)
    for (const core::Diagnostic& d : r.diagnostics)
      if (d.code == "open_vertex_gap") {
        r.diagnostics.push_back(
            core::make_error("open_gap_stop",
                             d.message + ": stopped before the split (its sub-volumes there "
                                         "cannot all be closed)",
                             d.entities));
        return finish(r, t0);
      }
  build_quads(solid, g, options.polyline_tolerance * solid.diagonal(), progress, r);
  if (progress.cancelled()) return stopped(r, progress, "projecting the Voronoi edges", t0);
  snap_coplanar(solid, r.quads, options.plane_snap * solid.diagonal());
  progress.report("decompose", 0.25);

  const int max_quads = options.max_quads_per_face * std::max(solid.num_faces(), 1);
  if (r.stats.quads > max_quads) {
    r.diagnostics.push_back(core::make_error(
        "too_many_decomposition_faces",
        std::to_string(r.stats.quads) + " decomposition quads for " +
            std::to_string(solid.num_faces()) + " model faces (limit " + std::to_string(max_quads) +
            "); the most prolific Voronoi elements: " + most_prolific(r.quads)));
    return finish(r, t0);
  }

  std::vector<std::vector<Vec3>> tools;
  for (const auto& q : r.quads) tools.push_back(q.points);
  occ::SplitResult split = occ::split_solid(solid, tools, std::max(tol, 1e-7),
                                            within(options.split_time_limit, progress));
  for (auto& d : split.diagnostics) r.diagnostics.push_back(d);
  if (!split.ok && progress.cancelled())
    return stopped(r, progress, "OCCT split the solid by its decomposition faces", t0);
  if (!split.ok) return finish(r, t0);
  progress.report("decompose", 0.5);
  if (split.dropped_internal_faces > 0)
    r.diagnostics.push_back(
        core::make_info("dangling_decomposition_faces",
                        std::to_string(split.dropped_internal_faces) +
                            " pieces of decomposition faces separated nothing and were dropped"));
  // One piece is the solid itself: taken exactly, without the edges the decomposition
  // faces that separated nothing imprinted on its faces (HexMe s11's cube with a cylinder:
  // no multisweep with them, one without).
  if (split.pieces.size() == 1) split.pieces[0] = solid.clone();
  for (occ::Solid& piece : split.pieces) {
    SubVolume sv;
    sv.volume = piece.volume();
    sv.solid = std::make_shared<const occ::Solid>(std::move(piece));
    r.sub_volumes.push_back(std::move(sv));
  }
  detail::build_topology(solid, tol, r);
  for (std::size_t i = 0; i < r.sub_volumes.size(); ++i)
    detail::type_sub_volume(g, r, int(i), options, r.sub_volumes[i]);
  r.stats.sub_volumes_before_merge = int(r.sub_volumes.size());
  if (cancelled_only(progress)) return stopped(r, progress, "typing the sub-volumes", t0);
  // Pieces that are not closed or lose volume cannot be repaired by merging: report now,
  // unless the merge pass's first candidate, all pieces together, is kept - it is the
  // solid itself, taken exactly, whatever the pieces lost.
  r.status = DecompositionStatus::ok;
  detail::self_check(solid, tol, false, options.sharp_angle, r);
  if (r.status == DecompositionStatus::failed &&
      !(options.merge && detail::take_whole_solid(solid, g, tol, options, r))) {
    r.stats.sub_volumes = int(r.sub_volumes.size());
    return finish(r, t0);
  }
  r.diagnostics.erase(std::remove_if(r.diagnostics.begin(), r.diagnostics.end(),
                                     [](const core::Diagnostic& d) {
                                       return d.code == "invalid_decomposition_face";
                                     }),
                      r.diagnostics.end());

  if (cancelled_only(progress)) return stopped(r, progress, "checking the sub-volumes", t0);
  if (options.merge)
    detail::merge_pass(solid, g, tol, within(options.split_time_limit, progress), options, progress,
                       r);
  // A deadline ends the merge pass with what it has (merge_stopped); a cancel ends the run.
  if (cancelled_only(progress)) return stopped(r, progress, "merging sub-volumes", t0);
  progress.report("decompose", 0.75);
  // Judged glued only when it is a candidate for meshing: every piece has a scheme alone.
  if (std::none_of(r.sub_volumes.begin(), r.sub_volumes.end(),
                   [](const SubVolume& sv) { return sv.scheme == Scheme::none; }))
    detail::judge_glued(r, options.multisweep);
  detail::build_virtual_edges(solid, tol, r);

  r.stats.sub_volumes = int(r.sub_volumes.size());
  bool complete = true;
  for (std::size_t i = 0; i < r.sub_volumes.size(); ++i) {
    const SubVolume& sv = r.sub_volumes[i];
    if (sv.scheme != Scheme::none) continue;
    complete = false;
    r.diagnostics.push_back(core::make_warning(
        "no_scheme", "Sub-volume " + std::to_string(i) + " (" + sub_volume_type_name(sv.type) +
                         ") has no meshing scheme: " + sv.reason));
  }
  for (const auto& d : r.diagnostics)
    if (d.code == "open_vertex_gap" || d.code == "unusable_voronoi_edge" ||
        d.code == "split_check_failed")
      complete = false;
  r.status = complete ? DecompositionStatus::ok : DecompositionStatus::partial;
  detail::self_check(solid, tol, true, options.sharp_angle, r);
  progress.report("decompose", 1.0);
  return finish(r, t0);
}

}  // namespace vorohex::decompose
