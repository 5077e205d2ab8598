#include "mesh/face_set.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "core/option_checks.h"
#include "mesh/detail/grid_face.h"
#include "mesh/detail/sizing.h"
#include "mesh/interval_assignment.h"
#include "mesh/quad_face.h"
#include "mesh/submap_face.h"

namespace vorohex::mesh {

using core::EdgeId;
using core::FaceId;
using core::NodeClass;
using core::OrientedEdge;
using core::Vec3;
using core::VertexId;

void FaceSetOptions::validate() const {
  core::require_positive("FaceSetOptions.size", size);
  core::require_at_least("FaceSetOptions.max_intervals", max_intervals, 1);
  core::require_at_least("FaceSetOptions.smoothing_passes", smoothing_passes, 0);
  core::require_positive("FaceSetOptions.interval_time_limit", interval_time_limit);
  for (int n : fixed_counts) core::require_at_least("FaceSetOptions.fixed_counts", n, 0);
  for (const auto& p : given_edge_points)
    if (p.size() == 1)
      throw std::invalid_argument("FaceSetOptions.given_edge_points: an edge of one node");
  for (const FixedSum& f : fixed_sums) {
    core::require_at_least("FaceSetOptions.fixed_sums.count", f.count, 1);
    if (f.edges.empty())
      throw std::invalid_argument("FaceSetOptions.fixed_sums: a sum without edges");
  }
}

std::size_t FaceSetMesh::num_quads() const {
  std::size_t n = 0;
  for (const auto& q : quads) n += q.size();
  return n;
}

namespace {

enum class Scheme { map, submap, quad };

// A mapped face's logical sides: one wire whose vertices turn by 45 to 135 degrees (about the
// face normal) at exactly four corners and by less than 15 degrees elsewhere (a vertex a
// neighbour's edge ends at, on a straight or smooth side), so that the transfinite grid stays
// fair. Per wire edge its side 0..3, counted from the first corner at or after the wire's
// start (`first`: the index of the edge that starts there); empty when not mappable.
struct MappedSides {
  std::vector<int> side;  // per wire edge
  int first = 0;
  bool ok() const { return !side.empty(); }
};

MappedSides mapped_sides(const core::MeshDomain& s, FaceId f) {
  MappedSides out;
  const auto wires = s.face_wires(f);
  if (wires.size() != 1 || wires[0].size() < 4) return out;
  const auto& w = wires[0];
  const std::size_t n = w.size();
  const double kPi = 3.14159265358979323846;
  std::vector<bool> corner(n, false);  // at the start of edge k
  int corners = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const OrientedEdge &a = w[(k + n - 1) % n], &b = w[k];
    if (s.edge_is_degenerated(a.edge) || s.edge_is_degenerated(b.edge)) return out;
    std::vector<Vec3> pa = s.edge_points_by_length(a.edge, 16);
    std::vector<Vec3> pb = s.edge_points_by_length(b.edge, 16);
    if (!a.forward) std::reverse(pa.begin(), pa.end());
    if (!b.forward) std::reverse(pb.begin(), pb.end());
    const Vec3 t0 = (pa[pa.size() - 1] - pa[pa.size() - 2]).normalized();
    const Vec3 t1 = (pb[1] - pb[0]).normalized();
    const Vec3 nrm = s.face_normal(f, pb[0]);
    const double turn = std::atan2(t0.cross(t1).dot(nrm), t0.dot(t1));
    // 45 and 135 degrees themselves are corners: a face parted along a diagonal (the corner
    // of a ball's octant parted like a cube's) turns by exactly 45 degrees, which rounding
    // puts either side.
    constexpr double kRounding = 1e-9;
    if (turn >= kPi / 4 - kRounding && turn <= 3 * kPi / 4 + kRounding) {
      corner[k] = true;
      ++corners;
    } else if (std::abs(turn) > kPi / 12) {
      return out;
    }
  }
  if (corners != 4) return out;
  int first = 0;
  while (!corner[first]) ++first;
  out.first = first;
  out.side.assign(n, 0);
  int side = -1;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = (first + i) % n;
    if (corner[k]) ++side;
    out.side[k] = side;
  }
  return out;
}

