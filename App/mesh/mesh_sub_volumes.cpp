#include "mesh/mesh_sub_volumes.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <future>
#include <map>
#include <sstream>
#include <thread>

#include "core/option_checks.h"
#include "mesh/assemble.h"
#include "mesh/detail/sizing.h"
#include "mesh/interval_assignment.h"
#include "mesh/map_block.h"
#include "mesh/submap_face.h"
#include "mesh/sweep.h"

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

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string sub_volume_name(int k) {
  return "Sub-volume " + std::to_string(k + 1);
}

// One sub-volume: its solid, its scheme's structure, and its edge ids in `pieces`.
struct Part {
  occ::Solid solid;
  std::array<std::vector<EdgeId>, 3> block;  // non-empty: mapped block
  SweepStructure sweep;                      // else: sweep
  std::vector<int> shared_faces;             // part face ids shared with a neighbour
  std::vector<int> whole_edge;               // by part edge id
  bool is_block() const { return !block[0].empty(); }
  bool has_scheme() const { return is_block() || sweep.source.valid(); }
  const char* scheme() const { return is_block() ? "map" : "sweep"; }
};

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

void add_constraints(Curves& c, const occ::Solid& pieces, const Part& part, int k,
                     const SubVolumeMeshOptions& o) {
  auto cv = [&](EdgeId e) { return curve(c, pieces, part.whole_edge[e.value()], o); };
  const std::string who = sub_volume_name(k);
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
  // Every linking edge is a curve of the problem, also a lone one (a cylinder's seam).
  if (!s.linking.empty()) cv(s.linking[0]);
  for (std::size_t i = 1; i < s.linking.size(); ++i)
    c.problem.equal.push_back(
        {{cv(s.linking[0])}, {cv(s.linking[i])}, who + " (sweep): its layers"});
  for (const auto& loop : s.loops)
    for (const auto& [src, tgt] : loop)
      c.problem.equal.push_back({{cv(src)},
                                 {cv(tgt)},
                                 who + " (sweep): " + core::entity_name(src) + " and " +
                                     core::entity_name(tgt) + " across a linking face"});
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
    }
    c.problem.at_least.push_back({loop, s.loops.size() == 1 ? 4 : 6,
                                  who + " (sweep): loop " + std::to_string(l + 1) +
                                      " of its source " + core::entity_name(s.source)});
  }
}

// Sub-volume k of `pieces` with its scheme once glued: a mapped block, else a sweep whose
// source and target avoid the faces it shares with a neighbour where possible (neither:
// has_scheme() is false).
Part plan_part(const occ::Solid& pieces, int k) {
  Part p{pieces.part(k), {}, {}, {}, {}};
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
  p.sweep = sweep_structure(p.solid, p.shared_faces);
  return p;
}

std::string no_scheme_message(const Part& p, int k, int n) {
  const Applicability map = map_block_applicable(p.solid);
  const SweepApplicability sw = sweep_applicable(p.solid);
  return sub_volume_name(k) + " of " + std::to_string(n) + " is neither a mapped block (" +
         map.reason + ") nor a sweep (" + sw.reason + ") once glued to its neighbours.";
}

// Meshes one part with the assigned counts (by its own edge ids).
struct PartMesh {
  core::HexMesh mesh;
  bool ok = false;
  std::vector<core::Diagnostic> diagnostics;
};

PartMesh mesh_part(const Part& part, const std::vector<int>& counts,
                   const SubVolumeMeshOptions& options, const core::Progress& progress) {
  PartMesh out;
  if (part.is_block()) {
    MapBlockOptions o;
    o.size = options.size;
    o.max_intervals = options.max_intervals;
    o.edge_intervals = counts;
    o.size_field = options.size_field;
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
    o.avoid_sources = part.shared_faces;
    o.size_field = options.size_field;
    SweepResult r = sweep(part.solid, o, progress);
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
    Part p = plan_part(pieces, k);
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
    const bool own_ends = !p.is_block() && !shared(p.sweep.source) && !shared(p.sweep.target);
    result.stats.types.push_back(own_ends ? "Vs" : "Ve");
    parts.push_back(std::move(p));
  }

  // One interval assignment for all of them.
  const auto t0 = std::chrono::steady_clock::now();
  Curves curves;
  for (int k = 0; k < n; ++k) add_constraints(curves, pieces, parts[k], k, options);
  result.stats.curves = int(curves.problem.lengths.size());
  result.stats.constraints = int(curves.problem.equal.size() + curves.problem.even.size() +
                                 curves.problem.at_least.size());
  IntervalOptions io;
  io.size = options.size;
  io.max_intervals = options.max_intervals;
  io.time_limit = options.interval_time_limit;
  IntervalResult assigned = assign_intervals(curves.problem, io);
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
    if (p.is_block()) {
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
  std::atomic<int> next{0};
  const int threads = std::max(
      1, std::min(n, options.threads > 0 ? options.threads
                                         : int(std::max(1u, std::thread::hardware_concurrency()))));
  auto work = [&] {
    for (int k; (k = next.fetch_add(1)) < n;) {
      if (stop.load()) break;
      try {
        meshed[k] = mesh_part(parts[k], counts[k], options, worker_progress);
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

SubVolumePlan plan_sub_volumes(const occ::Solid& pieces) {
  SubVolumePlan plan;
  const int n = pieces.num_solids();
  plan.ok = n > 0;
  for (int k = 0; k < n; ++k) {
    const Part p = plan_part(pieces, k);
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
