#include "mesh/revolve.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>

#include "core/option_checks.h"
#include "mesh/detail/cad_lookup.h"
#include "mesh/detail/sizing.h"
#include "mesh/face_set.h"
#include "occ/revolution.h"

namespace vorohex::mesh {

using core::EdgeId;
using core::NodeClass;
using core::Vec3;
using Vec2 = Eigen::Vector2d;

void RevolveOptions::validate() const {
  core::require_positive("RevolveOptions.size", size);
  core::require_at_least("RevolveOptions.max_intervals", max_intervals, 1);
  core::require_at_least("RevolveOptions.smoothing_passes", smoothing_passes, 0);
  if (sectors != 0 && (sectors < 8 || sectors % 4 != 0))
    throw std::invalid_argument(
        "RevolveOptions.sectors must be 0 or a multiple of 4, at least 8 (got " +
        std::to_string(sectors) + ")");
  for (std::size_t e = 0; e < edge_intervals.size(); ++e)
    if (edge_intervals[e] < 0)
      throw std::invalid_argument("RevolveOptions.edge_intervals must not be negative (edge " +
                                  std::to_string(e) + ")");
}

namespace {

const double kPi = 3.14159265358979323846;

// An O-grid disc of radius 1 whose rim has 4m nodes at the angles 2 pi k / 4m: a square of
// m x m quads with corners at radius `ratio` on the angles 0, 90, 180, 270 degrees, and
// four blocks of m x layers quads between its sides and the rim. Quads counter-clockwise.
struct Disc {
  std::vector<Vec2> points;
  std::vector<int> rim;  // node of rim position k (angle 2 pi k / 4m)
  std::vector<std::array<int, 4>> quads;
};

Disc o_grid_disc(int m, int layers, double ratio) {
  Disc d;
  auto corner = [&](int b) {
    return Vec2(ratio * std::cos(kPi / 2 * b), ratio * std::sin(kPi / 2 * b));
  };
  const Vec2 c0 = corner(0), du = corner(1) - c0, dv = corner(3) - c0;
  std::vector<int> centre((m + 1) * (m + 1));
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= m; ++i) {
      centre[j * (m + 1) + i] = int(d.points.size());
      d.points.push_back(c0 + double(i) / m * du + double(j) / m * dv);
    }
  auto at = [&](int i, int j) { return centre[j * (m + 1) + i]; };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i)
      d.quads.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
  // Side b of the square, position k (from corner b to corner b + 1).
  auto side = [&](int b, int k) {
    switch (b) {
      case 0:
        return at(k, 0);
      case 1:
        return at(m, k);
      case 2:
        return at(m - k, m);
      default:
        return at(0, m - k);
    }
  };
  const int n = 4 * m;
  // Block nodes (b, k, t): t = 0 on the side, t = layers on the rim; k = m is the next
  // block's k = 0.
  std::map<std::array<int, 3>, int> block;
  auto node = [&](int b, int k, int t) -> int {
    if (k == m) b = (b + 1) % 4, k = 0;
    if (t == 0) return side(b, k);
    const auto it = block.find({b, k, t});
    if (it != block.end()) return it->second;
    const double angle = 2 * kPi * (b * m + k) / n;
    const Vec2 rim(std::cos(angle), std::sin(angle));
    const Vec2& inner = d.points[side(b, k)];
    const double w = double(t) / layers;
    const int id = int(d.points.size());
    d.points.push_back((1 - w) * inner + w * rim);
    block.emplace(std::array<int, 3>{b, k, t}, id);
    return id;
  };
  for (int b = 0; b < 4; ++b)
    for (int k = 0; k < m; ++k)
      for (int t = 0; t < layers; ++t)
        d.quads.push_back(
            {node(b, k, t), node(b, k, t + 1), node(b, k + 1, t + 1), node(b, k + 1, t)});
  d.rim.resize(n);
  for (int b = 0; b < 4; ++b)
    for (int k = 0; k < m; ++k) d.rim[b * m + k] = node(b, k, layers);
  return d;
}

