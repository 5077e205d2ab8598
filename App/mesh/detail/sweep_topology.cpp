#include "mesh/detail/sweep_topology.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace vorohex::mesh::detail {

using core::EdgeId;
using core::FaceId;
using core::OrientedEdge;
using core::Vec3;
using core::VertexId;
using Solid = core::MeshDomain;

namespace {

std::string name(FaceId f) {
  return core::entity_name(f);
}
std::string name(EdgeId e) {
  return core::entity_name(e);
}

VertexId start_of(const Solid& s, const OrientedEdge& e) {
  return e.forward ? s.edge_first_vertex(e.edge) : s.edge_last_vertex(e.edge);
}
VertexId end_of(const Solid& s, const OrientedEdge& e) {
  return e.forward ? s.edge_last_vertex(e.edge) : s.edge_first_vertex(e.edge);
}

// The turn (degrees) from edge a to edge b at the vertex where a ends and b starts, both as
// a wire reads them: the angle between a's direction arriving there and b's leaving it.
double chain_turn(const Solid& s, const OrientedEdge& a, const OrientedEdge& b) {
  auto ends = [&](const OrientedEdge& e) {
    std::vector<Vec3> p = s.edge_points_by_length(e.edge, 16);
    if (!e.forward) std::reverse(p.begin(), p.end());
    return p;
  };
  const std::vector<Vec3> pa = ends(a), pb = ends(b);
  const Vec3 ta = pa[pa.size() - 1] - pa[pa.size() - 2], tb = pb[1] - pb[0];
  const double c = ta.normalized().dot(tb.normalized());
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180 / M_PI;
}

// Whether e bounds face f on both sides (its seam) and no other face.
bool is_seam_of(const Solid& s, EdgeId e, FaceId f) {
  for (FaceId g : s.edge_faces(e))
    if (g != f) return false;
  return true;
}

// The sides of a linking face's wire `q` whose edges i .. i + ns - 1 lie on the source side
// (the source edge, or the separator below a face of a stack): the linking chain leaving the
// source side's start (`up`, as the wire reads it), the target chain and the linking chain
// coming back to it (`down`, as the wire reads it). Where exactly two of the junctions
// between the other edges turn by more than kSideTurn, they part the three chains;
// otherwise the linking sides are the single edges next to the source side and the rest is
// the target chain (whose junctions the caller checks).
void split_sides(const Solid& s, const std::vector<OrientedEdge>& q, int i, int ns, bool chains,
                 std::vector<OrientedEdge>& up, std::vector<OrientedEdge>& target,
                 std::vector<OrientedEdge>& down) {
  const int nq = int(q.size());
  auto at = [&](int c) -> const OrientedEdge& { return q[(i + c) % nq]; };
  std::vector<int> corners;  // junction c: between at(c) and at(c + 1), c in ns .. nq - 2
  for (int c = ns; chains && c + 1 < nq; ++c)
    if (chain_turn(s, at(c), at(c + 1)) > kSideTurn) corners.push_back(c);
  int c1 = ns, c2 = nq - 2;
  if (corners.size() == 2) c1 = corners[0], c2 = corners[1];
  up.clear(), target.clear(), down.clear();
  for (int c = ns; c <= c1; ++c) up.push_back(at(c));
  for (int c = c1 + 1; c <= c2; ++c) target.push_back(at(c));
  for (int c = c2 + 1; c < nq; ++c) down.push_back(at(c));
}

// The face across every edge of `chain` from face `f` (invalid where they differ or one
// bounds f alone).
FaceId across(const Solid& s, const std::vector<OrientedEdge>& chain, FaceId f) {
  FaceId out;
  for (const OrientedEdge& o : chain) {
    FaceId other;
    for (FaceId g : s.edge_faces(o.edge))
      if (g != f) other = g;
    if (!other.valid() || (out.valid() && other != out)) return FaceId();
    out = other;
  }
  return out;
}

// Where face g continues the linking face f below it across `chain` (read by f, whose
// linking chains end with `up_last` arriving at the chain's start and `down_first` leaving
// its end): the two meet flat across the chain, g's wire reads the chain backwards as
// consecutive edges, and g's sides next to it run on straight from those chains. Sets g's sides
// (split_sides) when it does.
bool continues(const Solid& s, FaceId f, FaceId g, const std::vector<OrientedEdge>& chain,
               const OrientedEdge& up_last, const OrientedEdge& down_first,
               std::vector<OrientedEdge>& up, std::vector<OrientedEdge>& target,
               std::vector<OrientedEdge>& down) {
  // The two faces meet flat across the chain (one face split there, not a bend).
  for (const OrientedEdge& o : chain) {
    const std::vector<Vec3> p = s.edge_points_by_length(o.edge, 2);
    const Vec3 nf = s.face_normal(f, p[1]), ng = s.face_normal(g, p[1]);
    if (nf.norm() <= 0 || ng.norm() <= 0 ||
        nf.normalized().dot(ng.normalized()) < std::cos(kSideTurn * M_PI / 180))
      return false;
  }
  const auto gw = s.face_wires(g);
  if (gw.size() != 1) return false;
  const auto& q = gw[0];
  const int nq = int(q.size()), ns = int(chain.size());
  if (nq < ns + 3) return false;
  int i = -1;
  for (int c = 0; c < nq; ++c)
    if (q[c].edge == chain.back().edge) i = c;
  if (i < 0) return false;
  for (int c = 0; c < ns; ++c)
    if (q[(i + c) % nq].edge != chain[ns - 1 - c].edge) return false;
  split_sides(s, q, i, ns, true, up, target, down);
  return chain_turn(s, up_last, up.front()) <= kSideTurn &&
         chain_turn(s, down.back(), down_first) <= kSideTurn;
}

double chain_length(const Solid& s, const std::vector<Directed>& chain) {
  double l = 0;
  for (const Directed& d : chain) l += s.edge_length(d.edge);
  return l;
}

}  // namespace