struct Plan {
  std::vector<Scheme> scheme;           // per face id
  std::vector<MappedSides> sides;       // per face id, when mapped
  std::vector<SubmapStructure> submap;  // per face id, when submapped
};

// The interval problem: one curve per edge (index = edge id - 1); constraints per face.
// A whole circle (a round hole, a disc's rim): one closed circular edge.
bool whole_circle(const core::MeshDomain& s, EdgeId e) {
  return s.edge_first_vertex(e) == s.edge_last_vertex(e) &&
         s.curve_info(e).kind == core::CurveKind::circle;
}

// `preferences`: whole circles of quad-meshed faces get a multiple of 4 segments, at least
// 8, so that their quadrant points are nodes (where a load along the seam's axes peaks at
// a hole) and the rings around them are symmetric; dropped when they make the counts
// infeasible.
IntervalProblem problem_for(const core::MeshDomain& s, const Plan& plan, const FaceSetOptions& o,
                            bool preferences) {
  IntervalProblem p;
  for (EdgeId e : s.edges())
    p.add_curve(
        std::max(s.edge_length(e), 1e-300), core::entity_name(e),
        detail::graded(o.size_field) ? detail::edge_segments(s, e, o.size, o.size_field) : 0);
  p.fixed.assign(s.num_edges(), 0);
  for (EdgeId e : s.edges())
    if (e.value() < int(o.fixed_counts.size())) p.fixed[e.value() - 1] = o.fixed_counts[e.value()];
  for (EdgeId e : s.edges())
    if (e.value() < int(o.given_edge_points.size()) && !o.given_edge_points[e.value()].empty())
      p.fixed[e.value() - 1] = int(o.given_edge_points[e.value()].size()) - 1;
  // A fixed sum: a curve of the chain's length fixed to the count, equal to the chain.
  for (const FaceSetOptions::FixedSum& f : o.fixed_sums) {
    std::vector<int> chain;
    double length = 0;
    std::string names;
    for (int e : f.edges) {
      if (e < 1 || e > s.num_edges())
        throw std::invalid_argument("FaceSetOptions.fixed_sums: no edge " + std::to_string(e));
      chain.push_back(e - 1);
      length += s.edge_length(EdgeId(e));
      names += (names.empty() ? "" : "+") + core::entity_name(EdgeId(e));
    }
    const int k = p.add_curve(std::max(length, 1e-300), names);
    p.fixed.push_back(f.count);
    p.equal.push_back({chain, {k}, names + ": " + std::to_string(f.count) + " segments in all"});
  }
  for (FaceId f : s.faces()) {
    const auto wires = s.face_wires(f);
    const std::string name = core::entity_name(f);
    switch (plan.scheme[f.value()]) {
      case Scheme::map: {
        const auto& w = wires[0];
        const MappedSides& ms = plan.sides[f.value()];
        std::array<std::vector<int>, 4> side;
        for (std::size_t k = 0; k < w.size(); ++k)
          side[ms.side[k]].push_back(w[k].edge.value() - 1);
        for (int k = 0; k < 2; ++k)
          p.equal.push_back({side[k], side[k + 2], name + ": opposite sides of a mapped face"});
        break;
      }
      case Scheme::submap: {
        std::vector<std::vector<int>> curves;
        for (const auto& w : wires) {
          curves.emplace_back();
          for (const OrientedEdge& oe : w) curves.back().push_back(oe.edge.value() - 1);
        }
        add_submap_balance(p, plan.submap[f.value()], curves, name);
        break;
      }
      case Scheme::quad: {
        const int minimum = wires.size() == 1 ? 4 : 6;
        for (const auto& w : wires) {
          std::vector<int> curves;
          for (const OrientedEdge& oe : w) {
            curves.push_back(oe.edge.value() - 1);
            p.even.push_back({{oe.edge.value() - 1},
                              name + ": " + core::entity_name(oe.edge) +
                                  " even (its vertices are corner nodes of the quad mesh)"});
            if (preferences && whole_circle(s, oe.edge)) {
              const std::string circle =
                  name + ": " + core::entity_name(oe.edge) + ", a whole circle,";
              p.even.push_back({{oe.edge.value() - 1}, circle + " in a multiple of 4 segments", 4});
              p.at_least.push_back({{oe.edge.value() - 1}, 8, circle + " in at least 8 segments"});
            }
          }
          p.at_least.push_back(
              {curves, minimum,
               name + ": a loop of at least " + std::to_string(minimum) + " segments"});
        }
        break;
      }
    }
  }
  return p;
}

}  // namespace