// The section's edge that traces the solid's meridian edge e (a seam a neighbour shares),
// matched by their ends' heights and radii (the section lies in another half-plane): its id
// (0: none, or e is a circle about the axis) and whether it runs the other way.
struct SectionEdge {
  int id = 0;
  bool reversed = false;
};
SectionEdge section_edge(const core::MeshDomain& solid, const occ::RevolutionStructure& s,
                         EdgeId e) {
  const occ::Solid& sec = *s.section;
  const double tol = std::max(1e-6 * solid.diagonal(), 10 * solid.tolerance());
  auto hr = [&](const Vec3& p) { return Vec2(s.height(p), s.radius(p)); };
  auto ends = [&](const core::MeshDomain& d, EdgeId x) {
    const std::vector<Vec3> q = d.edge_points_by_length(x, 2);
    return std::array<Vec2, 3>{hr(q[0]), hr(q[1]), hr(q[2])};
  };
  if (solid.edge_is_degenerated(e)) return {};
  const auto a = ends(solid, e);
  if ((a[0] - a[2]).norm() <= tol) return {};  // a circle about the axis
  for (EdgeId f : sec.edges()) {
    const auto b = ends(sec, f);
    if ((a[1] - b[1]).norm() > tol) continue;
    if ((a[0] - b[0]).norm() <= tol && (a[2] - b[2]).norm() <= tol) return {f.value(), false};
    if ((a[0] - b[2]).norm() <= tol && (a[2] - b[0]).norm() <= tol) return {f.value(), true};
  }
  return {};
}

// The section's counts and given nodes from the solid's meridian edges' (options.edge_intervals,
// options.edge_nodes), turned into the section's half-plane.
void given_on_section(const core::MeshDomain& solid, const occ::RevolutionStructure& s,
                      const RevolveOptions& options, FaceSetOptions& fo) {
  const std::size_t n = std::size_t(s.section->num_edges()) + 1;
  fo.fixed_counts.assign(n, 0);
  fo.given_edge_points.assign(n, {});
  const std::size_t edges = std::max(options.edge_intervals.size(), options.edge_nodes.size());
  for (std::size_t e = 1; e < edges; ++e) {
    const int count = e < options.edge_intervals.size() ? options.edge_intervals[e] : 0;
    const bool nodes = e < options.edge_nodes.size() && options.edge_nodes[e].size() >= 2;
    if (count <= 0 && !nodes) continue;
    const SectionEdge f = section_edge(solid, s, EdgeId(int(e)));
    if (f.id == 0) continue;
    if (count > 0) fo.fixed_counts[f.id] = count;
    if (!nodes) continue;
    std::vector<Vec3> q;
    for (const Vec3& p : options.edge_nodes[e])
      q.push_back(s.origin + s.height(p) * s.axis + s.radius(p) * s.radial);
    if (f.reversed) std::reverse(q.begin(), q.end());
    fo.fixed_counts[f.id] = int(q.size()) - 1;
    fo.given_edge_points[f.id] = std::move(q);
  }
}

struct Plan {
  occ::RevolutionStructure structure;
  FaceSetMesh section;
  int sectors = 0;
  Disc disc;
  std::vector<std::vector<int>> core_levels;  // per core: section nodes along its side, by height
  bool ok = false;
  std::vector<core::Diagnostic> diagnostics;
};

Plan plan(const core::MeshDomain& solid, const RevolveOptions& options,
          const core::Progress& progress) {
  options.validate();
  Plan p;
  p.structure = occ::revolution_structure(solid);
  const occ::RevolutionStructure& s = p.structure;
  if (!s.ok) {
    p.diagnostics.push_back(core::make_error(
        "not_applicable", "The solid is not a solid of revolution: " + s.reason + "."));
    return p;
  }
  FaceSetOptions fo;
  fo.size = options.size;
  fo.max_intervals = options.max_intervals;
  fo.smoothing_passes = options.smoothing_passes;
  // Local sizes: the section refines wherever the field asks at any of 16 turns about the axis.
  core::SizeField section_field;
  if (detail::graded(options.size_field)) {
    section_field = options.size_field->revolved(s.origin, s.axis, 16);
    fo.size_field = &section_field;
  }
  if (!options.edge_intervals.empty() || !options.edge_nodes.empty())
    given_on_section(solid, s, options, fo);
  p.section = mesh_face_set(*s.section, fo, progress);
  if (!p.section.ok) {
    p.diagnostics = p.section.diagnostics;
    return p;
  }
  // Sectors: one count for the whole turn, the finest any section node asks for.
  double turn = 2 * kPi * s.max_radius / options.size;
  if (detail::graded(options.size_field))
    for (const Vec3& q : p.section.points)
      turn = std::max(turn, 2 * kPi * s.radius(q) / section_field.at(q));
  const double quarter = std::ceil(turn / 4);
  if (4 * quarter > options.max_intervals) {
    std::ostringstream m;
    m << "A full turn of radius " << s.max_radius << " at size " << options.size << " needs "
      << 4 * quarter << " sectors, more than max_intervals = " << options.max_intervals << ".";
    p.diagnostics.push_back(core::make_error("too_many_intervals", m.str()));
    return p;
  }
  const int m = options.sectors > 0 ? options.sectors / 4 : std::max(2, int(quarter));
  p.sectors = 4 * m;
  const double tol = std::max(1e-6 * solid.diagonal(), 10 * solid.tolerance());
  for (const Vec3& q : p.section.points)
    if (s.radius(q) <= tol) {
      p.diagnostics.push_back(core::make_error(
          "not_applicable", "The solid's section touches its axis where no core fits."));
      return p;
    }
  if (!s.cores.empty()) {
    const double rc = s.core_radius;
    const double ratio = 0.55;
    double core_size = options.size;
    if (detail::graded(options.size_field))
      for (const occ::RevolutionCore& c : s.cores)
        core_size = std::min(core_size, section_field.at(s.origin + 0.5 * (c.z0 + c.z1) * s.axis));
    const int layers = std::max(1, int(std::lround((1 - ratio) * rc / core_size)));
    p.disc = o_grid_disc(m, layers, ratio);
    for (const occ::RevolutionCore& c : s.cores) {
      std::vector<std::pair<double, int>> side;
      for (std::size_t n = 0; n < p.section.points.size(); ++n) {
        const Vec3& q = p.section.points[n];
        const double h = s.height(q);
        if (std::abs(s.radius(q) - rc) <= tol && h >= c.z0 - tol && h <= c.z1 + tol)
          side.emplace_back(h, int(n));
      }
      std::sort(side.begin(), side.end());
      std::vector<int> levels;
      for (const auto& [h, n] : side) levels.push_back(n);
      if (levels.size() < 2) {
        p.diagnostics.push_back(
            core::make_error("not_applicable", "A core of the solid has no nodes on its side."));
        return p;
      }
      p.core_levels.push_back(std::move(levels));
    }
  }
  p.ok = true;
  return p;
}