std::vector<EdgeId> chain_edges(const std::vector<Directed>& chain) {
  std::vector<EdgeId> out;
  for (const Directed& d : chain) out.push_back(d.edge);
  return out;
}

std::string find_sweep_topology(const Solid& s, FaceId S, SweepTopology& topo, bool imprinted) {
  const bool stacks = imprinted;
  topo = SweepTopology();
  topo.source = S;
  std::set<int> source_edges, linking_faces, source_vertices;
  const auto wires = s.face_wires(S);
  for (const auto& w : wires)
    for (const OrientedEdge& oe : w) {
      source_edges.insert(oe.edge.value());
      source_vertices.insert(s.edge_first_vertex(oe.edge).value());
      source_vertices.insert(s.edge_last_vertex(oe.edge).value());
    }
  FaceId T;
  std::set<int> target_edges;
  std::set<int> link_chains;  // by their first edge
  double link_sum = 0;
  for (const auto& w : wires) {
    std::vector<Link> loop;
    for (const OrientedEdge& oe : w) {
      if (s.edge_is_degenerated(oe.edge)) return name(oe.edge) + " is degenerated";
      FaceId L;
      for (FaceId f : s.edge_faces(oe.edge))
        if (f != S) L = f;
      if (!L.valid()) return name(oe.edge) + " bounds " + name(S) + " only (a seam)";
      if (!linking_faces.insert(L.value()).second)
        return name(L) + " touches " + name(S) + " along more than one edge";
      const auto lw = s.face_wires(L);
      const int nq = lw.empty() ? 0 : int(lw[0].size());
      if (lw.size() != 1 || nq < 4)
        return name(L) + " is not four-sided (" + std::to_string(lw.size()) + " wires, " +
               std::to_string(nq) + " edges)";
      const auto& q = lw[0];
      int i = -1;
      for (int c = 0; c < nq; ++c)
        if (q[c].edge == oe.edge) i = c;
      if (i < 0) return name(L) + " has an inconsistent wire";
      std::vector<OrientedEdge> up, opp, down;
      split_sides(s, q, i, 1, stacks, up, opp, down);
      // Up a stack of linking faces while the face across the side opposite the source runs
      // the linking chains on straight (the target face turns away from them).
      std::vector<OrientedEdge> up_all = up, down_all = down;  // down_all as the wires read
      std::vector<FaceId> stack;
      std::vector<std::vector<OrientedEdge>> separators;
      std::vector<int> below0, below1;
      for (FaceId g = stacks ? across(s, opp, L) : FaceId(); g.valid() && g != S;
           g = across(s, opp, stack.back())) {
        std::vector<OrientedEdge> gu, go, gd;
        if (std::find(stack.begin(), stack.end(), g) != stack.end() || g == L ||
            !continues(s, stack.empty() ? L : stack.back(), g, opp, up_all.back(), down_all.front(),
                       gu, go, gd))
          break;
        if (!linking_faces.insert(g.value()).second)
          return name(g) + " is in two stacks of linking faces";
        separators.push_back(opp);
        below0.push_back(int(up_all.size()));
        below1.push_back(int(down_all.size()));
        stack.push_back(g);
        up_all.insert(up_all.end(), gu.begin(), gu.end());
        down_all.insert(down_all.begin(), gd.begin(), gd.end());
        opp = std::move(go);
      }
      up = std::move(up_all), down = std::move(down_all);
      const FaceId top = stack.empty() ? L : stack.back();
      for (const auto& sep : separators)
        for (std::size_t c = 1; c < sep.size(); ++c)
          if (chain_turn(s, sep[c - 1], sep[c]) > kSideTurn)
            return name(sep[c - 1].edge) + " and " + name(sep[c].edge) +
                   " meet at a corner between two faces of a stack of linking faces";
      for (std::size_t c = 1; c < opp.size(); ++c)
        if (chain_turn(s, opp[c - 1], opp[c]) > kSideTurn)
          return name(L) + " is not four-sided (1 wires, " + std::to_string(nq) + " edges; " +
                 name(opp[c - 1].edge) + " and " + name(opp[c].edge) + " meet at a corner)";
      bool on_source = false;
      for (const auto* side : {&up, &opp, &down})
        for (const OrientedEdge& o : *side)
          on_source = on_source || source_edges.count(o.edge.value());
      if (on_source) return name(L) + " has more than one edge on " + name(S);
      for (const OrientedEdge& o : opp) {
        FaceId other;
        for (FaceId f : s.edge_faces(o.edge))
          if (f != top) other = f;
        if (!other.valid() || other == S) return name(o.edge) + " does not reach a target face";
        if (!T.valid()) T = other;
        if (other != T)
          return "the edges opposite " + name(S) + " lie on " + name(T) + " and " + name(other);
        target_edges.insert(o.edge.value());
      }
      for (std::size_t c = 1; c < opp.size(); ++c)
        if (source_vertices.count(start_of(s, opp[c]).value()))
          return name(S) + " and " + name(T) + " share a vertex";
      Link link;
      link.face = L;
      link.source = {oe.edge, oe.forward};
      for (const OrientedEdge& o : opp) link.target.push_back({o.edge, o.forward});
      for (const OrientedEdge& o : up) link.col0.push_back({o.edge, o.forward});
      for (auto it = down.rbegin(); it != down.rend(); ++it)
        link.col1.push_back({it->edge, !it->forward});
      link.stack = stack;
      for (const auto& sep : separators) {
        link.separators.emplace_back();
        for (const OrientedEdge& o : sep) link.separators.back().push_back({o.edge, o.forward});
      }
      link.below0 = below0, link.below1 = below1;
      link.b = start_of(s, oe);
      link.b_target = end_of(s, up.back());
      if (start_of(s, up.front()) != link.b) return name(L) + " has an inconsistent wire";
      // A linking chain leaves the source at its first vertex and never comes back to it:
      // every edge's end away from the source (as the chain runs up) is off the source.
      for (const OrientedEdge& e : up)
        if (source_vertices.count(end_of(s, e).value()))
          return name(e.edge) + " joins two vertices of " + name(S);
      for (const OrientedEdge& e : down)  // read by the wire from the top down
        if (source_vertices.count(start_of(s, e).value()))
          return name(e.edge) + " joins two vertices of " + name(S);
      for (const std::vector<Directed>* chain : {&link.col0, &link.col1})
        if (link_chains.insert(chain->front().edge.value()).second)
          link_sum += chain_length(s, *chain);
      loop.push_back(link);
    }
    for (std::size_t c = 0; c < loop.size(); ++c)
      if (chain_edges(loop[c].col1) != chain_edges(loop[(c + 1) % loop.size()].col0))
        return name(loop[c].face) + " and " + name(loop[(c + 1) % loop.size()].face) +
               " do not share a linking edge";
    topo.loops.push_back(std::move(loop));
  }
  if (!T.valid()) return name(S) + " has no edges";
  if (linking_faces.count(T.value())) return name(T) + " is both a linking and the target face";
  if (int(linking_faces.size()) + 2 != s.num_faces())
    return "besides " + name(S) + ", " + name(T) + " and " + std::to_string(linking_faces.size()) +
           " linking faces the solid has other faces";
  std::set<int> t_all;
  for (const auto& w : s.face_wires(T))
    for (const OrientedEdge& oe : w) {
      // A cone's apex (a degenerated edge) and its seam (an edge of the target alone) bound
      // no linking face: a drill point's cone is the target of a sweep from a disc, its
      // apex where the line along the axis through the disc's centre meets it.
      if (s.edge_is_degenerated(oe.edge)) continue;
      if (is_seam_of(s, oe.edge, T)) continue;
      t_all.insert(oe.edge.value());
      if (source_vertices.count(s.edge_first_vertex(oe.edge).value()))
        return name(S) + " and " + name(T) + " share a vertex";
    }
  if (t_all != target_edges) return name(T) + " has edges that no linking face reaches";
  topo.target = T;
  topo.link_length = link_chains.empty() ? 0 : link_sum / link_chains.size();
  return "";
}

