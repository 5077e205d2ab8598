#include "mesh/multisweep.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "core/option_checks.h"
#include "mesh/detail/cad_lookup.h"
#include "mesh/detail/sizing.h"
#include "mesh/face_set.h"
#include "occ/prismatic.h"

namespace vorohex::mesh {

using core::NodeClass;
using core::Vec3;

void MultisweepOptions::validate() const {
  core::require_positive("MultisweepOptions.size", size);
  core::require_at_least("MultisweepOptions.max_intervals", max_intervals, 1);
  core::require_at_least("MultisweepOptions.smoothing_passes", smoothing_passes, 0);
  for (int n : edge_intervals) core::require_at_least("MultisweepOptions.edge_intervals", n, 0);
}

namespace {

// Everything both evaluate() and the meshing need: the structure, the regions' quads and
// the layers of each slab.
struct Plan {
  occ::PrismaticStructure structure;
  FaceSetMesh regions;
  std::vector<int> layers;      // per slab
  std::vector<int> level_z;     // per level: its index in the list of heights
  std::vector<double> heights;  // every layer's height, bottom to top
  // Per 2-D node and level: the level's height over the node, on a sloped cap where one at
  // that level covers a region around it (empty when no cap is sloped: the levels' heights).
  std::vector<std::vector<double>> level_height;
  bool ok = false;
  std::vector<core::Diagnostic> diagnostics;
};

// Given counts on the solid's edges, as the arrangement's edges and the slabs' layers must
// have them: an edge at one height covers the arrangement edges under it (their counts sum to
// its count), an edge along the axis spans slabs (their layers sum to its count). False with
// why when an edge is neither, or the layers cannot be met.
struct FixedCounts {
  std::vector<FaceSetOptions::FixedSum> sums;  // on arrangement edge ids
  std::vector<int> layers;                     // per slab, 0: free
  std::vector<std::vector<Vec3>> points;       // per arrangement edge id: given nodes
  std::vector<std::vector<double>> heights;    // per slab: given layer heights (both levels)
};

// Given nodes of edge e: the arrangement edges under it and the slabs it spans take them.
bool given_nodes(const core::MeshDomain& solid, const occ::PrismaticStructure& s, core::EdgeId e,
                 const std::vector<Vec3>& nodes, const occ::EdgeInStructure& where,
                 FixedCounts& out, std::string& why) {
  const occ::Solid& arr = *s.arrangement;
  const double tol = std::max(1e-6 * solid.diagonal(), 10 * solid.tolerance());
  const std::string who = "the nodes given on " + core::entity_name(e);
  for (int a : where.arrangement_edges) {
    const core::EdgeId ae(a);
    const Vec3 a0 = arr.vertex_point(arr.edge_first_vertex(ae));
    const Vec3 a1 = arr.vertex_point(arr.edge_last_vertex(ae));
    // The nodes moved to the arrangement's plane; the run between a's two vertices.
    std::vector<Vec3> flat;
    for (const Vec3& q : nodes) flat.push_back(q + (s.height(a0) - s.height(q)) * s.axis);
    int i0 = -1, i1 = -1;
    for (int i = 0; i < int(flat.size()); ++i) {
      if ((flat[i] - a0).norm() <= tol) i0 = i;
      if ((flat[i] - a1).norm() <= tol) i1 = i;
    }
    if (i0 < 0 || i1 < 0 || i0 == i1) {
      why = who + " miss a vertex of the cross-section under it";
      return false;
    }
    std::vector<Vec3> run;
    for (int i = i0;; i += i1 > i0 ? 1 : -1) {
      run.push_back(flat[i]);
      if (i == i1) break;
    }
    run.front() = a0, run.back() = a1;
    if (!out.points[a].empty() && out.points[a].size() != run.size()) {
      why = who + " differ from those given on another edge over the same cross-section edge";
      return false;
    }
    out.points[a] = std::move(run);
  }
  for (int l : where.slabs) {
    std::vector<double> h;
    for (const Vec3& q : nodes) {
      const double z = s.height(q);
      if (z >= s.levels[l] - tol && z <= s.levels[l + 1] + tol) h.push_back(z);
    }
    std::sort(h.begin(), h.end());
    if (h.size() < 2 || std::abs(h.front() - s.levels[l]) > tol ||
        std::abs(h.back() - s.levels[l + 1]) > tol) {
      why = who + " miss a level of the slabs it spans";
      return false;
    }
    h.front() = s.levels[l], h.back() = s.levels[l + 1];
    if (!out.heights[l].empty()) {
      bool same = out.heights[l].size() == h.size();
      for (std::size_t i = 0; same && i < h.size(); ++i)
        same = std::abs(out.heights[l][i] - h[i]) <= tol;
      if (!same) {
        why = who + " give the layers of a slab other heights than another edge's";
        return false;
      }
    }
    out.layers[l] = int(h.size()) - 1;
    out.heights[l] = std::move(h);
  }
  return true;
}

bool fixed_counts(const core::MeshDomain& solid, const occ::PrismaticStructure& s,
                  const MultisweepOptions& options, FixedCounts& out, std::string& why) {
  const std::vector<int>& given = options.edge_intervals;
  out.layers.assign(s.levels.size() - 1, 0);
  out.heights.assign(s.levels.size() - 1, {});
  out.points.assign(s.arrangement->num_edges() + 1, {});
  std::vector<std::pair<std::vector<int>, int>> spans;  // slabs of an axial edge, its count
  for (core::EdgeId e : solid.edges()) {
    const bool has_nodes =
        e.value() < int(options.edge_nodes.size()) && options.edge_nodes[e.value()].size() >= 2;
    if (has_nodes && !solid.edge_is_degenerated(e) &&
        solid.edge_first_vertex(e) != solid.edge_last_vertex(e)) {
      if (!given_nodes(solid, s, e, options.edge_nodes[e.value()],
                       occ::edge_in_structure(solid, s, e), out, why))
        return false;
      continue;
    }
    const int n = e.value() < int(given.size()) ? given[e.value()] : 0;
    if (n <= 0 || solid.edge_is_degenerated(e)) continue;
    occ::EdgeInStructure where = occ::edge_in_structure(solid, s, e);
    if (!where.arrangement_edges.empty()) {
      out.sums.push_back({std::move(where.arrangement_edges), n});
    } else if (!where.slabs.empty()) {
      spans.emplace_back(std::move(where.slabs), n);
    } else {
      why = core::entity_name(e) + " lies neither over the cross-section nor along the axis";
      return false;
    }
  }
  // Single slabs first, then each longer span shares what is left by thickness.
  std::stable_sort(spans.begin(), spans.end(),
                   [](const auto& a, const auto& b) { return a.first.size() < b.first.size(); });
  for (const auto& [span, n] : spans) {
    int left = n;
    double free_thickness = 0;
    std::vector<int> open;
    for (int l : span) {
      if (out.layers[l] > 0) {
        left -= out.layers[l];
      } else {
        open.push_back(l);
        free_thickness += s.levels[l + 1] - s.levels[l];
      }
    }
    if (left < int(open.size()) || (open.empty() && left != 0)) {
      why = "the given counts ask " + std::to_string(n) + " layers of slabs that already have " +
            std::to_string(n - left);
      return false;
    }
    for (std::size_t i = 0; i < open.size(); ++i) {
      const int l = open[i];
      const int k = i + 1 == open.size()
                        ? left
                        : std::max(1, int(std::lround(left * (s.levels[l + 1] - s.levels[l]) /
                                                      std::max(free_thickness, 1e-300))));
      const int k_ok = std::min(k, left - int(open.size() - i - 1));
      out.layers[l] = k_ok;
      left -= k_ok;
      free_thickness -= s.levels[l + 1] - s.levels[l];
    }
  }
  return true;
}

// The height of sloped cap k over the point b (anywhere on the line along the axis).
double sloped_height(const core::MeshDomain& solid, const occ::PrismaticStructure& s, int k,
                     const Vec3& b) {
  const Vec3 start = b + (s.levels[s.cap_level[k]] - s.height(b)) * s.axis;
  return s.height(detail::onto_face_along(solid, s.caps[k], start, s.axis));
}

// The sloped cap at level l covering region f, or -1.
int sloped_cap_over(const occ::PrismaticStructure& s, int f, int l) {
  for (int k : s.covering_caps[f])
    if (s.cap_sloped[k] && s.cap_level[k] == l) return k;
  return -1;
}

// Fills p.level_height where a cap is sloped. False with why where a level breaks (a sloped
// cap's rim meets a region where that level is flat off its height) or a slab over a node
// would keep less than a fiftieth of its thickness.
bool sloped_levels(const core::MeshDomain& solid, Plan& p, std::string& why) {
  const occ::PrismaticStructure& s = p.structure;
  if (std::none_of(s.cap_sloped.begin(), s.cap_sloped.end(), [](bool b) { return b; })) return true;
  const FaceSetMesh& F = p.regions;
  const int levels = int(s.levels.size()), slabs = levels - 1;
  const double tol = std::max(1e-6 * solid.diagonal(), 10 * solid.tolerance());
  p.level_height.assign(F.points.size(), s.levels);
  std::vector<std::vector<char>> on_slope(F.points.size(), std::vector<char>(levels, 0));
  auto used = [&](int f, int l) {
    return (l > 0 && s.inside[f][l - 1]) || (l < slabs && s.inside[f][l]);
  };
  for (int f = 1; f < int(F.quads.size()); ++f)
    for (int l = 0; l < levels; ++l) {
      const int k = sloped_cap_over(s, f, l);
      if (k < 0 || !used(f, l)) continue;
      for (const auto& q : F.quads[f])
        for (int n : q)
          if (!on_slope[n][l]) {  // a ridge's nodes: from the first cap (they meet there)
            p.level_height[n][l] = sloped_height(solid, s, k, F.points[n]);
            on_slope[n][l] = 1;
          }
    }
  for (int f = 1; f < int(F.quads.size()); ++f)
    for (int l = 0; l < levels; ++l) {
      if (!used(f, l) || sloped_cap_over(s, f, l) >= 0) continue;
      for (const auto& q : F.quads[f])
        for (int n : q)
          if (on_slope[n][l] && std::abs(p.level_height[n][l] - s.levels[l]) > tol) {
            why = "a sloped cap's rim leaves the height of level " + std::to_string(l + 1) +
                  " where that level is flat";
            return false;
          }
    }
  for (int f = 1; f < int(F.quads.size()); ++f)
    for (int l = 0; l < slabs; ++l) {
      if (!s.inside[f][l]) continue;
      const double least = 0.02 * (s.levels[l + 1] - s.levels[l]);
      for (const auto& q : F.quads[f])
        for (int n : q)
          if (p.level_height[n][l + 1] - p.level_height[n][l] < least) {
            why = "a sloped cap leaves slab " + std::to_string(l + 1) + " almost no thickness";
            return false;
          }
    }
  return true;
}

Plan plan(const core::MeshDomain& solid, const MultisweepOptions& options,
          const core::Progress& progress) {
  options.validate();
  Plan p;
  p.structure = occ::prismatic_structure(solid);
  if (!p.structure.ok) {
    p.diagnostics.push_back(core::make_error(
        "not_applicable", "The solid is not prismatic: " + p.structure.reason + "."));
    return p;
  }
  const occ::PrismaticStructure& s = p.structure;
  FixedCounts fixed;
  std::string why;
  if (!fixed_counts(solid, s, options, fixed, why)) {
    p.diagnostics.push_back(core::make_error(
        "intervals_infeasible", "The multisweep cannot meet the given counts: " + why + "."));
    return p;
  }
  FaceSetOptions fo;
  fo.fixed_sums = fixed.sums;
  fo.given_edge_points = fixed.points;
  fo.size = options.size;
  fo.max_intervals = options.max_intervals;
  fo.smoothing_passes = options.smoothing_passes;
  // Local sizes: the cross-section refines wherever any slab (its levels and middles) asks.
  core::SizeField section_field;
  if (detail::graded(options.size_field)) {
    std::vector<double> heights;
    for (std::size_t l = 0; l < s.levels.size(); ++l) {
      heights.push_back(s.levels[l]);
      if (l + 1 < s.levels.size()) heights.push_back(0.5 * (s.levels[l] + s.levels[l + 1]));
    }
    section_field = options.size_field->extruded(s.origin, s.axis, heights);
    fo.size_field = &section_field;
  }
  p.regions = mesh_face_set(*s.arrangement, fo, progress);
  if (!p.regions.ok) {
    p.diagnostics = p.regions.diagnostics;
    return p;
  }
  if (!sloped_levels(solid, p, why)) {
    p.diagnostics.push_back(
        core::make_error("not_applicable", "The solid is not prismatic: " + why + "."));
    return p;
  }
  const std::size_t slabs = s.levels.size() - 1;
  p.heights.push_back(s.levels[0]);
  p.level_z.push_back(0);
  for (std::size_t l = 0; l < slabs; ++l) {
    const double t = s.levels[l + 1] - s.levels[l];
    // With local sizes: the finest column over the section's vertices sets the layers and
    // their spacing (one set of heights per slab).
    double want = t / options.size;
    Vec3 column = s.origin;
    if (detail::graded(options.size_field))
      for (core::VertexId v : s.arrangement->vertices()) {
        const Vec3 b = s.arrangement->vertex_point(v);
        const Vec3 lo = b + (s.levels[l] - s.height(b)) * s.axis, hi = lo + t * s.axis;
        const double n = options.size_field->segments_along({lo, lo + 0.5 * (hi - lo), hi});
        if (n > want) want = n, column = lo;
      }
    const double k =
        fixed.layers[l] > 0 ? double(fixed.layers[l]) : std::max(1.0, std::round(want));
    if (k > options.max_intervals) {
      std::ostringstream m;
      m << "A slab " << t << " thick at size " << options.size << " needs " << k
        << " layers, more than max_intervals = " << options.max_intervals << ".";
      p.diagnostics.push_back(core::make_error("too_many_intervals", m.str()));
      return p;
    }
    p.layers.push_back(int(k));
    if (!fixed.heights[l].empty()) {  // a neighbour's nodes on an edge along the axis
      for (std::size_t i = 1; i < fixed.heights[l].size(); ++i)
        p.heights.push_back(fixed.heights[l][i]);
      p.level_z.push_back(int(p.heights.size()) - 1);
      continue;
    }
    const std::vector<double> w =
        detail::graded_parameters(column, column + t * s.axis, int(k), options.size_field);
    for (int i = 1; i <= int(k); ++i)
      p.heights.push_back(i == int(k) ? s.levels[l + 1] : s.levels[l] + t * w[i]);
    p.level_z.push_back(int(p.heights.size()) - 1);
  }
  p.ok = true;
  return p;
}

// Per 2-D node, whether it is used in each slab (a region around it lies inside the slab).
std::vector<std::vector<bool>> node_slabs(const Plan& p) {
  const auto& s = p.structure;
  std::vector<std::vector<bool>> used(p.regions.points.size(),
                                      std::vector<bool>(p.layers.size(), false));
  for (int f = 1; f < int(p.regions.quads.size()); ++f)
    for (std::size_t l = 0; l < p.layers.size(); ++l) {
      if (!s.inside[f][l]) continue;
      for (const auto& q : p.regions.quads[f])
        for (int n : q) used[n][l] = true;
    }
  return used;
}

}  // namespace

MultisweepApplicability multisweep_applicable(const core::MeshDomain& solid) {
  MultisweepApplicability a;
  const occ::PrismaticStructure s = occ::prismatic_structure(solid);
  a.ok = s.ok;
  a.reason = s.reason;
  if (s.ok) {
    a.axis = s.axis;
    a.levels = int(s.levels.size());
    a.regions = s.arrangement->num_faces();
  }
  return a;
}

namespace {
MultisweepEstimate estimate(const Plan& p) {
  MultisweepEstimate e;
  if (!p.ok) return e;
  for (int k : p.layers) e.layers += k;
  for (int f = 1; f < int(p.regions.quads.size()); ++f)
    for (std::size_t l = 0; l < p.layers.size(); ++l)
      if (p.structure.inside[f][l]) e.hexes += p.regions.quads[f].size() * std::size_t(p.layers[l]);
  // Nodes: per 2-D node, the heights of the slabs it is used in (levels counted once).
  for (const std::vector<bool>& slabs : node_slabs(p)) {
    std::size_t n = 0;
    for (std::size_t l = 0; l < slabs.size(); ++l) {
      if (!slabs[l]) continue;
      n += std::size_t(p.layers[l]) + ((l == 0 || !slabs[l - 1]) ? 1 : 0);
    }
    e.nodes += n;
  }
  return e;
}
}  // namespace

MultisweepEstimate multisweep_evaluate(const core::MeshDomain& solid,
                                       const MultisweepOptions& options) {
  return estimate(plan(solid, options, {}));
}

MultisweepResult multisweep(const core::MeshDomain& solid, const MultisweepOptions& options,
                            const core::Progress& progress) {
  MultisweepResult r;
  const char* stage = "multisweep";
  progress.report(stage, 0.0);
  Plan p = plan(solid, options, progress);
  r.diagnostics = std::move(p.diagnostics);
  if (!p.ok) return r;
  const occ::PrismaticStructure& s = p.structure;
  const occ::Solid& arr = *s.arrangement;
  const FaceSetMesh& F = p.regions;
  r.axis = s.axis;
  r.levels = int(s.levels.size());
  r.regions = arr.num_faces();
  for (int k : p.layers) r.layers += k;
  r.region_min_quality = F.min_quality;
  r.region_mean_quality = F.mean_quality;
  progress.report(stage, 0.2);

  const std::size_t slabs = p.layers.size(), nz = p.heights.size();
  // The slab of each height index strictly inside a slab; -1 at the levels.
  std::vector<int> slab_of(nz, -1), level_of(nz, -1);
  for (std::size_t l = 0; l <= slabs; ++l) level_of[p.level_z[l]] = int(l);
  for (std::size_t l = 0; l < slabs; ++l)
    for (int z = p.level_z[l] + 1; z < p.level_z[l + 1]; ++z) slab_of[z] = int(l);

  // Regions around each arrangement edge and vertex.
  std::vector<std::vector<int>> edge_regions(arr.num_edges() + 1),
      vertex_regions(arr.num_vertices() + 1);
  for (core::EdgeId e : arr.edges())
    for (core::FaceId f : arr.edge_faces(e)) {
      edge_regions[e.value()].push_back(f.value());
      for (core::VertexId v : {arr.edge_first_vertex(e), arr.edge_last_vertex(e)})
        if (v.valid()) vertex_regions[v.value()].push_back(f.value());
    }
  auto inside = [&](int f, int l) {
    return l >= 0 && l < int(slabs) && s.inside[f][std::size_t(l)];
  };

  // Which CAD entity a node at (arrangement entity, height index) lies on. Regions are
  // decided from the caps; edges and vertices of the arrangement by the CAD's distance.
  const double tol = std::max(1e-6 * solid.diagonal(), 10 * solid.tolerance());
  auto lookup = [&](const Vec3& q) { return detail::cad_entity_at(solid, q, tol); };
  std::map<std::tuple<int, int, int>, NodeClass> classes;
  auto classify = [&](NodeClass on, int z) {
    const auto key = std::make_tuple(int(on.dim), on.id, z);
    const auto it = classes.find(key);
    if (it != classes.end()) return it->second;
    const int lv = level_of[z];
    const std::vector<int>* around = nullptr;
    if (on.dim == 2) {
      static thread_local std::vector<int> one(1);
      one[0] = on.id;
      around = &one;
    } else {
      around = on.dim == 1 ? &edge_regions[on.id] : &vertex_regions[on.id];
    }
    // Inside all around (below and above at a level): an interior node.
    bool all_in = around->size() >= (on.dim == 2 ? 1u : 2u);
    for (int f : *around)
      all_in = all_in && (lv < 0 ? inside(f, slab_of[z]) : inside(f, lv - 1) && inside(f, lv));
    NodeClass c = NodeClass::interior();
    if (all_in && on.dim != 0) {
      c = NodeClass::interior();
    } else if (on.dim == 2) {
      // On the cap covering the region at this level.
      for (int k : s.covering_caps[on.id])
        if (s.cap_level[k] == lv) c = NodeClass::on(s.caps[k]);
    } else {
      const Vec3 base = on.dim == 0 ? arr.vertex_point(core::VertexId(on.id))
                                    : arr.edge_points_by_length(core::EdgeId(on.id), 2)[1];
      // A level over a sloped cap lies on it (any cap at that level around: they meet here).
      auto level_at = [&](int l) {
        for (int f : *around)
          if (const int k = sloped_cap_over(s, f, l); k >= 0)
            return sloped_height(solid, s, k, base);
        return s.levels[l];
      };
      const double h =
          lv >= 0 ? level_at(lv) : 0.5 * (level_at(slab_of[z]) + level_at(slab_of[z] + 1));
      c = lookup(base + (h - s.height(base)) * s.axis);
    }
    classes.emplace(key, c);
    return c;
  };

  core::HexMesh& mesh = r.mesh;
  std::unordered_map<std::uint64_t, std::int32_t> node_id;
  const MultisweepEstimate expected = estimate(p);
  node_id.reserve(expected.nodes);
  mesh.reserve(expected.nodes, expected.hexes);
  auto node = [&](int n2, int z) {
    const std::uint64_t key = std::uint64_t(n2) * nz + std::uint64_t(z);
    const auto it = node_id.find(key);
    if (it != node_id.end()) return it->second;
    const Vec3& b = F.points[n2];
    double h = p.heights[z];
    if (!p.level_height.empty()) {  // between the levels as they lie over this node
      const std::vector<double>& at = p.level_height[n2];
      if (level_of[z] >= 0) {
        h = at[level_of[z]];
      } else {
        const int l = slab_of[z];
        const double t = (h - s.levels[l]) / (s.levels[l + 1] - s.levels[l]);
        h = at[l] + t * (at[l + 1] - at[l]);
      }
    }
    const Vec3 q = b + (h - s.height(b)) * s.axis;
    const std::int32_t id = mesh.add_node(q, classify(F.on[n2], z)).value();
    node_id.emplace(key, id);
    return id;
  };
  std::size_t done = 0;
  const std::size_t total = std::max<std::size_t>(1, expected.hexes);
  for (std::size_t l = 0; l < slabs; ++l) {
    for (int f = 1; f <= arr.num_faces(); ++f) {
      if (!s.inside[f][l]) continue;
      for (const auto& q : F.quads[f]) {
        for (int k = 0; k < p.layers[l]; ++k) {
          const int z0 = p.level_z[l] + k, z1 = z0 + 1;
          core::HexNodes h;
          for (int c = 0; c < 4; ++c) {
            h[c] = node(q[c], z0);
            h[c + 4] = node(q[c], z1);
          }
          mesh.add_hex(h, 0);
        }
      }
      done += F.quads[f].size() * std::size_t(p.layers[l]);
      progress.report(stage, 0.2 + 0.8 * double(done) / double(total));
      if (progress.cancelled()) {
        r.mesh = core::HexMesh();
        r.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
        return r;
      }
    }
  }
  // Nodes on the solid's edges and faces put onto them where the arrangement traces an edge
  // by a curve through samples of it (occ::prismatic_structure: any edge but a line or a
  // circle across the axis), which a NURBS export's circle of radius 20 leaves 2.4e-4 off;
  // extruded from there, nodes lay off the CAD. Only nodes that near (1e-4 of the size), and
  // not those on vertices: a vertex's point may lie off its edges by its tolerance (HexMe
  // i16: 2.9e-4; two hexahedra folded there).
  const std::vector<core::EdgeId> edges = solid.edges();
  const bool traced = std::any_of(edges.begin(), edges.end(), [&](core::EdgeId e) {
    const core::CurveInfo c = solid.curve_info(e);
    return c.kind == core::CurveKind::other ||
           (c.kind == core::CurveKind::circle && std::abs(c.direction.dot(s.axis)) < 1 - 1e-9);
  });
  const double off = 1e-9 * solid.diagonal(), near = 1e-4 * solid.diagonal();
  for (std::size_t n = 0; traced && n < mesh.points().size(); ++n) {
    const core::NodeId id(static_cast<std::int32_t>(n));
    const core::NodeClass c = mesh.node_class(id);
    const Vec3& q = mesh.points()[n];
    Vec3 on = q;
    if (c.dim == 1) on = solid.project_to_edge(core::EdgeId(c.id), q);
    if (c.dim == 2) on = solid.project_to_face(core::FaceId(c.id), q);
    if (const double d = (on - q).norm(); d > off && d < near) mesh.set_point(id, on);
  }
  // The corners of an extruded quad are positive when the quad is (and its column rises); a
  // region whose quads turned the wrong way would show here.
  std::size_t folded = 0;
  for (const core::HexNodes& h : mesh.hexes()) {
    const auto c = [&](int i) -> const Vec3& { return mesh.points()[h[i]]; };
    bool bad = false;
    for (int i = 0; i < 4 && !bad; ++i) {
      const int n = (i + 1) % 4, pv = (i + 3) % 4;
      bad = (c(n) - c(i)).cross(c(pv) - c(i)).dot(c(i + 4) - c(i)) <= 0 ||
            (c(n + 4) - c(i + 4)).cross(c(pv + 4) - c(i + 4)).dot(c(i + 4) - c(i)) <= 0;
    }
    folded += bad;
  }
  if (folded > 0) {
    r.diagnostics.push_back(core::make_error(
        "inverted_elements", std::to_string(folded) +
                                 " extruded hexahedra have a non-positive corner Jacobian (the "
                                 "quads of their region fold)."));
    r.mesh = core::HexMesh();
    return r;
  }
  r.ok = true;
  return r;
}

}  // namespace vorohex::mesh