RevolveEstimate estimate(const Plan& p) {
  RevolveEstimate e;
  if (!p.ok) return e;
  e.sectors = p.sectors;
  e.nodes = p.section.points.size() * std::size_t(p.sectors);
  e.hexes = p.section.num_quads() * std::size_t(p.sectors);
  const std::size_t inner = p.disc.points.size() - p.disc.rim.size();
  for (const auto& levels : p.core_levels) {
    e.nodes += inner * levels.size();
    e.hexes += p.disc.quads.size() * (levels.size() - 1);
  }
  return e;
}

}  // namespace

RevolveApplicability revolve_applicable(const core::MeshDomain& solid) {
  RevolveApplicability a;
  const occ::RevolutionStructure s = occ::revolution_structure(solid);
  a.ok = s.ok;
  a.reason = s.reason;
  a.origin = s.origin;
  a.axis = s.axis;
  a.cores = int(s.cores.size());
  return a;
}

RevolveEstimate revolve_evaluate(const core::MeshDomain& solid, const RevolveOptions& options) {
  return estimate(plan(solid, options, {}));
}

RevolveResult revolve(const core::MeshDomain& solid, const RevolveOptions& options,
                      const core::Progress& progress) {
  RevolveResult r;
  const char* stage = "revolve";
  progress.report(stage, 0.0);
  Plan p = plan(solid, options, progress);
  r.diagnostics = std::move(p.diagnostics);
  if (!p.ok) return r;
  const occ::RevolutionStructure& s = p.structure;
  const FaceSetMesh& F = p.section;
  const occ::Solid& sec = *s.section;
  const int N = p.sectors;
  r.origin = s.origin;
  r.axis = s.axis;
  r.sectors = N;
  r.cores = int(s.cores.size());
  r.core_radius = s.core_radius;
  r.section_min_quality = F.min_quality;
  r.section_mean_quality = F.mean_quality;
  progress.report(stage, 0.2);

  // The section lies in the half-plane along `radial`; the sectors start at `er`, through
  // the given start point where there is one (a neighbour meshes a circle it shares from
  // that circle's vertex).
  const Vec3 radial = s.radial;
  Vec3 er = radial, et = s.axis.cross(radial);
  if (options.has_start) {
    const Vec3 d = options.start - s.origin;
    const double phase = std::atan2(d.dot(et), d.dot(er));
    er = std::cos(phase) * radial + std::sin(phase) * et;
    et = s.axis.cross(er);
  }
  std::vector<double> cosine(N), sine(N);
  for (int i = 0; i < N; ++i)
    cosine[i] = std::cos(2 * kPi * i / N), sine[i] = std::sin(2 * kPi * i / N);
  auto turned = [&](const Vec3& q, int i) {
    const double h = s.height(q), rad = (q - s.origin - h * s.axis).dot(radial);
    return Vec3(s.origin + h * s.axis + rad * (cosine[i] * er + sine[i] * et));
  };

  // Classes of the revolved nodes: per section entity and sector, by the CAD's distance
  // (a face of revolution may be split by seams into faces that hold different sectors).
  const double tol = std::max(1e-6 * solid.diagonal(), 10 * solid.tolerance());
  std::map<std::pair<int, int>, std::vector<NodeClass>> classes;  // (dim, id) -> per sector
  auto classes_of = [&](NodeClass on) -> const std::vector<NodeClass>& {
    const auto key = std::make_pair(int(on.dim), on.id);
    auto it = classes.find(key);
    if (it != classes.end()) return it->second;
    std::vector<NodeClass> per(N, NodeClass::interior());
    if (on.dim < 2 && !(on.dim == 1 && s.core_side[on.id])) {
      const Vec3 base = on.dim == 0 ? sec.vertex_point(core::VertexId(on.id))
                                    : sec.edge_points_by_length(core::EdgeId(on.id), 2)[1];
      NodeClass hint = NodeClass::interior();
      for (int i = 0; i < N; ++i)
        per[i] = hint = detail::cad_entity_at(solid, turned(base, i), tol, hint);
    }
    return classes.emplace(key, std::move(per)).first->second;
  };

  core::HexMesh& mesh = r.mesh;
  const RevolveEstimate expected = estimate(p);
  mesh.reserve(expected.nodes, expected.hexes);
  for (std::size_t n = 0; n < F.points.size(); ++n) {
    const std::vector<NodeClass>& c = classes_of(F.on[n]);
    for (int i = 0; i < N; ++i) mesh.add_node(turned(F.points[n], i), c[i]);
  }
  auto id = [&](int n, int i) { return std::int32_t(n * N + (i % N)); };
  for (int f = 1; f < int(F.quads.size()); ++f) {
    for (const auto& q : F.quads[f])
      for (int i = 0; i < N; ++i) {
        core::HexNodes h;
        for (int c = 0; c < 4; ++c) {
          h[c] = id(q[c], i);
          h[c + 4] = id(q[c], i + 1);
        }
        mesh.add_hex(h, 0);
      }
    if (progress.cancelled()) {
      r.mesh = core::HexMesh();
      r.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
      return r;
    }
  }
  progress.report(stage, 0.7);
  // Cores: the disc at each node height of the core's side, its rim the revolved nodes.
  for (std::size_t k = 0; k < s.cores.size(); ++k) {
    const occ::RevolutionCore& core = s.cores[k];
    const std::vector<int>& levels = p.core_levels[k];
    const Disc& d = p.disc;
    std::vector<int> is_rim(d.points.size(), -1);
    for (int i = 0; i < N; ++i) is_rim[d.rim[i]] = i;
    std::vector<std::vector<std::int32_t>> ids(levels.size(),
                                               std::vector<std::int32_t>(d.points.size()));
    for (std::size_t j = 0; j < levels.size(); ++j) {
      const double h = s.height(F.points[levels[j]]);
      const NodeClass c = j == 0                   ? NodeClass::on(core.bottom)
                          : j + 1 == levels.size() ? NodeClass::on(core.top)
                                                   : NodeClass::interior();
      for (std::size_t n = 0; n < d.points.size(); ++n) {
        if (is_rim[n] >= 0) {
          ids[j][n] = id(levels[j], is_rim[n]);
          continue;
        }
        const Vec2 q = s.core_radius * d.points[n];
        ids[j][n] = mesh.add_node(s.origin + h * s.axis + q.x() * er + q.y() * et, c).value();
      }
    }
    for (std::size_t j = 0; j + 1 < levels.size(); ++j)
      for (const auto& q : d.quads) {
        core::HexNodes h;
        for (int c = 0; c < 4; ++c) {
          h[c] = ids[j][q[c]];
          h[c + 4] = ids[j + 1][q[c]];
        }
        mesh.add_hex(h, 0);
      }
  }
  std::size_t folded = 0;
  for (const core::HexNodes& h : mesh.hexes()) {
    const auto c = [&](int i) -> const Vec3& { return mesh.points()[h[i]]; };
    bool bad = false;
    for (int i = 0; i < 4 && !bad; ++i) {
      const int n = (i + 1) % 4, pv = (i + 3) % 4;
      bad = (c(n) - c(i)).cross(c(pv) - c(i)).dot(c(i + 4) - c(i)) <= 0;
    }
    folded += bad;
  }
  if (folded > 0) {
    r.diagnostics.push_back(core::make_error(
        "inverted_elements", std::to_string(folded) +
                                 " revolved hexahedra have a non-positive corner Jacobian (the "
                                 "quads of the section fold)."));
    r.mesh = core::HexMesh();
    return r;
  }
  progress.report(stage, 1.0);
  r.ok = true;
  return r;
}

}  // namespace vorohex::mesh
