#include "mesh/sweep.h"

#include "core/option_checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "mesh/detail/cad_lookup.h"
#include "mesh/detail/grid_face.h"
#include "mesh/detail/quad_quality.h"
#include "mesh/detail/shared_face_mesh.h"
#include "mesh/detail/sizing.h"
#include "mesh/detail/sweep_layers.h"
#include "mesh/detail/sweep_source.h"
#include "mesh/detail/sweep_topology.h"
#include "mesh/interval_assignment.h"
#include "mesh/quad_face.h"
#include "mesh/submap_face.h"
#include "quality/scaled_jacobian.h"

namespace vorohex::mesh {

using core::EdgeId;
using core::FaceId;
using core::NodeClass;
using core::OrientedEdge;
using core::Vec3;
using core::VertexId;
using Solid = core::MeshDomain;
using detail::AffineFit;

// The smoothed layers' sweep is kept only from this scaled Jacobian up (SweepOptions::
// smooth_layers), as an untangled one is (smooth::untangle_folded).
constexpr double kSmoothedLayersQuality = 0.3;
// Nodes (per layer times layers) beyond which the layers are not deformed (each of the four
// steps per layer takes up to 200 sweeps over a layer's nodes): the sweeps the tapered holes
// need have a few thousand; sub-volumes of HexMe's industrial models that fold have more, and
// their decompositions' time went to it (i13 33 -> 48 s).
constexpr double kSmoothedLayersNodes = 200'000;

void SweepOptions::validate() const {
  core::require_positive("SweepOptions.size", size);
  core::require_at_least("SweepOptions.max_intervals", max_intervals, 1);
  core::require_at_least("SweepOptions.smoothing_passes", smoothing_passes, 0);
}

namespace {

using detail::Directed;
using detail::Link;
using Topology = detail::SweepTopology;
using detail::chain_edges;

std::string name(FaceId f) {
  return core::entity_name(f);
}
std::string name(EdgeId e) {
  return core::entity_name(e);
}

std::vector<Vec3> read_edge(const Solid& s, const Directed& d, int n, const core::SizeField* field,
                            const std::vector<std::vector<Vec3>>& given = {}) {
  auto pts = detail::edge_points(s, d.edge, n, field, given);
  if (!d.forward) std::reverse(pts.begin(), pts.end());
  return pts;
}

// Intervals of each edge of a target chain for `n` along the source edge: the given counts
// (edge_intervals), or n split in proportion to each edge's own count at the size (each at
// least 1; largest remainders first). Empty when n is less than the chain's edges.
std::vector<int> chain_counts(const Solid& s, const std::vector<Directed>& chain, int n,
                              const SweepOptions& o) {
  if (chain.size() == 1) return {n};
  if (n < int(chain.size())) return {};
  std::vector<int> out;
  if (!o.edge_intervals.empty()) {
    for (const Directed& d : chain)
      out.push_back(d.edge.value() < int(o.edge_intervals.size()) ? o.edge_intervals[d.edge.value()]
                                                                  : 0);
    return out;
  }
  std::vector<double> want;
  double total = 0;
  for (const Directed& d : chain) {
    want.push_back(std::max(1e-9, detail::edge_segments(s, d.edge, o.size, o.size_field)));
    total += want.back();
  }
  std::vector<std::pair<double, std::size_t>> rest;
  int used = 0;
  for (std::size_t c = 0; c < chain.size(); ++c) {
    const double x = 1 + (n - int(chain.size())) * want[c] / total;
    out.push_back(int(std::floor(x)));
    used += out.back();
    rest.push_back({x - std::floor(x), c});
  }
  std::sort(rest.begin(), rest.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t r = 0; used < n; ++r, ++used) ++out[rest[r % rest.size()].second];
  return out;
}

// The nodes along a target chain (n + 1 points, its vertices among them) and, per node, the
// entity it lies on (the inner vertices of the chain, else the edge).
std::vector<Vec3> read_chain(const Solid& s, const std::vector<Directed>& chain,
                             const std::vector<int>& counts, const core::SizeField* field,
                             const std::vector<std::vector<Vec3>>& given,
                             std::vector<NodeClass>& classes) {
  std::vector<Vec3> out;
  classes.clear();
  for (std::size_t c = 0; c < chain.size(); ++c) {
    const Directed& d = chain[c];
    const auto pts = read_edge(s, d, counts[c], field, given);
    // The vertex where this edge starts ends the previous one: a node of its own.
    if (c > 0)
      classes.back() =
          NodeClass::on(d.forward ? s.edge_first_vertex(d.edge) : s.edge_last_vertex(d.edge));
    for (std::size_t m = c == 0 ? 0 : 1; m < pts.size(); ++m) {
      out.push_back(pts[m]);
      classes.push_back(NodeClass::on(d.edge));
    }
  }
  return out;
}

struct Plan {
  bool ok = false;
  Topology topo;
  int layers = 0;
  // Source (and target) meshed by transfinite interpolation: grid[0] x grid[1] segments
  // (0 when the source went through quad_face).
  std::array<int, 2> grid{0, 0};
  // Source (and target) submapped: the direction of each source edge (empty otherwise).
  std::vector<int> submap;
  bool source_given = false;             // the source's quads are SweepOptions::source_quads
  std::vector<std::vector<int>> counts;  // intervals per source loop edge
  // Per source loop edge: the intervals of each target edge across (one, or a chain's).
  std::vector<std::vector<std::vector<int>>> target_counts;
  std::vector<std::vector<Vec3>> source_loops;  // source boundary nodes per loop
  QuadFaceMesh source_mesh;
  std::vector<core::Diagnostic> diagnostics;
};

// Each target chain's intervals for its source edge's count (Plan::target_counts); false
// with the diagnostic when a count is less than the edges across it.
bool set_target_counts(const Solid& solid, const SweepOptions& options, Plan& p) {
  const Topology& t = p.topo;
  p.target_counts.assign(t.loops.size(), {});
  for (std::size_t l = 0; l < t.loops.size(); ++l)
    for (std::size_t e = 0; e < t.loops[l].size(); ++e) {
      const Link& link = t.loops[l][e];
      p.target_counts[l].push_back(chain_counts(solid, link.target, p.counts[l][e], options));
      if (p.target_counts[l].back().empty()) {
        p.diagnostics.push_back(
            core::make_error("too_few_intervals",
                             name(link.source.edge) + " has " + std::to_string(p.counts[l][e]) +
                                 " intervals, fewer than the edges across " + name(link.face),
                             {name(link.source.edge)}));
        return false;
      }
    }
  return true;
}

// The source by the general quad mesher (any face, holes included); false with its
// diagnostics when it fails.
bool mesh_source_unstructured(const Solid& solid, const SweepOptions& options, Plan& p) {
  if (!options.source_quads.empty() &&
      detail::source_from_quads(solid, p.topo.source, p.source_loops, options.source_quads,
                                1e-6 * options.size, p.source_mesh)) {
    p.source_given = true;
    return true;
  }
  QuadFaceOptions qo;
  qo.size = options.size;
  qo.smoothing_passes = options.smoothing_passes;
  qo.size_field = options.size_field;
  p.source_mesh = quad_face(solid, p.topo.source, p.source_loops, qo);
  if (!p.source_mesh.ok) p.diagnostics = p.source_mesh.diagnostics;
  return p.source_mesh.ok;
}

// Whether the counts balance along the submap directions (+u = -u, +v = -v).
bool balanced(const std::vector<int>& dirs, const std::vector<int>& counts) {
  if (dirs.empty() || dirs.size() != counts.size()) return false;
  int sum[4] = {0, 0, 0, 0};
  for (std::size_t e = 0; e < dirs.size(); ++e) sum[dirs[e]] += counts[e];
  return sum[0] == sum[2] && sum[1] == sum[3];
}

// Planning with the intervals given per edge: checked, not chosen.
Plan plan_given(const Solid& solid, const SweepOptions& options, Plan p) {
  const Topology& t = p.topo;
  auto given = [&](EdgeId e) {
    const int i = e.value();
    return i < int(options.edge_intervals.size()) ? options.edge_intervals[i] : 0;
  };
  auto refuse = [&](const std::string& why, std::vector<std::string> names) {
    p.diagnostics.push_back(core::make_error("intervals_mismatch",
                                             "The given intervals do not fit the sweep from " +
                                                 name(t.source) + " to " + name(t.target) + ": " +
                                                 why + ".",
                                             std::move(names)));
    return p;
  };
  for (const auto& loop : t.loops)
    for (const Link& l : loop)
      for (const std::vector<Directed>* chain : {&l.col0, &l.col1}) {
        int k = 0;
        std::string names;
        for (const Directed& c : *chain) {
          const int m = given(c.edge);
          if (m < 1) k = -1;
          if (k >= 0) k += m;
          names += (names.empty() ? "" : " + ") + name(c.edge);
        }
        if (k < 1 || k > options.max_intervals || (p.layers != 0 && k != p.layers))
          return refuse(names + " has " + std::to_string(k) +
                            " intervals, other linking "
                            "edges " +
                            std::to_string(p.layers),
                        {name(chain->front().edge)});
        p.layers = k;
      }
  auto sum = [&](const std::vector<Directed>& chain, std::size_t n) {
    int k = 0;
    for (std::size_t c = 0; c < n; ++c) k += std::max(0, given(chain[c].edge));
    return k;
  };
  for (const auto& loop : t.loops)
    for (const Link& l : loop)
      for (std::size_t j = 0; j < l.separators.size(); ++j) {
        const int n = given(l.source.edge), across = sum(l.separators[j], l.separators[j].size());
        if (across != n ||
            sum(l.col0, std::size_t(l.below0[j])) != sum(l.col1, std::size_t(l.below1[j])))
          return refuse(name(l.separators[j].front().edge) + ", between " + name(l.face) +
                            " and the faces above it, lies on no layer (" + std::to_string(across) +
                            " intervals across, " + std::to_string(n) + " on the source edge)",
                        {name(l.separators[j].front().edge)});
      }
  for (std::size_t li = 0; li < t.loops.size(); ++li) {
    const auto& loop = t.loops[li];
    std::vector<int> counts;
    int total = 0;
    for (const Link& l : loop) {
      const int n = given(l.source.edge);
      int across = 0;
      bool missing = false;
      std::string targets;
      std::vector<std::string> names{name(l.source.edge)};
      for (const Directed& d : l.target) {
        across += std::max(0, given(d.edge));
        targets += (targets.empty() ? "" : " + ") + name(d.edge);
        names.push_back(name(d.edge));
        missing = missing || given(d.edge) < 1;
      }
      if (n < 1 || n > options.max_intervals || missing || across != n)
        return refuse(name(l.source.edge) + " has " + std::to_string(n) + " intervals and " +
                          targets + " across " + name(l.face) + " " +
                          std::to_string(std::max(0, across)),
                      names);
      counts.push_back(n);
      total += n;
    }
    const bool grid =
        t.loops.size() == 1 && loop.size() == 4 && counts[0] == counts[2] && counts[1] == counts[3];
    const std::vector<int> dirs =
        t.loops.size() == 1 ? submap_directions(solid, t.source) : std::vector<int>();
    if (grid)
      p.grid = {counts[0], counts[1]};
    else if (balanced(dirs, counts))
      p.submap = dirs;
    else if (total % 2 != 0 || total < (t.loops.size() == 1 ? 4 : 6))
      return refuse("loop " + std::to_string(li + 1) + " of " + name(t.source) + " has " +
                        std::to_string(total) + " segments (quads need an even number, at least " +
                        (t.loops.size() == 1 ? "4" : "6") + ")",
                    {name(t.source)});
    p.counts.push_back(counts);
    std::vector<Vec3> nodes;
    for (std::size_t e = 0; e < loop.size(); ++e) {
      auto pts =
          read_edge(solid, loop[e].source, counts[e], options.size_field, options.edge_nodes);
      nodes.insert(nodes.end(), pts.begin(), pts.end() - 1);
    }
    p.source_loops.push_back(std::move(nodes));
  }
  if (!set_target_counts(solid, options, p)) return p;
  if (p.grid[0] > 0) {
    p.source_mesh = detail::grid_face(solid, t.source, p.source_loops[0], p.grid[0], p.grid[1]);
  } else if (!p.submap.empty()) {
    p.source_mesh = submap_face(solid, t.source, p.source_loops[0], p.counts[0], p.submap);
    // A lattice that folds (a strip's end whose side turns round through two tangent fillets
    // between its corners: a boss's root and top edges filleted) gives way to the quad
    // mesher's mesh of the same nodes.
    if (!p.source_mesh.ok) {
      const std::vector<core::Diagnostic> folded = p.source_mesh.diagnostics;
      p.submap.clear();
      if (!mesh_source_unstructured(solid, options, p)) {
        p.diagnostics.insert(p.diagnostics.begin(), folded.begin(), folded.end());
        return p;
      }
    }
  } else if (!mesh_source_unstructured(solid, options, p)) {
    return p;
  }
  p.ok = true;
  return p;
}

bool has_stacks(const Topology& t) {
  for (const auto& loop : t.loops)
    for (const Link& l : loop)
      if (!l.stack.empty()) return true;
  return false;
}

Plan plan(const Solid& solid, const SweepOptions& options) {
  options.validate();
  Plan p;
  try {
    const std::string why =
        detail::choose_sweep_topology(solid, p.topo, options.avoid_sources, options.imprinted);
    if (!why.empty()) {
      p.diagnostics.push_back(
          core::make_error("not_applicable", "The solid is not a one-to-one sweep: " + why + "."));
      return p;
    }
    const Topology& t = p.topo;
    auto too_many = [&](double length, double n, std::vector<std::string> names) {
      std::ostringstream s;
      s << "Edges of length " << length << " at size " << options.size << " need " << n
        << " intervals, more than max_intervals = " << options.max_intervals << ".";
      p.diagnostics.push_back(core::make_error("too_many_intervals", s.str(), std::move(names)));
      return p;
    };
    if (!options.edge_intervals.empty()) return plan_given(solid, options, std::move(p));
    if (has_stacks(t)) {  // its separators' layers come from its neighbours' intervals
      p.diagnostics.push_back(core::make_error(
          "intervals_needed",
          "The sweep from " + name(t.source) + " to " + name(t.target) +
              " has linking sides that are stacks of faces (a neighbour's imprints): it is "
              "meshed with the intervals assigned with its neighbours (mesh_sub_volumes), "
              "not on its own.",
          {name(t.source)}));
      return p;
    }
    // Layers: with local sizes, the finest count a linking edge asks for (a sweep has one
    // layer count for all).
    double layer_target = t.link_length / options.size;
    if (detail::graded(options.size_field))
      for (const auto& loop : t.loops)
        for (const Link& l : loop)
          for (const std::vector<Directed>* chain : {&l.col0, &l.col1}) {
            double segments = 0;
            for (const Directed& c : *chain)
              segments += detail::edge_segments(solid, c.edge, options.size, options.size_field);
            layer_target = std::max(layer_target, segments);
          }
    // At least one layer per edge of the longest linking chain (its vertices are nodes).
    std::size_t longest_chain = 1;
    for (const auto& loop : t.loops)
      for (const Link& l : loop) longest_chain = std::max(longest_chain, l.col0.size());
    const double k = std::max(double(longest_chain), std::round(layer_target));
    if (k > options.max_intervals) return too_many(t.link_length, k, {});
    p.layers = int(k);
    // A submappable source (an L, a T, a stepped outline): counts from one interval
    // assignment so that opposite directions balance, and the lattice mesh.
    if (t.loops.size() == 1) {
      const std::vector<int> dirs = submap_directions(solid, t.source);
      if (!dirs.empty()) {
        IntervalProblem ip;
        std::vector<int> curves;
        for (const Link& l : t.loops[0])
          curves.push_back(ip.add_curve(
              solid.edge_length(l.source.edge), name(l.source.edge),
              detail::edge_segments(solid, l.source.edge, options.size, options.size_field)));
        add_submap_balance(ip, dirs, curves, name(t.source));
        IntervalOptions io;
        io.size = options.size;
        io.max_intervals = options.max_intervals;
        const IntervalResult assigned = assign_intervals(ip, io);
        if (assigned.ok()) {
          std::vector<Vec3> nodes;
          for (std::size_t e = 0; e < t.loops[0].size(); ++e) {
            auto pts = read_edge(solid, t.loops[0][e].source, assigned.intervals[e],
                                 options.size_field, options.edge_nodes);
            nodes.insert(nodes.end(), pts.begin(), pts.end() - 1);
          }
          QuadFaceMesh lattice = submap_face(solid, t.source, nodes, assigned.intervals, dirs);
          if (lattice.ok) {
            p.counts = {assigned.intervals};
            p.source_loops = {std::move(nodes)};
            p.source_mesh = std::move(lattice);
            p.submap = dirs;
          }
        }
      }
    }
    // Source edges: their own counts, each even so that every model vertex is a coarse node
    // of the quad mesher; loops of at least 6 (4 for a face without holes).
    for (const auto& loop : t.loops) {
      if (!p.submap.empty()) break;
      std::vector<int> counts;
      std::vector<double> lengths;
      int total = 0;
      for (const Link& l : loop) {
        const double len = solid.edge_length(l.source.edge);
        const double want =
            detail::edge_segments(solid, l.source.edge, options.size, options.size_field);
        double n = std::max(1.0, std::round(want));
        n += std::fmod(n, 2.0);
        // A whole circle (a round hole): a multiple of 4, at least 8, so that its quadrant
        // points are nodes and the rings around it are symmetric.
        if (solid.edge_first_vertex(l.source.edge) == solid.edge_last_vertex(l.source.edge) &&
            solid.curve_info(l.source.edge).kind == core::CurveKind::circle)
          n = std::max(8.0, 4 * std::ceil(want / 4));
        // A chain of target edges: at least one interval each.
        while (n < double(l.target.size())) n += 2;
        if (n > options.max_intervals) return too_many(len, n, {name(l.source.edge)});
        counts.push_back(int(n));
        lengths.push_back(len);
        total += int(n);
      }
      const int minimum = t.loops.size() == 1 ? 4 : 6;
      while (total < minimum) {
        std::size_t c = 0;
        for (std::size_t e = 1; e < counts.size(); ++e)
          if (lengths[e] / counts[e] > lengths[c] / counts[c]) c = e;
        counts[c] += 2;
        total += 2;
      }
      p.counts.push_back(counts);
      std::vector<Vec3> nodes;
      for (std::size_t e = 0; e < loop.size(); ++e) {
        auto pts = detail::edge_points(solid, loop[e].source.edge, counts[e], options.size_field,
                                       options.edge_nodes);
        if (!loop[e].source.forward) std::reverse(pts.begin(), pts.end());
        nodes.insert(nodes.end(), pts.begin(), pts.end() - 1);
      }
      p.source_loops.push_back(std::move(nodes));
    }
    if (!set_target_counts(solid, options, p)) return p;
    if (p.submap.empty() && !mesh_source_unstructured(solid, options, p)) return p;
    const double nodes = double(p.source_mesh.points.size()) * (p.layers + 1);
    if (nodes > double(std::numeric_limits<std::int32_t>::max())) {
      p.diagnostics.push_back(core::make_error(
          "too_many_nodes", "The sweep would need " + std::to_string(nodes) +
                                " nodes, more than a mesh can index; use a larger size."));
      return p;
    }
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const std::exception& e) {
    p.diagnostics.push_back(
        core::make_error("geometry_error", std::string("Planning the sweep failed: ") + e.what()));
    return p;
  }
  p.ok = true;
  return p;
}

}  // namespace

SweepApplicability sweep_applicable(const core::MeshDomain& solid, bool imprinted) {
  SweepApplicability a;
  try {
    Topology t;
    a.reason = detail::choose_sweep_topology(solid, t, {}, imprinted);
    if (a.reason.empty()) a.source = t.source, a.target = t.target;
  } catch (const std::exception& e) {
    a.reason = std::string("its topology cannot be explored (") + e.what() + ")";
  }
  a.ok = a.reason.empty();
  return a;
}

SweepStructure sweep_structure(const core::MeshDomain& solid, const std::vector<int>& avoid_sources,
                               bool imprinted) {
  SweepStructure out;
  Topology t;
  try {
    if (!detail::choose_sweep_topology(solid, t, avoid_sources, imprinted).empty()) return out;
  } catch (const std::exception&) {
    return out;
  }
  out.source = t.source;
  out.target = t.target;
  std::set<int> seen;
  for (const auto& loop : t.loops) {
    out.loops.emplace_back();
    for (const Link& l : loop) {
      std::vector<EdgeId> across;
      for (const Directed& d : l.target) across.push_back(d.edge);
      out.loops.back().emplace_back(l.source.edge, std::move(across));
      for (const std::vector<Directed>* chain : {&l.col0, &l.col1})
        if (seen.insert(chain->front().edge.value()).second)
          out.linking.push_back(chain_edges(*chain));
      for (std::size_t j = 0; j < l.separators.size(); ++j) {
        SweepStructure::Level level;
        level.source = l.source.edge;
        level.across = chain_edges(l.separators[j]);
        for (int c = 0; c < l.below0[j]; ++c) level.below0.push_back(l.col0[c].edge);
        for (int c = 0; c < l.below1[j]; ++c) level.below1.push_back(l.col1[c].edge);
        out.levels.push_back(std::move(level));
      }
    }
  }
  return out;
}

SweepEstimate sweep_evaluate(const core::MeshDomain& solid, const SweepOptions& options) {
  const Plan p = plan(solid, options);
  SweepEstimate e;
  if (!p.ok) return e;
  e.layers = p.layers;
  e.nodes = p.source_mesh.points.size() * std::size_t(p.layers + 1);
  e.hexes = p.source_mesh.quads.size() * std::size_t(p.layers);
  return e;
}

namespace {

// The target's quads (corner points) carried onto the source: a corner on the target's
// boundary (xt, within tol) goes to the source's boundary node of the same index (xs), the
// inner ones where the mean value weights put them as the boundary moves from xt to xs in
// steps (detail::smooth_layer_interiors), onto the source face. The sweep takes them only
// where their boundary corners are all its source's nodes. Empty where the steps were cut
// short.
std::vector<std::array<Vec3, 4>> quads_on_source(const core::MeshDomain& solid, FaceId source,
                                                 const std::vector<Vec3>& xs,
                                                 const std::vector<Vec3>& xt,
                                                 const std::vector<std::array<Vec3, 4>>& quads,
                                                 double tol, double size) {
  const std::size_t nb = xt.size();
  std::vector<Vec3> inner;
  std::vector<std::array<int, 4>> index(quads.size());
  for (std::size_t i = 0; i < quads.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      const Vec3& q = quads[i][c];
      std::size_t j = 0;
      while (j < nb && (xt[j] - q).norm() > tol) ++j;
      if (j == nb) {
        j = 0;
        while (j < inner.size() && (inner[j] - q).norm() > tol) ++j;
        if (j == inner.size()) inner.push_back(q);
        j += nb;
      }
      index[i][c] = int(j);
    }
  const std::size_t M = nb + inner.size();
  std::vector<Vec3> P(2 * M);
  for (std::size_t j = 0; j < nb; ++j) P[j] = xt[j], P[M + j] = xs[j];
  for (std::size_t j = 0; j < inner.size(); ++j) P[nb + j] = P[M + nb + j] = inner[j];
  if (detail::smooth_layer_interiors(
          P, M, nb, 1, 1, index, 1e-3 * size, 200,
          [&](int, const Vec3& q) { return solid.project_to_face(source, q); }) < 0)
    return {};
  std::vector<std::array<Vec3, 4>> out(quads.size());
  for (std::size_t i = 0; i < quads.size(); ++i)
    for (int c = 0; c < 4; ++c) out[i][c] = P[M + std::size_t(index[i][c])];
  return out;
}

}  // namespace

SweepResult sweep(const core::MeshDomain& solid, const SweepOptions& options,
                  const core::Progress& progress) {
  SweepResult result;
  Plan p = plan(solid, options);  // throws std::invalid_argument on bad options
  result.diagnostics = std::move(p.diagnostics);
  if (!p.ok) return result;
  const Topology& t = p.topo;
  const QuadFaceMesh& sm = p.source_mesh;
  result.source = t.source;
  result.target = t.target;
  result.layers = p.layers;
  result.source_min_quality = sm.min_quality;
  result.source_mean_quality = sm.mean_quality;
  if (sm.min_quality < 0.3)
    result.diagnostics.push_back(
        core::make_warning("poor_source_quads",
                           "The source face mesh has quads of scaled Jacobian " +
                               std::to_string(sm.min_quality) + " (< 0.3).",
                           {name(t.source)}));

  const int K = p.layers;
  const std::size_t M = sm.points.size(), nb = sm.num_boundary;
  std::vector<Vec3> P(M * (K + 1));
  std::vector<NodeClass> C(P.size(), NodeClass::interior());
  auto id = [&](int k, std::size_t j) { return std::size_t(k) * M + j; };
  const char* stage = "sweep";
  auto cancelled = [&] {
    if (!progress.cancelled()) return false;
    result.diagnostics.push_back(core::make_error("cancelled", "Sweeping was cancelled."));
    return true;
  };

  bool target_mismatch = false;
  try {
    // Linking faces: transfinite interpolation of their four edge rows, projected if curved.
    std::size_t j0 = 0;
    for (std::size_t l = 0; l < t.loops.size(); ++l) {
      const std::size_t loop_size = p.source_loops[l].size();
      for (std::size_t e = 0; e < t.loops[l].size(); ++e) {
        const Link& link = t.loops[l][e];
        const int n = p.counts[l][e];
        const core::SizeField* f = options.size_field;
        const auto& g = options.edge_nodes;
        std::vector<NodeClass> ct, c0_class, c1_class;
        const auto rs = read_edge(solid, link.source, n, f, g),
                   rt = read_chain(solid, link.target, p.target_counts[l][e], f, g, ct);
        const std::vector<int> counts0 = chain_counts(solid, link.col0, K, options),
                               counts1 = chain_counts(solid, link.col1, K, options);
        const auto c0 = read_chain(solid, link.col0, counts0, f, g, c0_class),
                   c1 = read_chain(solid, link.col1, counts1, f, g, c1_class);
        if (c0.size() != std::size_t(K) + 1 || c1.size() != std::size_t(K) + 1)
          throw std::logic_error("linking chain shorter than its edges");
        // The rows between which each face of the stack is interpolated: the source edge's,
        // each separator's (on the layer of its vertices on the linking chains), the target's.
        std::vector<int> row_k{0};
        std::vector<std::vector<Vec3>> rows{rs};
        std::vector<std::vector<NodeClass>> row_class{{}};
        std::vector<char> curved{!solid.face_is_planar(link.face)};  // per face of the stack
        auto layer_of = [](const std::vector<int>& counts, int below) {
          int k = 0;
          for (int c = 0; c < below; ++c) k += counts[std::size_t(c)];
          return k;
        };
        for (std::size_t sj = 0; sj < link.separators.size(); ++sj) {
          const int k = layer_of(counts0, link.below0[sj]);
          if (k != layer_of(counts1, link.below1[sj]) || k <= row_k.back() || k >= K)
            throw std::logic_error("a separator of a stack of linking faces lies on no layer");
          std::vector<NodeClass> cls;
          rows.push_back(read_chain(solid, link.separators[sj],
                                    chain_counts(solid, link.separators[sj], n, options), f, g,
                                    cls));
          row_k.push_back(k);
          row_class.push_back(std::move(cls));
          curved.push_back(!solid.face_is_planar(link.stack[sj]));
        }
        row_k.push_back(K);
        rows.push_back(rt);
        row_class.push_back(ct);
        for (int m = 0; m < n; ++m) {
          const double s = double(m) / n;
          const std::size_t j = j0 + m;
          std::size_t seg = 0;  // the face of the stack: rows seg and seg + 1
          for (int k = 0; k <= K; ++k) {
            while (seg + 2 < row_k.size() && k > row_k[seg + 1]) ++seg;
            const FaceId face = seg == 0 ? link.face : link.stack[seg - 1];
            const int ka = row_k[seg], kb = row_k[seg + 1];
            const double w = double(k - ka) / (kb - ka);
            const std::vector<Vec3>&ra = rows[seg], &rb = rows[seg + 1];
            Vec3 q;
            NodeClass c;
            if (k == 0) {
              q = rs[m];
              c = m == 0 ? NodeClass::on(link.b) : NodeClass::on(link.source.edge);
            } else if (m == 0) {
              q = c0[k];
              c = k == K ? NodeClass::on(link.b_target) : c0_class[k];
            } else if (k == kb) {
              q = rb[m];
              c = row_class[seg + 1][m];
            } else {
              q = (1 - s) * c0[k] + s * c1[k] + (1 - w) * ra[m] + w * rb[m] -
                  ((1 - s) * (1 - w) * ra[0] + s * (1 - w) * ra[n] + (1 - s) * w * rb[0] +
                   s * w * rb[n]);
              if (curved[seg]) q = solid.project_to_face(face, q);
              c = NodeClass::on(face);
            }
            P[id(k, j)] = q;
            C[id(k, j)] = c;
          }
        }
        j0 += n;
      }
      if (j0 != nb && l + 1 == t.loops.size()) throw std::logic_error("boundary count mismatch");
      (void)loop_size;
    }
    // Source and target faces.
    std::vector<Vec3> xs(sm.points.begin(), sm.points.begin() + nb), xt(nb);
    for (std::size_t j = 0; j < nb; ++j) xt[j] = P[id(K, j)];
    AffineFit to_target(xs);
    to_target.fit(xt);
    Vec3 axis = Vec3::Zero();  // the sweep's, from the source's boundary centre to the target's
    for (std::size_t j = 0; j < nb; ++j) axis += (xt[j] - xs[j]) / double(nb);
    axis = axis.norm() > 0 ? Vec3(axis.normalized()) : axis;
    // A grid source has a grid target: transfinite interpolation of the target's own
    // boundary nodes (what a neighbour meshing that face as a mapped face computes).
    std::vector<Vec3> grid_target =
        p.grid[0] > 0 ? detail::grid_inner_nodes(solid, t.target, xt, p.grid[0], p.grid[1])
                      : std::vector<Vec3>();
    if (!p.submap.empty()) {  // the same lattice on the target's own boundary nodes
      const QuadFaceMesh tm = submap_face(solid, t.target, xt, p.counts[0], p.submap);
      if (!tm.ok) throw std::runtime_error("the target could not be submapped");
      grid_target.assign(tm.points.begin() + nb, tm.points.end());
    }
    // A target with an apex inside (a drill point's cone: a degenerated edge), whose
    // points nearest to the source's images near the axis lie on a ring around the apex, is
    // reached along the axis; its inner node nearest the apex goes there.
    const std::vector<core::VertexId> apexes = detail::apex_vertices(solid, t.target);
    const bool along = options.target_along_axis || !apexes.empty();
    for (std::size_t j = nb; j < M; ++j) {
      P[id(0, j)] = sm.points[j];
      C[id(0, j)] = NodeClass::on(t.source);
      const Vec3 image = to_target(sm.points[j]);
      P[id(K, j)] = !grid_target.empty() ? grid_target[j - nb]
                    : along              ? detail::onto_face_along(solid, t.target, image, axis)
                                         : solid.project_to_face(t.target, image);
      C[id(K, j)] = NodeClass::on(t.target);
    }
    // A mapped or submapped source that a neighbour meshed first (a multisweep's wall): its
    // inner nodes put on the neighbour's, paired by the quads' connectivity, so that both
    // meshes of the face are one (the same cells; the positions differ: the neighbour's
    // extruded rows against this lattice's). Where they do not pair up, the face stays this
    // sweep's own and the join's check names it.
    if (!options.source_quads.empty() && (p.grid[0] > 0 || !p.submap.empty()))
      detail::onto_quads_by_connectivity(P, 0, M, nb, sm.quads, options.source_quads, options.size);
    target_mismatch = !options.target_quads.empty() &&
                      !detail::onto_quads_by_connectivity(P, std::size_t(K) * M, M, nb, sm.quads,
                                                          options.target_quads, options.size) &&
                      !detail::onto_target_quads(P, std::size_t(K) * M, M, nb, options.target_quads,
                                                 options.size);
    for (core::VertexId v : apexes) {
      const Vec3 apex = solid.vertex_point(v);
      std::size_t nearest = M;
      for (std::size_t j = nb; j < M; ++j)
        if (nearest == M || (P[id(K, j)] - apex).norm() < (P[id(K, nearest)] - apex).norm())
          nearest = j;
      if (nearest < M && (P[id(K, nearest)] - apex).norm() < options.size)
        P[id(K, nearest)] = apex, C[id(K, nearest)] = NodeClass::on(v);
    }
  } catch (const std::exception& e) {
    result.diagnostics.push_back(core::make_error(
        "geometry_error", std::string("Placing the sweep's boundary nodes failed: ") + e.what()));
    return result;
  }
  if (target_mismatch) {
    // A source meshed freely whose target a neighbour meshed first (a cam's chamfer slab,
    // swept from the part's face to the multisweep's cap over it, which the merged cuts'
    // traces imprinted so that no sweep goes the other way): swept again from the image of
    // the target's quads on the source.
    if (options.source_quads.empty() && p.grid[0] == 0 && p.submap.empty()) {
      std::vector<Vec3> xs(nb), xt(nb);
      for (std::size_t j = 0; j < nb; ++j) xs[j] = P[id(0, j)], xt[j] = P[id(K, j)];
      SweepOptions again = options;
      again.source_quads = quads_on_source(solid, t.source, xs, xt, options.target_quads,
                                           1e-6 * options.size, options.size);
      if (!again.source_quads.empty()) {
        SweepResult r = sweep(solid, again, progress);
        if (r.ok) return r;
      }
    }
    result.diagnostics.push_back(
        core::make_error("target_mismatch",
                         "The quads a neighbour meshed on the target " + name(t.target) +
                             " are not the image of the source's: their inner nodes do not pair up "
                             "with the swept ones.",
                         {name(t.target)}));
    return result;
  }
  if (cancelled()) return result;
  progress.report(stage, 0.1);

  // Inner layers: blend of the source- and target-based affine predictions.
  {
    std::vector<Vec3> xs(nb), xt(nb), y(nb);
    for (std::size_t j = 0; j < nb; ++j) xs[j] = P[id(0, j)], xt[j] = P[id(K, j)];
    AffineFit from_source(xs), from_target(xt);
    for (int k = 1; k < K; ++k) {
      for (std::size_t j = 0; j < nb; ++j) y[j] = P[id(k, j)];
      from_source.fit(y);
      from_target.fit(y);
      const double w = double(k) / K;
      for (std::size_t j = nb; j < M; ++j)
        P[id(k, j)] = (1 - w) * from_source(P[id(0, j)]) + w * from_target(P[id(K, j)]);
      progress.report(stage, 0.1 + 0.5 * k / K);
      if (cancelled()) return result;
    }
  }
  // Or each layer the one below deformed to its boundary (the target too where its inner
  // nodes are the source's images, put back on it).
  if (options.smooth_layers && M > nb && K > 0) {
    if (double(M) * K > kSmoothedLayersNodes) {
      result.diagnostics.push_back(core::make_error(
          "not_supported_yet", "The sweep's layers are not deformed to their boundaries beyond " +
                                   std::to_string(int(kSmoothedLayersNodes)) + " nodes (" +
                                   std::to_string(M * K) + ")."));
      return result;
    }
    const bool free_target = p.grid[0] == 0 && p.submap.empty() && options.target_quads.empty() &&
                             detail::apex_vertices(solid, t.target).empty();
    const int sweeps = detail::smooth_layer_interiors(
        P, M, nb, 1, free_target ? K : K - 1, sm.quads, 1e-3 * options.size, 200,
        [&](int k, const Vec3& q) { return k == K ? solid.project_to_face(t.target, q) : q; },
        [&] { return progress.cancelled(); });
    if (sweeps < 0 && cancelled()) return result;
  }

  // Hexes: source quads run counter-clockwise about the source's outward normal, i.e.
  // clockwise seen from the next layer, so they are reversed for VTK order.
  core::HexMesh& mesh = result.mesh;
  mesh.reserve(P.size(), sm.quads.size() * K);
  for (std::size_t i = 0; i < P.size(); ++i) mesh.add_node(P[i], C[i]);
  std::vector<Vec3>().swap(P);
  double orientation = 0;  // summed corner triple products of the first layer
  for (const auto& q : sm.quads) {
    const Vec3 &a = mesh.points()[q[0]], &b = mesh.points()[q[3]], &d = mesh.points()[q[1]],
               &up = mesh.points()[id(1, q[0])];
    orientation += (b - a).cross(d - a).dot(up - a);
  }
  const bool flip = orientation < 0;
  for (int k = 0; k < K; ++k) {
    for (const auto& q : sm.quads) {
      std::array<std::int32_t, 4> r = {q[0], q[3], q[2], q[1]};
      if (flip) r = {q[0], q[1], q[2], q[3]};
      core::HexNodes h;
      for (int c = 0; c < 4; ++c) {
        h[c] = std::int32_t(id(k, r[c]));
        h[c + 4] = std::int32_t(id(k + 1, r[c]));
      }
      mesh.add_hex(h, 0);
    }
    progress.report(stage, 0.6 + 0.4 * (k + 1) / K);
    if (cancelled()) {
      result.mesh = core::HexMesh();
      return result;
    }
  }
  // Corner determinants: the layer placement may fold under strong twist or shape change;
  // say so instead of handing on a tangled mesh.
  std::size_t folded = 0;
  for (const core::HexNodes& h : mesh.hexes()) {
    const auto c = [&](int i) -> const Vec3& { return mesh.points()[h[i]]; };
    bool bad = false;
    for (int i = 0; i < 4 && !bad; ++i) {
      const int n = (i + 1) % 4, pv = (i + 3) % 4;
      bad = (c(n) - c(i)).cross(c(pv) - c(i)).dot(c(i + 4) - c(i)) <= 0 ||
            (c(pv + 4) - c(i + 4)).cross(c(n + 4) - c(i + 4)).dot(c(i) - c(i + 4)) <= 0;
    }
    folded += bad;
  }
  result.folded = folded;
  if (folded > 0) {
    result.diagnostics.push_back(core::make_error("inverted_elements",
                                                  std::to_string(folded) +
                                                      " swept hexahedra have a non-positive corner "
                                                      "Jacobian (the layers fold between " +
                                                      name(t.source) + " and " + name(t.target) +
                                                      ").",
                                                  {name(t.source), name(t.target)}));
    return result;
  }
  // Deformed layers that do not fold may still be poor (a sheared thin slab): below the bar
  // untangling a folded sweep must reach (smooth::untangle_folded), the next try or scheme
  // does better (HexMe n03: 0.12 before smoothing, 0.26 after; its multisweep 0.32).
  // Where the source's quads are a neighbour's (a multisweep's cap), no other source does
  // better: the bar is relative to their quality (a flange's chamfer slab, swept in one layer
  // from the hub's cap, quads at 0.259, to the chamfer's smaller annulus: 0.183, 0.456 once
  // the whole is smoothed; refused, the grid mesher's 46,304 hexahedra).
  if (options.smooth_layers) {
    const std::vector<double> sj = quality::scaled_jacobians(mesh);
    const double worst = sj.empty() ? 0 : *std::min_element(sj.begin(), sj.end());
    const double bar = p.source_given ? std::min(kSmoothedLayersQuality, 0.6 * sm.min_quality)
                                      : kSmoothedLayersQuality;
    if (worst < bar) {
      std::ostringstream s;
      s << "The sweep's layers deformed to their boundaries (between " << name(t.source) << " and "
        << name(t.target) << ") do not fold, but their worst hexahedron has a scaled "
        << "Jacobian of " << worst << " (< " << bar << ").";
      result.diagnostics.push_back(
          core::make_error("poor_elements", s.str(), {name(t.source), name(t.target)}));
      return result;
    }
  }
  result.ok = true;
  return result;
}

void accept_untangled(SweepResult& r) {
  for (core::Diagnostic& d : r.diagnostics)
    if (d.code == "inverted_elements" && d.severity == core::Severity::error) {
      d = core::make_warning(
          "sweep_untangled",
          std::to_string(r.folded) + " swept hexahedra folded (the layers fold between " +
              name(r.source) + " and " + name(r.target) + "); the smoothing untangled them.",
          d.entities);
    }
  r.ok = true;
}

}  // namespace vorohex::mesh
