#include "grid/detail/features.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <set>
#include <unordered_map>
#include <unordered_set>

namespace vorohex::grid::detail {
namespace {

using core::NodeClass;
using core::NodeId;
using core::Vec3;

struct Surface {
  std::vector<std::int32_t> nodes;                                       // outer nodes
  std::unordered_map<std::int32_t, std::vector<std::int32_t>> adjacent;  // along quad edges
};

std::int64_t edge_key(std::int32_t a, std::int32_t b) {
  if (a > b) std::swap(a, b);
  return (std::int64_t(a) << 32) | std::uint32_t(b);
}

// Shortest path from `from` to `to` over the outer surface; nodes in `blocked` (other than
// `to`) are not entered. Cost: length plus twice the distance of the entered node from the
// curve, so the path hugs it. Empty when there is none.
std::vector<std::int32_t> shortest_path(const core::HexMesh& mesh, const Surface& s,
                                        std::int32_t from, std::int32_t to,
                                        const std::unordered_set<std::int32_t>& blocked,
                                        const std::function<double(std::int32_t)>& off_curve) {
  if (from == to) return {from};
  std::unordered_map<std::int32_t, double> dist;
  std::unordered_map<std::int32_t, std::int32_t> prev;
  using Item = std::pair<double, std::int32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  dist[from] = 0;
  queue.push({0, from});
  std::size_t settled = 0;
  while (!queue.empty()) {
    const auto [d, u] = queue.top();
    queue.pop();
    if (d > dist[u]) continue;
    if (u == to) break;
    if (++settled > 20000) return {};
    auto it = s.adjacent.find(u);
    if (it == s.adjacent.end()) continue;
    for (std::int32_t v : it->second) {
      if (v != to && blocked.count(v)) continue;
      const double off = off_curve(v);
      if (!std::isfinite(off)) continue;
      const double w = (mesh.point(NodeId(u)) - mesh.point(NodeId(v))).norm() + 2 * off;
      auto [dv, fresh] = dist.try_emplace(v, std::numeric_limits<double>::infinity());
      if (d + w < dv->second) {
        dv->second = d + w;
        prev[v] = u;
        queue.push({d + w, v});
      }
    }
  }
  if (!prev.count(to)) return {};
  std::vector<std::int32_t> path{to};
  while (path.back() != from) path.push_back(prev[path.back()]);
  std::reverse(path.begin(), path.end());
  return path;
}

// Surface Laplacian over the outer quads: each node that may move goes to the mean of its
// neighbours on the outer surface, then back onto its entity (a face node onto its face, or
// onto the nearest face when `nearest`, onto the nearest face of its composite when it is
// in one; an edge node onto its curve, moving only along neighbours on the same curve or its
// vertices). Vertex nodes stay.
void relax(core::HexMesh& mesh, const Surface& s, const core::MeshDomain& solid, int iterations,
           const std::function<bool(std::int32_t)>& movable, bool nearest,
           const SmallFeatures& small) {
  for (int it = 0; it < iterations; ++it)
    for (std::int32_t n : s.nodes) {
      const NodeClass c = mesh.node_class(NodeId(n));
      if (c.dim == 0 || c.dim == 3 || !movable(n)) continue;
      Vec3 sum = Vec3::Zero();
      int k = 0;
      for (std::int32_t m : s.adjacent.at(n)) {
        const NodeClass cm = mesh.node_class(NodeId(m));
        if (c.dim == 1 && !(cm.dim == 0 || (cm.dim == 1 && cm.id == c.id))) continue;
        sum += mesh.point(NodeId(m)), ++k;
      }
      if (k < 2) continue;
      const Vec3 target = sum / k;
      if (c.dim == 1) {
        mesh.set_point(NodeId(n), solid.project_to_edge(core::EdgeId(c.id), target));
      } else {
        core::FaceId f = nearest ? solid.nearest_face(target) : core::FaceId(c.id);
        if (f.value() <= 0) continue;
        mesh.set_point(NodeId(n), small.project(solid, f, target, f));
        mesh.set_node_class(NodeId(n), NodeClass::on(f));
      }
    }
}

}  // namespace

std::size_t uncross(const std::vector<Vec3>& targets, std::vector<Vec3>& positions,
                    std::vector<std::int32_t>& nodes, double reach) {
  std::size_t swaps = 0;
  const double eps = 1e-12 * reach * reach;
  bool swapped = true;
  for (int round = 0; swapped && round < 10; ++round) {
    swapped = false;
    for (std::size_t i = 0; i < targets.size(); ++i)
      for (std::size_t j = i + 1; j < targets.size(); ++j) {
        if ((targets[i] - targets[j]).norm() > reach) continue;
        const double kept =
            (positions[i] - targets[i]).squaredNorm() + (positions[j] - targets[j]).squaredNorm();
        const double crossed =
            (positions[j] - targets[i]).squaredNorm() + (positions[i] - targets[j]).squaredNorm();
        if (crossed < kept - eps) {
          std::swap(positions[i], positions[j]);
          std::swap(nodes[i], nodes[j]);
          swapped = true;
          ++swaps;
        }
      }
  }
  return swaps;
}

// How far from a model edge, in cells, the outer nodes of its chain may lie. Along a
// curve the grid does not follow, the core's staircase keeps its outer nodes up to about
// the margin plus a cell's diagonal (0.5 + 1.41 cells) from the curve: with 1.5 the band of
// nodes around a tube's end circle fell apart where the staircase turns (at 45 degrees to
// the grid) and the circle got no chain (a tube with a cross hole: its two end circles and
// the hole's three rims uncaptured, 1.1 % of the volume cut off).
constexpr double kChainBand = 2.5;
// How far from the points at a third and two thirds of a closed curve its chain's
// waypoints may lie, in cells (within the band).
constexpr double kTargetReach = 1.5;
// A face's interior angle at a vertex above kReflex is split into quads of at most
// kQuadAngle (see quads_needed below). Flat angles count: an edge running on straight
// through a vertex (HexMe i13's Vertex55, s10's Vertex2, where a third edge meets it) on a
// core corner's node left the face one quad there with both chains along two of its sides,
// flat (i13 0.023 -> 0.455, s10 0.236 -> 0.441 with two).
constexpr double kReflex = 170 * M_PI / 180;
// At most kQuadAngle: a face's 267 degrees at a vertex of HexMe i19 (at a third of its size)
// in three quads rather than two leaves its finer grid valid (two inverted hexahedra
// before); n06's pit rim, 252 degrees of the top face, keeps two (in three its minimum fell
// from 0.40 to 0.14). 120 and 160 degrees were measured: each loses one of them.
constexpr double kQuadAngle = 130 * M_PI / 180;
// A candidate vertex node's cost per quad it lacks for such an angle, in cells (half a
// lacking chain's: with a whole cell HexMe n06's pit rim vertices, 252 degrees of the top
// face, moved to nodes farther away and its minimum fell from 0.40 to 0.15).
constexpr double kBentWeight = 0.5;

// With share_cusps: how close (in cells) another edge's chain node must be to this edge's
// curve, at a cusp, for the chains to share it.
constexpr double kCuspShare = 0.3;

int quads_for_angle(double alpha) {
  return alpha > kReflex ? int(std::ceil(alpha / kQuadAngle)) : 1;
}

int region_face(const std::map<int, int>& votes, const std::set<int>& around,
                const std::function<bool(int, int)>& borders) {
  if (votes.empty()) return -1;
  auto borders_all = [&](int f) {
    for (int x : around)
      if (!borders(f, x)) return false;
    return true;
  };
  const int winner = std::max_element(votes.begin(), votes.end(), [](auto& x, auto& y) {
                       return x.second < y.second;
                     })->first;
  if (borders_all(winner)) return winner;
  int best = winner, best_votes = 0;
  for (const auto& [f, n] : votes)
    if (n > best_votes && borders_all(f)) best = f, best_votes = n;
  return best;
}

FeatureCapture capture_features(core::HexMesh& mesh,
                                const std::vector<std::array<std::int32_t, 4>>& outer_quads,
                                const std::vector<std::int32_t>& outer_nodes,
                                const std::vector<core::Vec3>& normals,
                                const core::MeshDomain& solid, const SmallFeatures& small,
                                double size, bool tangent_edges_last, bool share_cusps) {
  FeatureCapture r;
  std::unordered_map<std::int32_t, Vec3> normal_of;
  for (std::size_t i = 0; i < outer_nodes.size() && i < normals.size(); ++i)
    normal_of[outer_nodes[i]] = normals[i];
  auto normal = [&](std::int32_t n) {
    auto it = normal_of.find(n);
    return it == normal_of.end() ? Vec3(Vec3::Zero()) : it->second;
  };
  // Mismatch between a node's direction and a feature's mean outward normal m, in length.
  auto mismatch = [&](std::int32_t n, const Vec3& m) { return size * (1 - normal(n).dot(m)); };
  Surface s;
  {
    std::unordered_set<std::int64_t> seen;
    for (const auto& q : outer_quads)
      for (int c = 0; c < 4; ++c) {
        const std::int32_t a = q[c], b = q[(c + 1) % 4];
        s.nodes.push_back(a);
        if (seen.insert(edge_key(a, b)).second) {
          s.adjacent[a].push_back(b);
          s.adjacent[b].push_back(a);
        }
      }
    std::sort(s.nodes.begin(), s.nodes.end());
    s.nodes.erase(std::unique(s.nodes.begin(), s.nodes.end()), s.nodes.end());
  }
  // 0. Outer nodes that closest points put (nearly) on top of a neighbour - the core's
  // nodes in the shadow of a concave edge all project onto that edge - are spread out.
  {
    double mean = 0;
    std::size_t count = 0;
    for (std::int32_t n : s.nodes)
      for (std::int32_t m : s.adjacent.at(n))
        mean += (mesh.point(NodeId(n)) - mesh.point(NodeId(m))).norm(), ++count;
    mean = count ? mean / double(count) : size;
    std::unordered_set<std::int32_t> crowded;
    for (std::int32_t n : s.nodes)
      for (std::int32_t m : s.adjacent.at(n))
        if ((mesh.point(NodeId(n)) - mesh.point(NodeId(m))).norm() < 0.3 * mean) {
          crowded.insert(n);
          for (std::int32_t k : s.adjacent.at(n)) crowded.insert(k);
        }
    relax(
        mesh, s, solid, 10, [&](std::int32_t n) { return crowded.count(n) > 0; }, true, small);
  }

  std::unordered_set<std::int32_t> on_feature;

  // Features smaller than a quarter of the size (the pipeline's tiny_edges and
  // sliver_faces: engravings, small chamfers, with the faces they enclose) are absorbed, not
  // resolved (grid/composites.h): their edges get no chain, their vertices no node, and the
  // nodes near them go to the nearest face of the composite they form with a resolved face.
  const std::vector<char>& absorbed_edge = small.absorbed_edge;
  // Per vertex: its feature edges (not seams, not degenerated) and those not absorbed. A
  // vertex with none (a sphere's poles, the end of a cylinder's seam) is no feature.
  std::vector<int> live_edges(solid.num_vertices() + 1, 0), all_edges(solid.num_vertices() + 1, 0);
  for (core::EdgeId e : solid.edges()) {
    if (solid.edge_is_degenerated(e)) continue;
    const std::vector<core::FaceId> ef = solid.edge_faces(e);
    if (ef.size() < 2 || ef[0] == ef[1]) continue;
    for (core::VertexId v : {solid.edge_first_vertex(e), solid.edge_last_vertex(e)}) {
      ++all_edges[v.value()];
      if (!absorbed_edge[e.value()]) ++live_edges[v.value()];
    }
  }

  // 1. Vertices.
  std::vector<std::vector<core::FaceId>> faces_of_vertex(solid.num_vertices() + 1);
  for (core::EdgeId e : solid.edges())
    for (core::VertexId v : {solid.edge_first_vertex(e), solid.edge_last_vertex(e)})
      for (core::FaceId f : solid.edge_faces(e))
        if (std::find(faces_of_vertex[v.value()].begin(), faces_of_vertex[v.value()].end(), f) ==
            faces_of_vertex[v.value()].end())
          faces_of_vertex[v.value()].push_back(f);
  // Per vertex: the outer quads it needs around its node: one per face, and where a face's
  // interior angle there is flat or reflex (over kReflex), enough to split that angle into quads of
  // at most kQuadAngle. A node with fewer bends a quad inside out at the vertex (HexMe i17
  // at a third of its size: a wall meeting a floor at a vertex where the floor's angle is
  // 191 degrees, on a core corner's node with three quads, the floor's one inverted; valid,
  // min 0.42, on a node with four); a flat angle likewise (kReflex). An angle next to an
  // absorbed edge does not count: the composite has no corner there (HexMe i20's Edge41,
  // 0.6 long, straight on from Edge42: asking two quads there drew Vertex31 and Vertex32 to
  // nodes on the wrong faces, min 0.216 -> 0.144).
  std::vector<int> quads_needed(solid.num_vertices() + 1, 0);
  {
    std::unordered_map<int, std::vector<Vec3>> samples;
    auto points = [&](core::EdgeId e) -> const std::vector<Vec3>& {
      auto [it, fresh] = samples.try_emplace(e.value());
      if (fresh) it->second = solid.edge_points_by_length(e, 16);
      return it->second;
    };
    for (core::FaceId f : solid.faces())
      for (const std::vector<core::OrientedEdge>& wire : solid.face_wires(f))
        for (std::size_t k = 0; k < wire.size(); ++k) {
          const core::OrientedEdge& in = wire[(k + wire.size() - 1) % wire.size()];
          const core::OrientedEdge& out = wire[k];
          const core::VertexId v =
              out.forward ? solid.edge_first_vertex(out.edge) : solid.edge_last_vertex(out.edge);
          int quads = 1;
          if (!solid.edge_is_degenerated(in.edge) && !solid.edge_is_degenerated(out.edge) &&
              !absorbed_edge[in.edge.value()] && !absorbed_edge[out.edge.value()]) {
            const std::vector<Vec3>& a = points(in.edge);
            const std::vector<Vec3>& b = points(out.edge);
            const std::size_t na = a.size(), nb = b.size();
            if (na >= 2 && nb >= 2) {
              const Vec3 t_in = in.forward ? Vec3(a[na - 1] - a[na - 2]) : Vec3(a[0] - a[1]);
              const Vec3 t_out = out.forward ? Vec3(b[1] - b[0]) : Vec3(b[nb - 2] - b[nb - 1]);
              const Vec3 normal = solid.face_normal(f, solid.vertex_point(v));
              const double turn = std::atan2(t_in.cross(t_out).dot(normal), t_in.dot(t_out));
              quads = quads_for_angle(M_PI - turn);  // the face's interior angle at v
            }
          }
          quads_needed[v.value()] += quads;
        }
  }
  std::vector<std::int32_t> vertex_node(solid.num_vertices() + 1, -1);
  std::vector<core::VertexId> taken;  // captured, in the order they chose
  for (core::VertexId v : solid.vertices()) {
    if (all_edges[v.value()] == 0) continue;
    ++r.vertices;
    if (live_edges[v.value()] == 0) {
      r.absorbed.push_back(core::entity_name(v));
      continue;
    }
    const Vec3 p = solid.vertex_point(v);
    Vec3 m = Vec3::Zero();
    for (core::FaceId f : faces_of_vertex[v.value()]) m += solid.face_normal(f, p);
    m.normalize();
    std::int32_t n = -1;
    double best = std::numeric_limits<double>::infinity();
    for (std::int32_t c : s.nodes) {
      if (on_feature.count(c)) continue;
      const double d = (mesh.point(NodeId(c)) - p).norm();
      if (d >= best) continue;
      // A node with fewer outer edges than the vertex has feature edges leaves a chain no
      // way out (HexMe n09: a pyramid's apex on a core corner, three edges for four chains);
      // one with fewer quads than the vertex's angles need bends one (above).
      const int valence = int(s.adjacent.at(c).size());
      const int lacking = std::max(0, live_edges[v.value()] - valence);
      const int bent =
          std::max(0, quads_needed[v.value()] - std::max(valence, live_edges[v.value()]));
      const double score =
          d + (m.allFinite() ? 2 * mismatch(c, m) : 0.0) + (lacking + kBentWeight * bent) * size;
      if (score < best) best = score, n = c;
    }
    if (n < 0) {
      r.missed.push_back(core::entity_name(v));
      continue;
    }
    vertex_node[v.value()] = n;
    on_feature.insert(n);
    taken.push_back(v);
    ++r.vertices_captured;
  }
  {
    std::vector<Vec3> targets, positions;
    std::vector<std::int32_t> nodes;
    for (core::VertexId v : taken) {
      targets.push_back(solid.vertex_point(v));
      nodes.push_back(vertex_node[v.value()]);
      positions.push_back(mesh.point(NodeId(nodes.back())));
    }
    uncross(targets, positions, nodes, 4 * size);
    for (std::size_t i = 0; i < taken.size(); ++i) vertex_node[taken[i].value()] = nodes[i];
  }
  for (core::VertexId v : taken) {
    const std::int32_t n = vertex_node[v.value()];
    mesh.set_point(NodeId(n), solid.vertex_point(v));
    mesh.set_node_class(NodeId(n), NodeClass::on(v));
  }

  // 2. Edges: chains through the nodes nearest to points along the curve.
  // The mesh edges the regions of faces stop at (chains, and the sides of quads a chain cuts
  // diagonally), each with the model edge it belongs to.
  std::unordered_map<std::int64_t, int> feature_edges;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> quads_of_edge;
  for (std::size_t q = 0; q < outer_quads.size(); ++q)
    for (int c = 0; c < 4; ++c)
      quads_of_edge[edge_key(outer_quads[q][c], outer_quads[q][(c + 1) % 4])].push_back(q);
  // Quads a chain cuts diagonally (see below): the model edge whose chain cut it, or -1. In
  // no face region, their edges barriers.
  std::vector<int> cut_by(outer_quads.size(), -1);
  std::vector<std::int32_t> turn_of(outer_quads.size(), -1);  // its node left out of the chain
  // Two edges leaving a common vertex in nearly the same direction (within 20 degrees:
  // tangent, as a circle leaving a straight edge's end along it). Elsewhere (the edges of a
  // pyramid's apex) sharing chains distorts the hexahedra more than cutting across does:
  // HexMe n06's minimum fell from 0.40 to 0.14 when its apex edges shared.
  std::map<std::pair<int, int>, bool> tangent_pairs;
  auto tangent_at_common_vertex = [&](core::EdgeId x, core::EdgeId y) {
    const int lo = std::min(x.value(), y.value()), hi = std::max(x.value(), y.value());
    auto [it, fresh] = tangent_pairs.try_emplace({lo, hi}, false);
    if (!fresh) return it->second;
    auto direction = [&](core::EdgeId d, core::VertexId v) {
      const std::vector<Vec3> p = solid.edge_points_by_length(d, 32);
      const Vec3 at = solid.vertex_point(v);  // the samples may run either way
      const bool first = (p.front() - at).norm() < (p.back() - at).norm();
      return Vec3(first ? p[1] - p[0] : p[p.size() - 2] - p.back()).normalized();
    };
    for (core::VertexId v : {solid.edge_first_vertex(x), solid.edge_last_vertex(x)})
      if (v == solid.edge_first_vertex(y) || v == solid.edge_last_vertex(y))
        it->second = it->second || direction(x, v).dot(direction(y, v)) > std::cos(20 * M_PI / 180);
    return it->second;
  };
  // Cusps: two edges of one face leaving a common vertex tangentially (the face's angle
  // there is zero; a circle tangent to a line: HexMe i03's Face10 at Vertex71). Per edge
  // (by id value), the edges it forms one with.
  std::vector<std::set<int>> cusp_partners(solid.num_edges() + 1);
  {
    std::vector<std::vector<core::EdgeId>> edges_at(solid.num_vertices() + 1);
    for (core::EdgeId e : solid.edges())
      if (const std::vector<core::FaceId> f = solid.edge_faces(e); !solid.edge_is_degenerated(e) &&
                                                                   !absorbed_edge[e.value()] &&
                                                                   f.size() == 2 && f[0] != f[1])
        for (core::VertexId v : {solid.edge_first_vertex(e), solid.edge_last_vertex(e)})
          edges_at[v.value()].push_back(e);
    for (core::VertexId v : solid.vertices()) {
      const std::vector<core::EdgeId>& at = edges_at[v.value()];
      bool found = false;
      for (std::size_t i = 0; i < at.size(); ++i)
        for (std::size_t j = i + 1; j < at.size(); ++j) {
          const std::vector<core::FaceId> fi = solid.edge_faces(at[i]);
          const std::vector<core::FaceId> fj = solid.edge_faces(at[j]);
          if (std::find_first_of(fi.begin(), fi.end(), fj.begin(), fj.end()) == fi.end() ||
              !tangent_at_common_vertex(at[i], at[j]))
            continue;
          cusp_partners[at[i].value()].insert(at[j].value());
          cusp_partners[at[j].value()].insert(at[i].value());
          found = true;
        }
      if (found) r.cusps.push_back(v);
    }
  }
  std::unordered_set<std::int32_t> reserved;       // turn nodes taken out of a chain
  std::set<std::pair<int, int>> captured_between;  // face pairs with a captured edge
  // With tangent_edges_last, the edges along which the faces are tangent (a sphere on a
  // cylinder of its radius, a fillet's rims) take their chains after the others: such a
  // chain only tells two faces apart, and near a vertex it shares with a sharp edge its
  // nodes can leave the sharp edge no path (HexMe s10: a dome on a cylinder, cut by two
  // planes; the arcs where the planes meet the dome found the equator's chain in their way).
  std::vector<core::EdgeId> order = solid.edges();
  if (tangent_edges_last)
    std::stable_partition(order.begin(), order.end(), [&](core::EdgeId e) {
      const std::vector<core::FaceId> faces = solid.edge_faces(e);
      if (solid.edge_is_degenerated(e) || faces.size() < 2 || faces[0] == faces[1]) return true;
      const std::vector<Vec3> p = solid.edge_points_by_length(e, 4);
      for (int k = 1; k <= 3; ++k)
        if (solid.face_normal(faces[0], p[k]).dot(solid.face_normal(faces[1], p[k])) <=
            std::cos(M_PI / 18))
          return true;  // sharp somewhere: first
      return false;
    });
  for (core::EdgeId e : order) {
    if (solid.edge_is_degenerated(e)) continue;
    const std::vector<core::FaceId> faces = solid.edge_faces(e);
    if (faces.size() < 2 || faces[0] == faces[1]) continue;  // a seam: no feature
    ++r.edges;
    if (absorbed_edge[e.value()]) {
      r.absorbed.push_back(core::entity_name(e));
      continue;
    }
    const std::int32_t a = vertex_node[solid.edge_first_vertex(e).value()];
    const std::int32_t b = vertex_node[solid.edge_last_vertex(e).value()];
    if (a < 0 || b < 0) {
      r.missed.push_back(core::entity_name(e));
      continue;
    }
    const double length = solid.edge_length(e);
    // Off the curve: the outer node's distance, plus the mismatch of its direction with the
    // edge's (where outer nodes tie - several on a concave edge - the chain follows the
    // core's edge instead of zigzagging, which would leave quads with three nodes on it).
    std::unordered_map<std::int32_t, double> off;
    auto off_curve = [&](std::int32_t n) {
      auto [it, fresh] = off.try_emplace(n, 0.0);
      if (fresh) {
        const Vec3 p = mesh.point(NodeId(n));
        const Vec3 q = solid.project_to_edge(e, p);
        Vec3 m = Vec3::Zero();
        for (core::FaceId f : faces) m += solid.face_normal(f, q);
        // Nodes farther than kChainBand cells from the curve are not entered: a path that
        // needs them is no chain along the edge (and the search stays local).
        const double d = (q - p).norm();
        it->second = d > kChainBand * size ? std::numeric_limits<double>::infinity()
                                           : d + mismatch(n, m.normalized());
      }
      return it->second;
    };
    // A closed curve (one vertex) passes through the nodes best placed at a third and two
    // thirds of its length; an open one is one shortest path between its vertices.
    std::vector<std::int32_t> targets;
    if (a == b) {
      const std::vector<Vec3> thirds = solid.edge_points_by_length(e, 3);
      for (int i = 1; i <= 2; ++i) {
        double best = std::numeric_limits<double>::infinity();
        std::int32_t t = -1;
        for (std::int32_t n : s.nodes) {
          if (on_feature.count(n)) continue;
          const double d = (mesh.point(NodeId(n)) - thirds[i]).norm();
          if (d > kTargetReach * size || d >= best) continue;
          const double score = d + off_curve(n);
          if (score < best) best = score, t = n;
        }
        if (t >= 0) targets.push_back(t);
      }
      if (targets.size() < 2 || targets[0] == targets[1]) targets.clear();
    }
    targets.push_back(b);
    std::vector<std::int32_t> chain{a};
    std::unordered_set<std::int32_t> blocked = on_feature;
    blocked.insert(reserved.begin(), reserved.end());
    for (std::int32_t t : targets) blocked.insert(t);
    bool ok = length > 0;
    // Where no path avoids other chains, this one may use, within a cell of its curve, the
    // chain nodes of edges tangent to it at a common vertex (shared: they stay on their
    // edge) and the turn nodes other chains left (taken: they go onto this edge). HexMe
    // i20's quarter circles leave their vertices tangent to straight edges, and for the
    // first cells both chains need the nodes along the line.
    auto usable = [&](std::int32_t n) {
      const NodeClass c = mesh.node_class(NodeId(n));
      const bool other_chain = on_feature.count(n) && c.dim == 1 && c.id != e.value() &&
                               tangent_at_common_vertex(e, core::EdgeId(c.id));
      if (!other_chain && !reserved.count(n)) return false;
      const Vec3 p = mesh.point(NodeId(n));
      return (solid.project_to_edge(e, p) - p).norm() < size;
    };
    std::unordered_set<std::int32_t> shared;
    // With share_cusps, the chain nodes of an edge this one forms a cusp with, within
    // kCuspShare cells of this curve, are open to it first (shared: the tip of the face
    // between them, narrower than that, gets no quads).
    std::unordered_set<std::int32_t> at_cusp;
    if (share_cusps && !cusp_partners[e.value()].empty())
      for (std::int32_t n : blocked) {
        const NodeClass c = mesh.node_class(NodeId(n));
        if (!on_feature.count(n) || c.dim != 1 || !cusp_partners[e.value()].count(c.id)) continue;
        const Vec3 p = mesh.point(NodeId(n));
        if ((solid.project_to_edge(e, p) - p).norm() < kCuspShare * size) at_cusp.insert(n);
      }
    // `blocked` without those (kept alongside it; a target among them stays blocked).
    std::unordered_set<std::int32_t> open;
    if (!at_cusp.empty())
      for (std::int32_t n : blocked)
        if (!at_cusp.count(n)) open.insert(n);
    for (std::int32_t target : targets) {
      if (!ok) break;
      std::vector<std::int32_t> piece;
      if (!at_cusp.empty()) {
        const bool blocked_too = at_cusp.count(target) && open.insert(target).second;
        piece = shortest_path(mesh, s, chain.back(), target, open, off_curve);
        if (blocked_too) open.erase(target);
        for (std::size_t k = 1; k + 1 < piece.size(); ++k)
          if (at_cusp.count(piece[k])) shared.insert(piece[k]);
      }
      if (piece.size() < 2)
        piece = shortest_path(mesh, s, chain.back(), target, blocked, off_curve);
      if (piece.size() < 2) {
        std::unordered_set<std::int32_t> relaxed;
        for (std::int32_t n : blocked)
          if (n == target || !usable(n)) relaxed.insert(n);
        piece = shortest_path(mesh, s, chain.back(), target, relaxed, off_curve);
        for (std::size_t k = 1; k + 1 < piece.size(); ++k)
          if (on_feature.count(piece[k])) shared.insert(piece[k]);
      }
      if (piece.size() < 2) {
        ok = false;
        break;
      }
      for (std::size_t k = 1; k < piece.size(); ++k) {
        chain.push_back(piece[k]);
        blocked.insert(piece[k]);
        if (!at_cusp.empty() && !at_cusp.count(piece[k])) open.insert(piece[k]);
      }
    }
    if (!ok || chain.size() < 2 || chain.back() != b) {
      r.missed.push_back(core::entity_name(e));
      continue;
    }
    if (!shared.empty()) r.joined.push_back(core::entity_name(e));
    // A chain that turns at a node has that node and its two chain neighbours in one quad,
    // which would end flat on the curve (an angle of 180 degrees: a hex of scaled Jacobian
    // about 0). The turn node leaves the chain instead, which then cuts that quad along its
    // diagonal: a staircase becomes a diagonal line of quads across the curve.
    {
      auto quad_with = [&](std::int32_t x, std::int32_t y, std::int32_t z) -> long {
        for (std::size_t q : quads_of_edge[edge_key(x, y)]) {
          const auto& n = outer_quads[q];
          if (std::find(n.begin(), n.end(), z) != n.end()) return long(q);
        }
        return -1;
      };
      std::vector<std::int32_t> kept{chain[0]};
      bool last_diagonal = false;  // kept.back() joins its predecessor across a quad
      for (std::size_t k = 1; k + 1 < chain.size(); ++k) {
        const long q = last_diagonal || shared.count(chain[k])
                           ? -1
                           : quad_with(kept.back(), chain[k], chain[k + 1]);
        if (q >= 0 && cut_by[q] < 0) {
          cut_by[q] = e.value();
          turn_of[q] = chain[k];
          reserved.insert(chain[k]);
          ++r.quads_across_edges;
          last_diagonal = true;
          continue;
        }
        kept.push_back(chain[k]);
        last_diagonal = false;
      }
      kept.push_back(chain.back());
      chain = std::move(kept);
    }
    const int m = int(chain.size()) - 1;
    const std::vector<Vec3> points = solid.edge_points_by_length(e, m);
    for (int k = 1; k < m; ++k) {
      if (shared.count(chain[k])) continue;
      mesh.set_point(NodeId(chain[k]), points[k]);
      mesh.set_node_class(NodeId(chain[k]), NodeClass::on(e));
      on_feature.insert(chain[k]);
    }
    for (int k = 0; k < m; ++k) feature_edges.emplace(edge_key(chain[k], chain[k + 1]), e.value());
    captured_between.insert({std::min(faces[0].value(), faces[1].value()),
                             std::max(faces[0].value(), faces[1].value())});
    ++r.edges_captured;
  }

  // 3. Faces: regions of quads between the chains, each on the face most of its free
  // nodes projected to.
  std::vector<int> region(outer_quads.size(), -1);
  int regions = 0;
  std::vector<char> face_used(solid.num_faces() + 1, 0);
  for (std::size_t q = 0; q < outer_quads.size(); ++q)
    if (cut_by[q] >= 0)
      for (int c = 0; c < 4; ++c)
        feature_edges.emplace(edge_key(outer_quads[q][c], outer_quads[q][(c + 1) % 4]), cut_by[q]);
  // Puts node n on face `to` (projected), unless that is far from the node: false then.
  // Far (more than three cells), the face is not where the node is: the region leaked across an
  // uncaptured edge onto another part of the model (HexMe i11: an end face's nodes sent 38 units,
  // 16 cells, away to the edge of a cylinder, two hexes inverted per node). Moves of one or two
  // cells are real (n05).
  auto move_to = [&](std::int32_t n, int to) {
    core::FaceId f(to);
    const Vec3 p = small.project(solid, f, mesh.point(NodeId(n)), f);
    if (!p.allFinite() || (p - mesh.point(NodeId(n))).norm() > 3 * size) return false;
    mesh.set_point(NodeId(n), p);
    mesh.set_node_class(NodeId(n), NodeClass::on(f));
    return true;
  };
  for (std::size_t seed = 0; seed < outer_quads.size(); ++seed) {
    if (region[seed] >= 0 || cut_by[seed] >= 0) continue;
    std::vector<std::size_t> members{seed}, stack{seed};
    std::set<int> around;  // the model edges of the chains around the region
    region[seed] = regions;
    while (!stack.empty()) {
      const std::size_t q = stack.back();
      stack.pop_back();
      for (int c = 0; c < 4; ++c) {
        const std::int64_t k = edge_key(outer_quads[q][c], outer_quads[q][(c + 1) % 4]);
        if (const auto it = feature_edges.find(k); it != feature_edges.end()) {
          around.insert(it->second);
          continue;
        }
        for (std::size_t o : quads_of_edge[k])
          if (region[o] < 0 && cut_by[o] < 0)
            region[o] = regions, stack.push_back(o), members.push_back(o);
      }
    }
    ++regions;
    // A composite votes as one face (its host).
    auto host_of = [&](int f) {
      const int c = small.composite_of_face[f];
      return c < 0 ? f : small.composites[c].host.value();
    };
    std::map<int, int> votes;
    std::unordered_set<std::int32_t> free_nodes;
    for (std::size_t q : members)
      for (std::int32_t n : outer_quads[q]) {
        const NodeClass c = mesh.node_class(NodeId(n));
        if (c.dim == 2 && free_nodes.insert(n).second) ++votes[host_of(c.id)];
      }
    if (votes.empty()) continue;
    // A region lies on a face every chain around it borders. Where the vote names another
    // (a narrow region with a node or two, first projected across its edge: HexMe i13's
    // strip between two edges of a small slanted face, whose one free node had landed on
    // the border of the next face and stayed on the line of the edge, a hexahedron flat),
    // the face that borders them all and has the most votes (region_face).
    const int face = region_face(votes, around, [&](int f, int x) {
      for (core::FaceId g : solid.edge_faces(core::EdgeId(x)))
        if (host_of(g.value()) == f) return true;
      return false;
    });
    face_used[face] = 1;
    for (std::size_t q : members) {
      bool moved = false;
      for (std::int32_t n : outer_quads[q]) {
        const NodeClass c = mesh.node_class(NodeId(n));
        moved = moved || (c.dim == 2 && !small.same_composite(c.id, face));
      }
      r.quads_moved += moved;
    }
    // A node that projected across a captured edge goes to the region's face; one on
    // another face (across an absorbed or uncaptured feature) stays where it is.
    for (std::int32_t n : free_nodes) {
      const int own = mesh.node_class(NodeId(n)).id;
      if (small.same_composite(own, face)) continue;
      if (!captured_between.count({std::min(own, face), std::max(own, face)}) || !move_to(n, face))
        face_used[own] = 1;
    }
  }
  // A quad a chain cuts diagonally lies on both faces of the chain's edge, a triangle on
  // each: its two corners off the chain belong one to each face. Where both are on one face
  // (a region that ran across an uncaptured edge keeps its nodes on the faces they first
  // projected to: HexMe i09, both on the torus Face26, the turn node, outside the chain's
  // turn, held at the torus's boundary on Edge94's curve and the quad flat along it, min
  // 0.001), one held on the edge's curve (projected beyond its face) most of whose
  // neighbours lie on the edge's other face goes there.
  for (std::size_t q = 0; q < outer_quads.size(); ++q) {
    if (turn_of[q] < 0) continue;  // not cut (set with cut_by)
    const auto& quad = outer_quads[q];
    const long at = std::find(quad.begin(), quad.end(), turn_of[q]) - quad.begin();  // in it
    const std::array<std::int32_t, 2> off{quad[std::size_t(at)], quad[std::size_t((at + 2) % 4)]};
    const NodeClass c0 = mesh.node_class(NodeId(off[0])), c1 = mesh.node_class(NodeId(off[1]));
    if (c0.dim != 2 || c1.dim != 2 || !small.same_composite(c0.id, c1.id)) continue;
    int other = -1;
    for (core::FaceId f : solid.edge_faces(core::EdgeId(cut_by[q])))
      if (!small.same_composite(f.value(), c0.id)) other = f.value();
    if (other < 0) continue;
    // The share of an off node's face neighbours on the other face.
    auto share = [&](std::int32_t n) {
      int on_other = 0, all = 0;
      for (std::int32_t m : s.adjacent.at(n)) {
        const NodeClass c = mesh.node_class(NodeId(m));
        if (c.dim != 2) continue;
        ++all;
        on_other += small.same_composite(c.id, other);
      }
      return all == 0 ? 0.0 : double(on_other) / all;
    };
    // A node inside its face stays: HexMe i19's finer grid, whose one such node, a quarter
    // cell inside the cylinder Face21, went to the plane Face9, ended with four hexahedra
    // inverted elsewhere (its smoothing's path changed).
    auto on_curve = [&](std::int32_t n) {
      const Vec3 p = mesh.point(NodeId(n));
      return (solid.project_to_edge(core::EdgeId(cut_by[q]), p) - p).norm() < 0.01 * size;
    };
    const double s0 = on_curve(off[0]) ? share(off[0]) : 0.0;
    const double s1 = on_curve(off[1]) ? share(off[1]) : 0.0;
    const std::int32_t n = s1 > s0 ? off[1] : off[0];
    if (std::max(s0, s1) > 0.7 && move_to(n, other)) face_used[other] = 1;
  }
  // 4. The surface evened out with every node on its entity (vertices stay, edge nodes
  // slide along their curve, face nodes on their face).
  relax(
      mesh, s, solid, 5, [](std::int32_t) { return true; }, false, small);

  r.faces = solid.num_faces();
  for (core::FaceId f : solid.faces()) {
    if (small.absorbed_face[f.value()])
      r.absorbed.push_back(core::entity_name(f));
    else if (face_used[f.value()])
      ++r.faces_captured;
    else
      r.missed.push_back(core::entity_name(f));
  }
  return r;
}

}  // namespace vorohex::grid::detail
