#include "mesh/mesh_sub_volumes.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <future>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <thread>

#include "core/option_checks.h"
#include "core/progress.h"
#include "mesh/assemble.h"
#include "mesh/detail/revolved_part.h"
#include "mesh/detail/shared_face_mesh.h"
#include "mesh/detail/sizing.h"
#include "mesh/detail/sub_volume_part.h"
#include "mesh/detail/sweep_orientation.h"
#include "mesh/interval_assignment.h"
#include "mesh/map_block.h"
#include "mesh/multisweep.h"
#include "mesh/revolve.h"
#include "mesh/submap_face.h"
#include "mesh/sweep.h"
#include "occ/prismatic.h"
#include "smooth/smooth_mesh.h"

namespace vorohex::mesh {

using core::EdgeId;

void SubVolumeMeshOptions::validate() const {
  core::require_positive("SubVolumeMeshOptions.size", size);
  core::require_at_least("SubVolumeMeshOptions.max_intervals", max_intervals, 1);
  core::require_at_least("SubVolumeMeshOptions.smoothing_passes", smoothing_passes, 0);
  core::require_positive("SubVolumeMeshOptions.interval_time_limit", interval_time_limit);
  core::require_at_least("SubVolumeMeshOptions.max_hexes", static_cast<long long>(max_hexes), 1);
  core::require_at_least("SubVolumeMeshOptions.threads", threads, 0);
}

namespace {

using core::seconds_since;

std::string sub_volume_name(int k) {
  return "Sub-volume " + std::to_string(k + 1);
}

using detail::free_face;
using detail::Part;

// A sub-volume revolved (detail/revolved_part.h) and the options it is revolved with.
detail::RevolvedPart revolved(const Part& p) {
  return {p.solid, p.origin, p.axis, p.shared_edge, p.turns};
}
RevolveOptions revolve_options(const SubVolumeMeshOptions& options) {
  RevolveOptions o;
  o.size = options.size;
  o.max_intervals = options.max_intervals;
  o.smoothing_passes = options.smoothing_passes;
  o.size_field = options.size_field;
  return o;
}

// The interval problem over the curves of `pieces` (one per non-degenerated edge).
struct Curves {
  IntervalProblem problem;
  std::map<int, int> of_edge;  // pieces edge id -> curve
};

int curve(Curves& c, const occ::Solid& pieces, int whole_edge, const SubVolumeMeshOptions& o) {
  const auto it = c.of_edge.find(whole_edge);
  if (it != c.of_edge.end()) return it->second;
  const EdgeId e(whole_edge);
  const int k = c.problem.add_curve(
      pieces.edge_length(e), core::entity_name(e),
      detail::graded(o.size_field) ? detail::edge_segments(pieces, e, o.size, o.size_field) : 0);
  c.of_edge.emplace(whole_edge, k);
  return k;
}

// What a multisweep asks of the counts of its edges: an edge at one height has the counts
// of the cross-section's edges under it, each even (regions meshed with quads need even
// edges; mapped ones accept them), an edge along the axis the layers of the slabs it spans
// (a curve per cross-section edge and per slab). The regions' own constraints stay inside
// the multisweep: it is meshed with the counts of its shared edges given (mesh_part).
void add_multisweep_constraints(Curves& c, const occ::Solid& pieces, const Part& part,
                                const std::string& who, const SubVolumeMeshOptions& o) {
  const occ::Solid& s = part.solid;
  const occ::PrismaticStructure& ps = *part.prismatic;
  std::map<int, int> arrangement_curve, slab_curve;
  auto arrangement = [&](int a) {
    auto [it, added] = arrangement_curve.emplace(a, -1);
    if (added) {
      it->second = c.problem.add_curve(ps.arrangement->edge_length(EdgeId(a)),
                                       who + " cross-section edge " + std::to_string(a));
      c.problem.even.push_back({{it->second}, who + " (multisweep): its cross-section's quads"});
    }
    return it->second;
  };
  auto slab = [&](int l) {
    auto [it, added] = slab_curve.emplace(l, -1);
    if (added)
      it->second = c.problem.add_curve(ps.levels[l + 1] - ps.levels[l],
                                       who + " slab " + std::to_string(l + 1));
    return it->second;
  };
  for (EdgeId e : s.edges()) {
    const occ::EdgeInStructure where = occ::edge_in_structure(s, ps, e);
    std::vector<int> under;
    for (int a : where.arrangement_edges) under.push_back(arrangement(a));
    for (int l : where.slabs) under.push_back(slab(l));
    if (under.empty()) continue;
    c.problem.equal.push_back({{curve(c, pieces, part.whole_edge[e.value()], o)},
                               under,
                               who + " (multisweep): " + core::entity_name(e) +
                                   (where.slabs.empty() ? ", the cross-section's edges under it"
                                                        : ", the layers of the slabs it spans")});
  }
}

// `preferences`: whole circles on unstructured sweep sources get a multiple of 4 segments,
// at least 8, as a lone sweep gives them (a round hole of 6 segments folds quads near it);
// dropped when they make the counts infeasible.
void add_constraints(Curves& c, const occ::Solid& pieces, const Part& part, int k,
                     const SubVolumeMeshOptions& o, bool preferences) {
  auto cv = [&](EdgeId e) { return curve(c, pieces, part.whole_edge[e.value()], o); };
  const std::string who = sub_volume_name(k);
  if (part.multisweep) {
    add_multisweep_constraints(c, pieces, part, who, o);
    return;
  }
  if (part.revolve) {
    detail::add_revolved_constraints(c.problem, revolved(part), cv, who);
    return;
  }
  if (part.is_block()) {
    static const char* axis[3] = {"first", "second", "third"};
    for (int d = 0; d < 3; ++d)
      for (int m = 1; m < 4; ++m)
        c.problem.equal.push_back(
            {{cv(part.block[d][0])},
             {cv(part.block[d][m])},
             who + " (mapped block): parallel edges of its " + axis[d] + " direction"});
    return;
  }
  const SweepStructure& s = part.sweep;
  // Every linking edge is a curve of the problem, also a lone one (a cylinder's seam); a
  // linking chain (a neighbour's vertices imprinted on a linking side) sums to the layers,
  // each of its edges at least one.
  auto chain = [&](const std::vector<EdgeId>& edges) {
    std::vector<int> curves;
    for (EdgeId e : edges) curves.push_back(cv(e));
    if (curves.size() > 1)
      for (int k : curves)
        c.problem.at_least.push_back({{k}, 1, who + " (sweep): a chain of linking edges"});
    return curves;
  };
  std::vector<std::vector<int>> sides;
  for (const std::vector<EdgeId>& edges : s.linking) sides.push_back(chain(edges));
  for (std::size_t i = 1; i < sides.size(); ++i)
    c.problem.equal.push_back({sides[0], sides[i], who + " (sweep): its layers"});
  // The edges between two faces of a stack of linking faces: across as the source edge
  // below, on one layer.
  for (const SweepStructure::Level& level : s.levels) {
    std::vector<int> across, below0, below1;
    for (EdgeId e : level.across) across.push_back(cv(e));
    for (EdgeId e : level.below0) below0.push_back(cv(e));
    for (EdgeId e : level.below1) below1.push_back(cv(e));
    c.problem.equal.push_back({{cv(level.source)}, across, who + " (sweep): across a stack"});
    c.problem.equal.push_back({below0, below1, who + " (sweep): a stack's edge on a layer"});
    if (across.size() > 1)
      for (int k : across)
        c.problem.at_least.push_back({{k}, 1, who + " (sweep): a chain across a stack"});
  }
  for (const auto& loop : s.loops)
    for (const auto& [src, tgt] : loop) {
      std::vector<int> across;
      std::string names;
      for (EdgeId t : tgt) {
        across.push_back(cv(t));
        names += (names.empty() ? "" : " + ") + core::entity_name(t);
      }
      c.problem.equal.push_back({{cv(src)},
                                 across,
                                 who + " (sweep): " + core::entity_name(src) + " and " + names +
                                     " across a linking face"});
      if (tgt.size() > 1)  // each edge of a chain at least one interval
        for (int a : across)
          c.problem.at_least.push_back(
              {{a}, 1, who + " (sweep): " + names + ", a chain of target edges"});
    }
  const bool grid = s.loops.size() == 1 && s.loops[0].size() == 4;
  if (grid) {
    // A four-sided source is a mapped grid (conforming with neighbours mapping it).
    for (int side = 0; side < 2; ++side)
      c.problem.equal.push_back(
          {{cv(s.loops[0][side].first)},
           {cv(s.loops[0][side + 2].first)},
           who + " (sweep): opposite sides of its source " + core::entity_name(s.source)});
    return;
  }
  // A submappable source (rectilinear outline): +u and -u sides balance, +v and -v too.
  const std::vector<int> dirs = submap_directions(part.solid, s.source);
  if (!dirs.empty() && dirs.size() == s.loops[0].size()) {
    std::vector<int> curves;
    for (const auto& st : s.loops[0]) curves.push_back(cv(st.first));
    add_submap_balance(c.problem, dirs, curves,
                       who + " (sweep): its source " + core::entity_name(s.source));
    return;
  }
  // Unstructured quads on the source: each edge even (model vertices stay coarse nodes of
  // the quad mesher), each loop at least 4 segments (6 with holes).
  for (std::size_t l = 0; l < s.loops.size(); ++l) {
    std::vector<int> loop;
    for (const auto& st : s.loops[l]) {
      loop.push_back(cv(st.first));
      c.problem.even.push_back({{cv(st.first)},
                                who + " (sweep): " + core::entity_name(st.first) +
                                    " on its source " + core::entity_name(s.source)});
      const bool circle =
          part.solid.edge_first_vertex(st.first) == part.solid.edge_last_vertex(st.first) &&
          part.solid.curve_info(st.first).kind == core::CurveKind::circle;
      if (preferences && circle) {
        const std::string why =
            who + " (sweep): " + core::entity_name(st.first) + ", a whole circle on its source,";
        c.problem.even.push_back({{cv(st.first)}, why + " in a multiple of 4 segments", 4});
        c.problem.at_least.push_back({{cv(st.first)}, 8, why + " in at least 8 segments"});
      }
    }
    c.problem.at_least.push_back({loop, s.loops.size() == 1 ? 4 : 6,
                                  who + " (sweep): loop " + std::to_string(l + 1) +
                                      " of its source " + core::entity_name(s.source)});
  }
}

// Sub-volume k of `pieces` with its scheme once glued: a mapped block, else a sweep whose
// source and target avoid the faces it shares with a neighbour where possible, else (or
// instead of a sweep with chains of target edges) a multisweep (none: has_scheme() is
// false).
Part plan_part(const occ::Solid& pieces, int k, bool multisweep, bool revolve, bool imprinted) {
  Part p(pieces.part(k));
  p.imprinted = imprinted;
  p.whole_edge = pieces.part_ids(p.solid, 1);
  p.block = map_block_edge_groups(p.solid);
  if (p.is_block()) return p;
  // A face shared with a neighbour is the sweep's target where possible: its mesh is then
  // the projection of this part's own far end, and two sweeps meeting there (a post on the
  // column under it) project congruent ends onto it the same way.
  const std::vector<int> whole_face = pieces.part_ids(p.solid, 2);
  for (std::size_t f = 1; f < whole_face.size(); ++f)
    if (whole_face[f] > 0 && pieces.face_is_interface(core::FaceId(whole_face[f])))
      p.shared_faces.push_back(int(f));
  p.whole_face = whole_face;
  p.avoid_sources = p.shared_faces;
  p.sweep = sweep_structure(p.solid, p.avoid_sources, imprinted);
  // A sweep whose target sides are chains (a neighbour's vertices imprinted there) is a
  // weaker structure than a prismatic part: the multisweep takes such a part when it can.
  bool chains = !p.sweep.levels.empty();  // a stack of linking faces: weaker still
  for (const auto& loop : p.sweep.loops)
    for (const auto& st : loop) chains = chains || st.second.size() > 1;
  for (const auto& side : p.sweep.linking) chains = chains || side.size() > 1;
  if (multisweep && (!p.sweep.source.valid() || chains)) {
    p.prismatic = std::make_shared<occ::PrismaticStructure>(occ::prismatic_structure(p.solid));
    p.multisweep = p.prismatic->ok;
    if (p.multisweep) p.sweep = SweepStructure();
  }
  if (revolve && !p.has_scheme()) {
    const RevolveApplicability a = revolve_applicable(p.solid);
    p.revolve = a.ok;
    p.origin = a.origin;
    p.axis = a.axis;
    if (p.revolve) p.turns = detail::turns_about_axis(p.solid, p.origin, p.axis);
  }
  return p;
}

std::string no_scheme_message(const Part& p, int k, int n) {
  const Applicability map = map_block_applicable(p.solid);
  const SweepApplicability sw = sweep_applicable(p.solid);
  const std::string prismatic = p.prismatic ? p.prismatic->reason : "not tried";
  return sub_volume_name(k) + " of " + std::to_string(n) + " is neither a mapped block (" +
         map.reason + "), a sweep (" + sw.reason + ") nor prismatic (" + prismatic +
         ") once glued to its neighbours.";
}

// The nodes of a part's mesh on its edge e, first to last vertex (by their distance along
// the edge; a closed edge's vertex first and last); empty for a degenerated edge.
std::vector<core::Vec3> nodes_on_edge(const core::HexMesh& mesh, const occ::Solid& solid,
                                      EdgeId e) {
  std::vector<core::Vec3> out;
  const core::VertexId v0 = solid.edge_first_vertex(e), v1 = solid.edge_last_vertex(e);
  if (solid.edge_is_degenerated(e)) return out;
  const std::vector<core::Vec3> line = solid.edge_points_by_length(e, 256);
  std::vector<std::pair<double, core::Vec3>> along;
  for (std::size_t i = 0; i < mesh.num_nodes(); ++i) {
    const core::NodeClass c = mesh.node_classes()[i];
    const bool on = (c.dim == 1 && c.id == e.value()) ||
                    (c.dim == 0 && (c.id == v0.value() || c.id == v1.value()));
    if (!on) continue;
    const core::Vec3& x = mesh.points()[i];
    double best = 1e300, t = 0;
    for (std::size_t k = 0; k + 1 < line.size(); ++k) {
      const core::Vec3 d = line[k + 1] - line[k];
      const double s =
          std::clamp((x - line[k]).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
      const double dist = (line[k] + s * d - x).squaredNorm();
      if (dist < best) best = dist, t = double(k) + s;
    }
    along.emplace_back(t, x);
  }
  std::sort(along.begin(), along.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [t, x] : along) out.push_back(x);
  // A closed edge (a circle): its vertex, found at its start, ends it too (its nodes were
  // never given: a cam's chamfer slab took the multisweep's quads on its cap but spaced the
  // rim's circle from its own vertex, and the two did not match).
  if (v0 == v1 && out.size() >= 2) out.push_back(solid.vertex_point(v0));
  return out;
}

// Meshes one part with the assigned counts (by its own edge ids).
struct PartMesh {
  core::HexMesh mesh;
  bool ok = false;
  std::vector<core::Diagnostic> diagnostics;
};

// `edge_nodes`: per part edge id, the nodes a neighbour meshed before it placed there
// (empty: none yet).
PartMesh mesh_part(const Part& part, const std::vector<int>& counts,
                   const SubVolumeMeshOptions& options, const core::Progress& progress,
                   const std::vector<std::vector<core::Vec3>>& edge_nodes = {},
                   const std::vector<std::array<core::Vec3, 4>>& source_quads = {},
                   const std::vector<std::array<core::Vec3, 4>>& target_quads = {}) {
  PartMesh out;
  if (part.multisweep) {
    // Only the counts of shared edges are given: its cross-section chooses the others.
    MultisweepOptions o;
    o.edge_nodes = edge_nodes;
    o.size = options.size;
    o.max_intervals = options.max_intervals;
    o.smoothing_passes = options.smoothing_passes;
    o.size_field = options.size_field;
    o.edge_intervals.assign(counts.size(), 0);
    for (std::size_t e = 1; e < counts.size(); ++e)
      if (part.shared_edge[e]) o.edge_intervals[e] = counts[e];
    MultisweepResult r = multisweep(part.solid, o, progress);
    out.ok = r.ok;
    out.mesh = std::move(r.mesh);
    out.diagnostics = std::move(r.diagnostics);
  } else if (part.revolve) {
    RevolveResult r = detail::mesh_revolved(revolved(part), revolve_options(options), counts,
                                            edge_nodes, progress);
    out.ok = r.ok;
    out.mesh = std::move(r.mesh);
    out.diagnostics = std::move(r.diagnostics);
  } else if (part.is_block()) {
    MapBlockOptions o;
    o.size = options.size;
    o.max_intervals = options.max_intervals;
    o.edge_intervals = counts;
    o.size_field = options.size_field;
    o.edge_nodes = edge_nodes;
    MapBlockResult r = map_block(part.solid, o, progress);
    out.ok = r.ok;
    out.mesh = std::move(r.mesh);
    out.diagnostics = std::move(r.diagnostics);
  } else {
    SweepOptions o;
    o.size = options.size;
    o.max_intervals = options.max_intervals;
    o.smoothing_passes = options.smoothing_passes;
    o.edge_intervals = counts;
    o.avoid_sources = part.avoid_sources;
    o.size_field = options.size_field;
    o.edge_nodes = edge_nodes;
    o.source_quads = source_quads;
    o.target_quads = target_quads;
    o.imprinted = part.imprinted;
    SweepResult r = sweep(part.solid, o, progress);
    if (!r.ok && r.folded > 0 && !progress.cancelled()) {  // the target's nodes along the axis
      SweepOptions along_axis = o;
      along_axis.target_along_axis = true;
      SweepResult along = sweep(part.solid, along_axis, progress);
      if (along.ok || (along.folded > 0 && along.folded < r.folded)) r = std::move(along);
    }
    if (!r.ok && r.folded > 0 && !progress.cancelled()) {  // each layer within its boundary
      SweepOptions smoothed = o;
      smoothed.smooth_layers = true;
      SweepResult other = sweep(part.solid, smoothed, progress);
      if (other.ok || (other.folded > 0 && other.folded < r.folded)) r = std::move(other);
    }
    // Folded layers: untangled with the nodes on the faces shared with a neighbour kept
    // (both meshes of a shared face must stay the same).
    if (!r.ok && r.folded > 0 && !progress.cancelled()) {
      std::set<int> faces(part.shared_faces.begin(), part.shared_faces.end()), edges;
      for (int f : part.shared_faces)
        for (const auto& wire : part.solid.face_wires(core::FaceId(f)))
          for (const core::OrientedEdge& oe : wire) edges.insert(oe.edge.value());
      std::vector<char> fixed(r.mesh.num_nodes(), 0);
      for (std::size_t i = 0; i < fixed.size(); ++i) {
        const core::NodeClass c = r.mesh.node_classes()[i];
        fixed[i] = (c.dim == 2 && faces.count(c.id)) || (c.dim == 1 && edges.count(c.id));
      }
      if (smooth::untangle_folded(r.mesh, part.solid, fixed, options.size_field, progress))
        accept_untangled(r);
    }
    out.ok = r.ok;
    out.mesh = std::move(r.mesh);
    out.diagnostics = std::move(r.diagnostics);
  }
  return out;
}

}  // namespace

SubVolumeMeshResult mesh_sub_volumes(const occ::Solid& pieces, const SubVolumeMeshOptions& options,
                                     const core::Progress& progress) {
  options.validate();
  SubVolumeMeshResult result;
  const int n = pieces.num_solids();
  progress.report("sub_volumes", 0.0);

  // Schemes.
  std::vector<Part> parts;
  parts.reserve(n);
  for (int k = 0; k < n; ++k) {
    Part p = plan_part(pieces, k, options.multisweep, options.revolve, true);
    if (!p.has_scheme()) {
      result.diagnostics.push_back(
          core::make_error("no_scheme", no_scheme_message(p, k, n), {sub_volume_name(k)}));
      return result;
    }
    result.stats.schemes.push_back(p.scheme());
    auto shared = [&](core::FaceId f) {
      return std::find(p.shared_faces.begin(), p.shared_faces.end(), f.value()) !=
             p.shared_faces.end();
    };
    const bool own_ends = p.multisweep
                              ? p.shared_faces.empty()
                              : p.is_sweep() && !shared(p.sweep.source) && !shared(p.sweep.target);
    result.stats.types.push_back(own_ends ? "Vs" : "Ve");
    parts.push_back(std::move(p));
  }
  // Which way each sweep goes, so that the faces they share are meshed once.
  detail::orient_sweeps(parts);

  // Edges a neighbour has too (their counts are given to a multisweep).
  {
    std::map<int, int> parts_of_edge;
    for (const Part& p : parts)
      for (std::size_t e = 1; e < p.whole_edge.size(); ++e) ++parts_of_edge[p.whole_edge[e]];
    for (Part& p : parts) {
      p.shared_edge.assign(p.whole_edge.size(), false);
      for (std::size_t e = 1; e < p.whole_edge.size(); ++e)
        p.shared_edge[e] = parts_of_edge[p.whole_edge[e]] > 1;
    }
  }

  const auto t0 = std::chrono::steady_clock::now();
  // One interval assignment for all of them (without the preferences if they make it
  // infeasible).
  IntervalOptions io;
  io.size = options.size;
  io.max_intervals = options.max_intervals;
  io.time_limit = options.interval_time_limit;
  Curves curves;
  IntervalResult assigned;
  for (bool preferences : {true, false}) {
    curves = Curves();
    for (int k = 0; k < n; ++k) add_constraints(curves, pieces, parts[k], k, options, preferences);
    assigned = assign_intervals(curves.problem, io);
    if (assigned.ok()) break;
  }
  result.stats.curves = int(curves.problem.lengths.size());
  result.stats.constraints = int(curves.problem.equal.size() + curves.problem.even.size() +
                                 curves.problem.at_least.size());
  result.stats.seconds_intervals = seconds_since(t0);
  result.diagnostics.insert(result.diagnostics.end(), assigned.diagnostics.begin(),
                            assigned.diagnostics.end());
  if (!assigned.ok()) return result;
  result.stats.interval_deviation = assigned.deviation;
  progress.report("sub_volumes", 0.1);

  // Counts per part edge id; hexes predicted from them.
  std::vector<std::vector<int>> counts(n);
  std::size_t predicted = 0;
  for (int k = 0; k < n; ++k) {
    const Part& p = parts[k];
    counts[k].assign(p.whole_edge.size(), 0);
    for (std::size_t e = 1; e < p.whole_edge.size(); ++e) {
      const auto it = curves.of_edge.find(p.whole_edge[e]);
      if (it != curves.of_edge.end()) counts[k][e] = assigned.intervals[it->second];
    }
    if (p.multisweep) {
      MultisweepOptions o;
      o.size = options.size;
      o.smoothing_passes = 0;
      o.size_field = options.size_field;
      o.edge_intervals.assign(counts[k].size(), 0);
      for (std::size_t e = 1; e < counts[k].size(); ++e)
        if (p.shared_edge[e]) o.edge_intervals[e] = counts[k][e];
      predicted += multisweep_evaluate(p.solid, o).hexes;
    } else if (p.revolve) {
      predicted += revolve_evaluate(p.solid, detail::revolved_options(
                                                 revolved(p), revolve_options(options), counts[k]))
                       .hexes;
    } else if (p.is_block()) {
      predicted += std::size_t(counts[k][p.block[0][0].value()]) *
                   counts[k][p.block[1][0].value()] * counts[k][p.block[2][0].value()];
    } else {
      SweepOptions o;
      o.size = options.size;
      o.smoothing_passes = 0;
      o.edge_intervals = counts[k];
      o.size_field = options.size_field;
      predicted += sweep_evaluate(p.solid, o).hexes;
    }
  }
  if (predicted > options.max_hexes) {
    std::ostringstream s;
    s << "The sub-volumes' meshes would have about " << predicted
      << " hexahedra, more than max_hexes = " << options.max_hexes
      << "; increase the size or the limit.";
    result.diagnostics.push_back(core::make_error("too_many_hexes", s.str()));
    return result;
  }

  // Mesh the parts, several at once; only this thread reports progress (the callback may
  // be Python's), workers see a cancel flag it sets.
  const auto t1 = std::chrono::steady_clock::now();
  std::atomic<bool> stop{false};
  const core::Progress worker_progress([](std::string_view, double) {}, &stop);
  std::vector<PartMesh> meshed(n);
  // Multisweeps first, one after the other: each takes the nodes the ones before it placed
  // on the edges they share (a cross-section splits an edge where a neighbour's does not);
  // those that split shared edges most go first. Blocks and sweeps then take the nodes the
  // multisweeps placed on the edges they share with them.
  std::map<int, std::vector<core::Vec3>> placed;  // whole edge id -> nodes
  auto given_to = [&](const Part& p) {
    std::vector<std::vector<core::Vec3>> given(p.whole_edge.size());
    for (std::size_t e = 1; e < p.whole_edge.size(); ++e) {
      const auto it = placed.find(p.whole_edge[e]);
      if (it == placed.end()) continue;
      given[e] = it->second;
      const EdgeId edge{int(e)};
      const core::Vec3 first = p.solid.vertex_point(p.solid.edge_first_vertex(edge));
      bool reverse = (given[e].front() - first).norm() > (given[e].back() - first).norm();
      // A closed edge runs this part's way round where its second node is nearer this
      // part's own second point than its last but one.
      const std::size_t n = given[e].size() - 1;
      if (n >= 2 && p.solid.edge_first_vertex(edge) == p.solid.edge_last_vertex(edge)) {
        const std::vector<core::Vec3> own = p.solid.edge_points_by_length(edge, int(n));
        reverse = (given[e][1] - own[1]).norm() > (given[e][1] - own[n - 1]).norm();
      }
      if (reverse) std::reverse(given[e].begin(), given[e].end());
    }
    return given;
  };
  {
    auto splits = [&](const Part& p) {
      int k = 0;
      for (EdgeId e : p.solid.edges()) {
        if (!p.shared_edge[e.value()]) continue;
        const occ::EdgeInStructure w = occ::edge_in_structure(p.solid, *p.prismatic, e);
        k += w.arrangement_edges.size() > 1 || w.slabs.size() > 1;
      }
      return k;
    };
    // (-splits, part); solids of revolution after them, taking their nodes on the seams they
    // share (a multisweep's slabs put nodes at its levels there), before the others.
    std::vector<std::pair<int, int>> order;
    for (int k = 0; k < n; ++k)
      if (parts[k].multisweep || parts[k].revolve)
        order.emplace_back(parts[k].revolve ? std::numeric_limits<int>::max() : -splits(parts[k]),
                           k);
    std::sort(order.begin(), order.end());
    for (const auto& [ignored, k] : order) {
      const Part& p = parts[k];
      try {
        meshed[k] = mesh_part(p, counts[k], options, progress, given_to(p));
      } catch (const std::exception& e) {
        meshed[k].diagnostics.push_back(core::make_error("geometry_error", e.what()));
      }
      if (!meshed[k].ok) break;  // reported at the join
      for (std::size_t e = 1; e < p.whole_edge.size(); ++e)
        if (p.shared_edge[e] && !placed.count(p.whole_edge[e])) {
          // A revolved part's circles stay its own (a gear blank's web, given the rings'
          // circles, no longer quad-meshed at any size).
          const EdgeId edge{int(e)};
          if (p.revolve && p.solid.edge_first_vertex(edge) == p.solid.edge_last_vertex(edge))
            continue;
          std::vector<core::Vec3> nodes = nodes_on_edge(meshed[k].mesh, p.solid, edge);
          if (nodes.size() >= 2) placed.emplace(p.whole_edge[e], std::move(nodes));
        }
    }
  }
  // The other shared edges' nodes placed once, on the glued sub-volumes (each part alone
  // would space them by its own faces: an edge's end at a cusp of one part's face is widened
  // there, and not in its neighbour's, so a keyed shaft's block and sweep placed different
  // nodes on the curve where the keyway's round end meets the shaft).
  for (int k = 0; k < n; ++k) {
    const Part& p = parts[k];
    if (p.multisweep || p.revolve) continue;
    for (std::size_t e = 1; e < p.whole_edge.size(); ++e) {
      const int whole = p.whole_edge[e];
      if (!p.shared_edge[e] || placed.count(whole) || counts[k][e] < 1) continue;
      if (pieces.edge_is_degenerated(EdgeId(whole)) ||
          pieces.edge_first_vertex(EdgeId(whole)) == pieces.edge_last_vertex(EdgeId(whole)))
        continue;  // closed: each part starts it at its own vertex
      std::vector<core::Vec3> nodes =
          detail::edge_points(pieces, EdgeId(whole), counts[k][e], options.size_field);
      if (nodes.size() >= 2) placed.emplace(whole, std::move(nodes));
    }
  }
  std::vector<std::vector<std::vector<core::Vec3>>> given(n);
  for (int k = 0; k < n; ++k)
    if (!parts[k].multisweep && !parts[k].revolve && !placed.empty()) given[k] = given_to(parts[k]);
  // A sweep's source or target that a multisweep meshed (a cap, or a wall: a sweep bridging
  // two multisweeps, as across a pulley's keyway): its quads there (the boundary quads of the
  // multisweep's mesh whose corners lie on that face or its edges and vertices).
  std::vector<std::vector<std::array<core::Vec3, 4>>> given_source(n), given_target(n);
  auto local_face = [&](int j, int whole) {  // part j's face that is `whole` (invalid: none)
    for (std::size_t f = 1; f < parts[j].whole_face.size(); ++f)
      if (parts[j].whole_face[f] == whole) return core::FaceId(int(f));
    return core::FaceId();
  };
  auto multisweep_quads = [&](int whole) {
    for (int j = 0; j < n; ++j) {
      if (!parts[j].multisweep || !meshed[j].ok) continue;
      if (const core::FaceId f = local_face(j, whole); f.valid())
        return detail::quads_on_face(meshed[j].mesh, parts[j].solid, f);
    }
    return std::vector<std::array<core::Vec3, 4>>();
  };
  for (int k = 0; k < n; ++k) {
    if (!parts[k].is_sweep()) continue;
    given_source[k] = multisweep_quads(parts[k].whole_face[parts[k].sweep.source.value()]);
    given_target[k] = multisweep_quads(parts[k].whole_face[parts[k].sweep.target.value()]);
  }
  // A sweep whose source, meshed freely, is another sweep's target (a stack of slabs: a block,
  // and slabs cut at a chamfer's and a fillet's feet at two heights) takes that sweep's quads
  // there as its source, so it is meshed after it (below); each of the others on its own.
  std::vector<int> after(n, -1);
  for (int k = 0; k < n; ++k) {
    if (!parts[k].is_sweep() || !given_source[k].empty() ||
        !free_face(parts[k].solid, parts[k].sweep.source))
      continue;
    const int face = parts[k].whole_face[parts[k].sweep.source.value()];
    for (int j = 0; j < n && after[k] < 0; ++j)
      if (j != k && parts[j].is_sweep() &&
          parts[j].whole_face[parts[j].sweep.target.value()] == face)
        after[k] = j;
  }
  // A ring of such sweeps (each one's source the one before's target): one of them meshes its
  // source freely, and the one before it takes those quads as its target.
  std::vector<int> target_from(n, -1);
  for (int k = 0; k < n; ++k) {
    int j = after[k];
    for (int steps = 0; j >= 0 && j != k && steps < n; ++steps) j = after[j];
    if (j != k) continue;
    target_from[after[k]] = k;
    after[k] = -1;
  }
  // Where a sweep's source or target is another sweep's or a block's face (not one whose
  // quads it gives it above), it takes that part's quads there, so it is meshed after it: a
  // linking side of the other's, a block's face, or the other's target (source) as its target
  // (source), the later sweep taking the earlier's. Each of the two sweeping its own quads
  // onto the face did not match: a keyed shaft's 1-thick chamfer slab swept from its end face
  // to the face of the strip above it, which that strip's sweep meshed as a linking side.
  auto waits_on = [&](int from, int on) {  // `from` is meshed after `on` (the chains above)
    std::vector<int> stack{from};
    std::vector<char> seen(n, 0);
    while (!stack.empty()) {
      const int x = stack.back();
      stack.pop_back();
      if (x == on) return true;
      if (x < 0 || seen[x]) continue;
      seen[x] = 1;
      stack.push_back(after[x]);
      stack.push_back(target_from[x]);
    }
    return false;
  };
  for (int k = 0; k < n; ++k) {
    if (!parts[k].is_sweep()) continue;
    for (const bool source : {true, false}) {
      int& from = source ? after[k] : target_from[k];
      if (from >= 0 || !(source ? given_source[k] : given_target[k]).empty()) continue;
      const int whole =
          parts[k].whole_face[(source ? parts[k].sweep.source : parts[k].sweep.target).value()];
      for (int j = 0; j < n && from < 0; ++j) {
        if (j == k || parts[j].multisweep || parts[j].revolve) continue;
        const core::FaceId f = local_face(j, whole);
        if (!f.valid()) continue;
        if (parts[j].is_sweep() && (f == parts[j].sweep.source || f == parts[j].sweep.target)) {
          // The other's source where this is the target, or its target where this is the
          // source: the chains above, or that one takes this one's quads.
          const bool same_end = (f == parts[j].sweep.source) == source;
          if (!same_end || j > k) continue;
        }
        if (!waits_on(j, k)) from = j;
      }
    }
  }
  std::atomic<int> next{0};
  const int threads = std::max(
      1, std::min(n, options.threads > 0 ? options.threads
                                         : int(std::max(1u, std::thread::hardware_concurrency()))));
  auto work = [&] {
    for (int k; (k = next.fetch_add(1)) < n;) {
      if (stop.load()) break;
      if (parts[k].multisweep || parts[k].revolve || after[k] >= 0 || target_from[k] >= 0)
        continue;  // meshed above, or below
      try {
        meshed[k] = mesh_part(parts[k], counts[k], options, worker_progress, given[k],
                              given_source[k], given_target[k]);
      } catch (const std::exception& e) {
        meshed[k].diagnostics.push_back(core::make_error("geometry_error", e.what()));
      }
    }
  };
  std::vector<std::future<void>> running;
  for (int t = 0; t < threads; ++t) running.push_back(std::async(std::launch::async, work));
  for (auto& f : running)
    while (f.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
      if (progress.cancelled()) stop = true;
      progress.report("sub_volumes", 0.1 + 0.8 * std::min(1.0, double(next.load()) / n));
    }
  // The stacked sweeps, each once the one below it is meshed (a chain: as many passes), and
  // the sweeps taking another part's quads on their source or target.
  auto quads_from = [&](int j, core::FaceId own, const Part& p) {
    return detail::quads_on_face(meshed[j].mesh, parts[j].solid,
                                 local_face(j, p.whole_face[own.value()]));
  };
  std::vector<char> waiting(n, 0);
  for (int k = 0; k < n; ++k)
    waiting[k] =
        !parts[k].multisweep && !parts[k].revolve && (after[k] >= 0 || target_from[k] >= 0);
  for (bool progressed = true; progressed && !stop.load() && !progress.cancelled();) {
    progressed = false;
    for (int k = 0; k < n; ++k) {
      const int j = after[k], t = target_from[k];
      if (!waiting[k] || (j >= 0 && !meshed[j].ok) || (t >= 0 && !meshed[t].ok)) continue;
      if (j >= 0) given_source[k] = quads_from(j, parts[k].sweep.source, parts[k]);
      if (t >= 0) given_target[k] = quads_from(t, parts[k].sweep.target, parts[k]);
      try {
        meshed[k] = mesh_part(parts[k], counts[k], options, worker_progress, given[k],
                              given_source[k], given_target[k]);
      } catch (const std::exception& e) {
        meshed[k].diagnostics.push_back(core::make_error("geometry_error", e.what()));
      }
      waiting[k] = 0;
      progressed = true;
    }
  }
  for (int k = 0; k < n; ++k)  // the one it waits on failed (or the two wait on each other)
    if (waiting[k] && !meshed[k].ok) {
      const int j = after[k] >= 0 && !meshed[after[k]].ok ? after[k] : target_from[k];
      meshed[k].diagnostics.push_back(core::make_error(
          "sub_volume_not_meshed", "it takes the quads of " + sub_volume_name(j) + " on its " +
                                       (j == after[k] ? "source" : "target") +
                                       ", which was not meshed, so it was not meshed either"));
    }
  result.stats.seconds_meshing = seconds_since(t1);
  if (stop.load() || progress.cancelled()) {
    result.diagnostics.push_back(
        core::make_error("cancelled", "Meshing the sub-volumes was cancelled."));
    return result;
  }

  // Join.
  const double tolerance = std::max(1e-9 * pieces.diagonal(), pieces.tolerance());
  bool all = true;
  for (int k = 0; k < n; ++k) {
    for (core::Diagnostic d : meshed[k].diagnostics) {
      d.message = sub_volume_name(k) + " (" + result.stats.schemes[k] + "): " + d.message;
      result.diagnostics.push_back(std::move(d));
    }
    if (!meshed[k].ok) {
      all = false;
      bool own = false;
      for (const core::Diagnostic& d : meshed[k].diagnostics)
        own = own || (d.severity == core::Severity::error && d.code != "sub_volume_not_meshed");
      if (own) result.failed.push_back(k);
      continue;
    }
    result.stats.nodes_merged +=
        append_part(result.mesh, pieces, meshed[k].mesh, parts[k].solid, k + 1, tolerance)
            .nodes_merged;
    meshed[k].mesh = core::HexMesh();  // memory back as soon as it is joined
  }
  if (!all) {
    result.mesh = core::HexMesh();
    return result;
  }
  progress.report("sub_volumes", 1.0);
  result.ok = true;
  return result;
}

SubVolumePlan plan_sub_volumes(const occ::Solid& pieces, bool multisweep, bool revolve,
                               bool imprinted) {
  SubVolumePlan plan;
  const int n = pieces.num_solids();
  plan.ok = n > 0;
  for (int k = 0; k < n; ++k) {
    const Part p = plan_part(pieces, k, multisweep, revolve, imprinted);
    if (p.has_scheme()) {
      plan.schemes.push_back(p.scheme());
      plan.reasons.emplace_back();
      continue;
    }
    plan.schemes.emplace_back();
    plan.reasons.push_back(no_scheme_message(p, k, n));
    if (plan.ok) plan.why_not = plan.reasons.back();
    plan.ok = false;
  }
  return plan;
}

}  // namespace vorohex::mesh