FaceSetMesh mesh_face_set(const core::MeshDomain& s, const FaceSetOptions& options,
                          const core::Progress& progress) {
  options.validate();
  FaceSetMesh out;
  const int nf = s.num_faces(), ne = s.num_edges(), nv = s.num_vertices();
  Plan plan;
  plan.scheme.assign(nf + 1, Scheme::quad);
  plan.submap.assign(nf + 1, {});
  plan.sides.assign(nf + 1, {});
  for (FaceId f : s.faces()) {
    plan.sides[f.value()] = mapped_sides(s, f);
    if (plan.sides[f.value()].ok()) {
      plan.scheme[f.value()] = Scheme::map;
    } else {
      plan.submap[f.value()] = submap_structure(s, f);
      if (plan.submap[f.value()].ok) plan.scheme[f.value()] = Scheme::submap;
    }
  }
  IntervalOptions io;
  io.size = options.size;
  io.max_intervals = options.max_intervals;
  io.time_limit = options.interval_time_limit;

  // Structured faces whose counts cannot be met, or whose grid folds, become quad faces.
  for (int round = 0; round <= nf; ++round) {
    if (progress.cancelled()) {
      out.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
      return out;
    }
    IntervalResult assigned = assign_intervals(problem_for(s, plan, options, true), io);
    if (!assigned.ok()) assigned = assign_intervals(problem_for(s, plan, options, false), io);
    if (!assigned.ok()) {
      // Structured faces over-constrain the counts (fixed counts, mapped faces in a ring):
      // once more with every face meshed by quad_face, which needs only even counts.
      bool structured = false;
      for (FaceId f : s.faces()) structured |= plan.scheme[f.value()] != Scheme::quad;
      if (!structured) {
        out.diagnostics = assigned.diagnostics;
        return out;
      }
      std::fill(plan.scheme.begin(), plan.scheme.end(), Scheme::quad);
      continue;
    }
    out = FaceSetMesh();
    out.edge_counts.assign(ne + 1, 0);
    for (int e = 1; e <= ne; ++e) out.edge_counts[e] = assigned.intervals[e - 1];
    // Nodes: vertices, then each edge's inner nodes.
    std::vector<int> vertex_node(nv + 1, -1);
    for (VertexId v : s.vertices()) {
      vertex_node[v.value()] = int(out.points.size());
      out.points.push_back(s.vertex_point(v));
      out.on.push_back(NodeClass::on(v));
    }
    out.edge_nodes.assign(ne + 1, {});
    for (EdgeId e : s.edges()) {
      const bool given = e.value() < int(options.given_edge_points.size()) &&
                         !options.given_edge_points[e.value()].empty();
      const std::vector<Vec3> p =
          given ? options.given_edge_points[e.value()]
                : detail::edge_points(s, e, out.edge_counts[e.value()], options.size_field);
      auto& ids = out.edge_nodes[e.value()];
      ids.push_back(vertex_node[s.edge_first_vertex(e).value()]);
      for (std::size_t i = 1; i + 1 < p.size(); ++i) {
        ids.push_back(int(out.points.size()));
        out.points.push_back(p[i]);
        out.on.push_back(NodeClass::on(e));
      }
      ids.push_back(vertex_node[s.edge_last_vertex(e).value()]);
    }
    out.quads.assign(nf + 1, {});
    out.face_schemes.assign(nf + 1, "");
    bool refold = false;
    double sum = 0;
    out.min_quality = 1;
    for (FaceId f : s.faces()) {
      std::vector<std::vector<Vec3>> loops;
      std::vector<int> ids;  // global id of each loop node, loop after loop
      std::vector<std::vector<int>> counts;
      for (const auto& w : s.face_wires(f)) {
        loops.emplace_back();
        counts.emplace_back();
        for (const OrientedEdge& oe : w) {
          std::vector<int> nodes = out.edge_nodes[oe.edge.value()];
          if (!oe.forward) std::reverse(nodes.begin(), nodes.end());
          for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
            ids.push_back(nodes[i]);
            loops.back().push_back(out.points[nodes[i]]);
          }
          counts.back().push_back(out.edge_counts[oe.edge.value()]);
        }
      }
      QuadFaceMesh m;
      const Scheme scheme = plan.scheme[f.value()];
      if (scheme == Scheme::map) {
        // The loop from the first corner on; the sides' counts.
        const MappedSides& ms = plan.sides[f.value()];
        std::size_t start = 0;
        for (int k = 0; k < ms.first; ++k) start += std::size_t(counts[0][k]);
        std::rotate(loops[0].begin(), loops[0].begin() + long(start), loops[0].end());
        std::rotate(ids.begin(), ids.begin() + long(start), ids.end());
        int n[2] = {0, 0};
        for (std::size_t k = 0; k < ms.side.size(); ++k)
          if (ms.side[k] < 2) n[ms.side[k]] += counts[0][k];
        m = detail::grid_face(s, f, loops[0], n[0], n[1]);
      } else if (scheme == Scheme::submap) {
        m = submap_face(s, f, loops, counts, plan.submap[f.value()]);
      } else {
        QuadFaceOptions qo;
        qo.size = options.size;
        qo.smoothing_passes = options.smoothing_passes;
        qo.size_field = options.size_field;
        m = quad_face(s, f, loops, qo);
        if (!m.ok) {
          out.diagnostics = m.diagnostics;
          return out;
        }
      }
      if (scheme != Scheme::quad && (!m.ok || m.min_quality <= 0)) {
        plan.scheme[f.value()] = Scheme::quad;
        refold = true;
        continue;
      }
      out.face_schemes[f.value()] = scheme == Scheme::map      ? "map"
                                    : scheme == Scheme::submap ? "submap"
                                                               : "quad";
      std::vector<int> local(m.points.size());
      for (std::size_t i = 0; i < m.num_boundary; ++i) local[i] = ids[i];
      for (std::size_t i = m.num_boundary; i < m.points.size(); ++i) {
        local[i] = int(out.points.size());
        out.points.push_back(m.points[i]);
        out.on.push_back(NodeClass::on(f));
      }
      for (const auto& q : m.quads)
        out.quads[f.value()].push_back({local[q[0]], local[q[1]], local[q[2]], local[q[3]]});
      out.min_quality = std::min(out.min_quality, m.min_quality);
      sum += m.mean_quality * double(m.quads.size());
    }
    if (refold) continue;
    const std::size_t n = out.num_quads();
    out.mean_quality = n > 0 ? sum / double(n) : 0;
    out.ok = true;
    return out;
  }
  out.diagnostics.push_back(
      core::make_error("quad_face_failed", "The faces could not be meshed with conforming quads."));
  return out;
}

}  // namespace vorohex::mesh