std::string choose_sweep_topology(const Solid& s, SweepTopology& best,
                                  const std::vector<int>& avoid, bool imprinted) {
  std::string first_reason;
  bool found = false;
  auto avoided = [&](FaceId f) {
    return std::find(avoid.begin(), avoid.end(), f.value()) != avoid.end();
  };
  for (int pass = 0; pass < (imprinted ? 2 : 1) && !found; ++pass)
    for (FaceId f : s.faces()) {
      SweepTopology t;
      const std::string why = find_sweep_topology(s, f, t, pass == 1);
      if (!why.empty()) {
        if (first_reason.empty()) first_reason = "with " + name(f) + " as source, " + why;
        continue;
      }
      if (!found) {
        best = std::move(t);
        found = true;
        continue;
      }
      // A source to avoid loses to any other; then the shortest links, the largest source.
      if (avoided(f) != avoided(best.source)) {
        if (!avoided(f)) best = std::move(t);
        continue;
      }
      const double tol = 1e-9 * std::max(1.0, best.link_length);
      if (t.link_length < best.link_length - tol ||
          (t.link_length <= best.link_length + tol && s.area(f) > s.area(best.source) * (1 + 1e-9)))
        best = std::move(t);
    }
  if (found) return "";
  return "no two faces are joined by four-sided linking faces (" + first_reason + ")";
}

}  // namespace vorohex::mesh::detail
