#include "pipeline/detail/finish.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/progress.h"
#include "grid/boundary_pillow.h"
#include "io/named_groups.h"
#include "io/second_order.h"
#include "quality/check_mesh.h"
#include "smooth/smooth_mesh.h"

namespace vorohex::pipeline::detail {

using core::append;
using core::seconds_since;

std::string type_of_scheme(const std::string& scheme) {
  if (scheme == "sweep" || scheme == "multisweep") return "Vs";
  return scheme == "map" || scheme == "midpoint" ? "Ve" : "-";
}

// The tet split's boundary vertices lie on the CAD from the start (CGAL puts them there) and
// smoothing slides them along their faces and edges: the volume the tetrahedra's surface
// cuts off stays about what it was. Where that is several times what the check allows, the
// tetrahedra missed features (HexMe i08: blades about 1 mm thick at size 10, 34 % of the
// volume), and no smoothing makes the mesh valid; it ran for 60 s before the check said so.
// Measured on the 28 HexMe models that reach the fallback: before smoothing the tet split's
// volume error is at most 0.71 times the allowance on 27 of them, 5.1 times on i08.
constexpr double kLostVolumeFactor = 2;

// Why the mesh is not worth smoothing (its volume error beyond kLostVolumeFactor times the
// check's allowance), or "".
std::string lost_volume(const core::HexMesh& mesh, const occ::Solid& solid,
                        const quality::CheckOptions& options) {
  const quality::CheckReport before = quality::check_mesh(mesh, &solid, options);
  const double error = std::abs(before.mesh_volume - before.cad_volume);
  if (!(error > kLostVolumeFactor * before.volume_allowance)) return "";
  std::ostringstream s;
  s << "The mesh was not smoothed: its volume " << before.mesh_volume
    << " differs from the solid's " << before.cad_volume << " by " << error << ", "
    << error / before.volume_allowance
    << " times what the check allows: the tetrahedra missed features of the part (walls or "
       "blades thinner than the size), which moving nodes on the CAD cannot restore.";
  return s.str();
}

void finish(MeshResult& result, const occ::Solid& solid, const MeshOptions& options,
            const core::Progress& progress, const core::SizeField& sizes) {
  if (result.stats.sub_volumes == 0) result.stats.sub_volumes = 1;
  if (result.stats.sub_volume_schemes.empty())
    result.stats.sub_volume_schemes.assign(result.stats.sub_volumes, result.stats.scheme);
  if (result.stats.sub_volume_types.size() != result.stats.sub_volume_schemes.size()) {
    result.stats.sub_volume_types.clear();
    for (const std::string& s : result.stats.sub_volume_schemes)
      result.stats.sub_volume_types.push_back(type_of_scheme(s));
  }

  if (progress.cancelled()) {
    result.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
    return;
  }

  // Global smoothing with nodes kept on their CAD entities; it never lowers the minimum
  // scaled Jacobian and never inverts an element. It moves nodes, so it cannot close an
  // open boundary or mend a quad more than two hexes share: such a mesh goes straight to
  // the check (HexMe i07's tetrahedra, 134,536 hexes with two open edges, were smoothed
  // for 40 s before the check found them open).
  const auto ts = std::chrono::steady_clock::now();
  bool smoothing =
      options.smoothing.laplacian_iterations > 0 || options.smoothing.optimisation_passes > 0;
  if (smoothing && result.mesh.num_hexes() > 0) {
    const quality::CheckReport topology = quality::check_topology(result.mesh);
    if (topology.open_boundary_edges > 0 || topology.non_manifold_quads > 0) {
      smoothing = false;
      std::ostringstream s;
      s << "The mesh was not smoothed: its boundary has " << topology.open_boundary_edges
        << " open edges and " << topology.non_manifold_quads
        << " quads are shared by more than two hexahedra, which moving nodes cannot mend.";
      result.diagnostics.push_back(core::make_info("smoothing_skipped", s.str()));
    }
  }
  if (smoothing && result.stats.scheme == "tet-split" && result.mesh.num_hexes() > 0) {
    if (std::string why = lost_volume(result.mesh, solid, options.check); !why.empty()) {
      smoothing = false;
      result.diagnostics.push_back(core::make_info("smoothing_skipped", why));
    }
  }
  if (smoothing) {
    smooth::SmoothOptions so = options.smoothing;
    so.size_field = &sizes;  // keeps a graded mesh graded
    const smooth::SmoothResult smoothed = smooth::smooth_mesh(result.mesh, solid, so, progress);
    append(result.diagnostics, smoothed.diagnostics);
    result.stats.min_sj_before_smoothing = smoothed.min_before;
    result.stats.mean_sj_before_smoothing = smoothed.mean_before;
    if (smoothed.status == smooth::SmoothStatus::cancelled) {
      result.mesh = core::HexMesh();  // a cancelled run hands over nothing
      return;
    }
  }
  result.stats.seconds_smoothing = seconds_since(ts);

  // Named groups per CAD entity; second order adds the mid-edge nodes (on the CAD where the
  // edge is), after smoothing, which moves corners only.
  result.groups = io::named_groups(result.mesh, solid);
  io::SecondOrderStats second;
  if (options.order == 2 && result.mesh.num_hexes() > 0) {
    second = io::make_second_order(result.mesh, solid, result.groups);
    if (second.straightened)
      result.diagnostics.push_back(core::make_warning(
          "mid_nodes_straightened",
          std::to_string(second.straightened) +
              " mid-edge nodes were put back on their straight edge because on the CAD they "
              "folded an element; they lie off the curved surface by the chord height"));
    result.groups = io::named_groups(result.mesh, solid);
  }

  // Never hand over an unchecked mesh: the validity check runs on every result.
  progress.report("check", 0.0);
  const auto t1 = std::chrono::steady_clock::now();
  result.check = quality::check_mesh(result.mesh, &solid, options.check, &result.scaled_jacobian);
  if (!smoothing) {  // not smoothed: "before smoothing" is the mesh as checked
    result.stats.min_sj_before_smoothing = result.check.scaled_jacobian.min;
    result.stats.mean_sj_before_smoothing = result.check.scaled_jacobian.mean;
  }
  result.stats.seconds_checking = seconds_since(t1);
  progress.report("check", 1.0);
  // Straightened mid-edge nodes off the CAD: say what they are and what helps.
  if (second.straightened)
    for (core::Diagnostic& d : result.check.diagnostics)
      if (d.code == "nodes_off_cad")
        d.message += std::string(!d.message.empty() && d.message.back() == '.' ? "" : ".") + " " +
                     std::to_string(second.straightened) +
                     " mid-edge nodes were put back straight (mid_nodes_straightened): at this "
                     "size some elements are too thin for the curvature of their face. Give a "
                     "smaller size (more elements across the curved faces) or first-order "
                     "elements.";
  append(result.diagnostics, result.check.diagnostics);
  result.ok = result.check.valid && !core::has_error(result.diagnostics);
}

// Below this a structured mesh with flat doublets gets the pillow layer; the pillowed mesh
// must be this much better to replace it. What two faces nearly flat means: outward normals
// within kFlatTurn degrees (two layers across a 90-degree fillet: 22.5; a 45-degree chamfer's
// slab, 45, is not one: 0.577 as it is).
constexpr double kFlatPillowBar = 0.4;
constexpr double kFlatPillowGain = 0.05;
constexpr double kFlatTurn = 30;

std::vector<core::Diagnostic> diagnostics_of_making(const MeshResult& result) {
  std::vector<core::Diagnostic> out;
  for (const core::Diagnostic& d : result.diagnostics) {
    bool from_check = d.severity == core::Severity::error || d.code == "smoothing_skipped" ||
                      d.code == "edge_nodes_released";
    for (const core::Diagnostic& c : result.check.diagnostics) from_check |= c.code == d.code;
    if (!from_check) out.push_back(d);
  }
  return out;
}

namespace {

// The first-order mesh under a second-order one: its corner nodes (make_second_order adds the
// mid-edge nodes after them) and hexahedra.
core::HexMesh first_order(const core::HexMesh& mesh) {
  std::size_t corners = mesh.num_nodes();
  for (const core::MidEdgeNodes& m : mesh.mid_edge_nodes())
    for (std::int32_t v : m) corners = std::min(corners, std::size_t(v));
  core::HexMesh out;
  out.reserve(corners, mesh.num_hexes());
  for (std::size_t v = 0; v < corners; ++v) {
    const core::NodeId id{std::int32_t(v)};
    out.add_node(mesh.point(id), mesh.node_class(id));
  }
  for (std::size_t h = 0; h < mesh.num_hexes(); ++h) {
    const core::HexId id{std::int32_t(h)};
    out.add_hex(mesh.hex(id), mesh.sub_volume(id));
  }
  return out;
}

}  // namespace

void pillow_flat_doublets(MeshResult& result, const occ::Solid& solid, const MeshOptions& options,
                          const core::Progress& progress, const core::SizeField& sizes) {
  // Not a fallback's mesh, nor several solids' where one of them is (scheme "sweep+grid").
  const std::string& scheme = result.stats.scheme;
  if (!result.ok || scheme.find("grid") != std::string::npos ||
      scheme.find("tet-split") != std::string::npos || result.mesh.num_hexes() == 0 ||
      progress.cancelled() || result.check.scaled_jacobian.min >= kFlatPillowBar)
    return;
  // Second order: the pillow goes under its corners' mesh, whose mid-edge nodes finish makes
  // again.
  core::HexMesh corners =
      result.mesh.order() == 2 ? first_order(result.mesh) : core::HexMesh(result.mesh);
  const std::size_t flat = grid::flat_doublets(corners, kFlatTurn);
  if (flat == 0) return;
  MeshResult again;
  again.stats = result.stats;
  again.mesh = std::move(corners);
  again.diagnostics = diagnostics_of_making(result);
  const grid::BoundaryPillowResult p = grid::pillow_boundary(again.mesh);
  if (again.mesh.num_hexes() > options.max_hexes) return;
  finish(again, solid, options, progress, sizes);
  if (progress.cancelled()) {  // as a cancel during the smoothing: no mesh handed over
    result.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
    result.ok = false;
    result.mesh = core::HexMesh();
    return;
  }
  // "Before smoothing" stays the mesh as its scheme made it, not the pillowed one.
  again.stats.min_sj_before_smoothing = result.stats.min_sj_before_smoothing;
  again.stats.mean_sj_before_smoothing = result.stats.mean_sj_before_smoothing;
  const double before = result.check.scaled_jacobian.min;
  const double after = again.check.scaled_jacobian.min;
  std::ostringstream s;
  s << std::setprecision(3) << flat << (flat == 1 ? " hexahedron has" : " hexahedra have")
    << " two boundary quads nearly flat across an edge (a tangent edge, as a fillet's), where no "
       "smoothing opens its angle; a pillow layer under the boundary ("
    << p.hexes_added << " hexahedra, one per boundary quad)";
  if (again.ok && after >= before + kFlatPillowGain) {
    s << " raised the minimum scaled Jacobian from " << before << " to " << after
      << ": that mesh is used.";
    again.diagnostics.push_back(core::make_warning("boundary_pillowed", s.str()));
    result = std::move(again);
    return;
  }
  if (again.ok)
    s << " gave min scaled Jacobian " << after;
  else
    s << " gave an invalid mesh (" << core::error_codes(again.diagnostics) << ")";
  s << ", not better than " << before << ": the mesh stays.";
  result.diagnostics.push_back(core::make_info("boundary_pillow_failed", s.str()));
}

}  // namespace vorohex::pipeline::detail
