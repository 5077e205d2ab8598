#include "grid/grid_mesh.h"

#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "core/progress.h"
#include "grid/detail/adaptive_core.h"
#include "grid/detail/core_cells.h"
#include "grid/detail/features.h"
#include "grid/detail/grid_frame.h"
#include "grid/detail/pillow.h"
#include "occ/tessellate.h"
#include "quality/scaled_jacobian.h"
#include "smooth/smooth_mesh.h"

namespace vorohex::grid {
namespace {

using core::seconds_since;

void measure(const core::HexMesh& mesh, double& min_sj, double& mean_sj, std::size_t& inverted) {
  const std::vector<double> sj = quality::scaled_jacobians(mesh);
  min_sj = sj.empty() ? 0 : 1, mean_sj = 0, inverted = 0;
  for (double v : sj) min_sj = std::min(min_sj, v), mean_sj += v, inverted += v <= 0;
  if (!sj.empty()) mean_sj /= double(sj.size());
}

}  // namespace

void GridOptions::validate() const {
  auto bad = [](const char* what, double v) {
    std::ostringstream s;
    s << what << ", got " << v;
    throw std::invalid_argument(s.str());
  };
  if (!std::isfinite(size) || size <= 0) bad("size must be a positive length", size);
  if (!std::isfinite(core_margin) || core_margin <= 0) bad("core_margin must be > 0", core_margin);
  if (laplacian_iterations < 0) bad("laplacian_iterations must be >= 0", laplacian_iterations);
  if (optimisation_passes < 0) bad("optimisation_passes must be >= 0", optimisation_passes);
  if (!(quality_target > 0 && quality_target <= 1))
    bad("quality_target must be in (0, 1]", quality_target);
  if (max_refinements < 0) bad("max_refinements must be >= 0", max_refinements);
  if (max_levels < 0 || max_levels > 4) bad("max_levels must be in [0, 4]", max_levels);
  if (max_local_cells == 0) bad("max_local_cells must be at least 1", 0);
  if (max_refined_cells == 0) bad("max_refined_cells must be at least 1", 0);
  if (max_grid_cells == 0) bad("max_grid_cells must be at least 1", 0);
  if (!(min_core_share >= 0 && min_core_share <= 1))
    bad("min_core_share must be in [0, 1]", min_core_share);
  if (max_hexes == 0) bad("max_hexes must be at least 1", 0);
}

GridResult grid_mesh(const occ::Solid& solid, const GridOptions& options,
                     const core::Progress& progress) {
  options.validate();
  GridResult r;
  auto t0 = std::chrono::steady_clock::now();
  progress.report("grid", 0.0);
  double size = options.size;
  // Chord error of the boundary's tessellation: small against the margin, so made again for
  // each halving of the size (the first one's chord error is a fifth of a cell at a quarter of
  // the size, 0.8 of a cell at a sixteenth: there HexMe i09, whose walls need a sixteenth,
  // kept 1,093 cells out of the core as separate pieces).
  occ::TessellationOptions to;
  occ::Tessellation tess;
  std::vector<core::Vec3> boundary;
  auto tessellate = [&](double at) {
    to.linear_deflection = std::min(0.05 * at, 0.01 * solid.diagonal());
    tess = occ::tessellate(solid, to);
    boundary.clear();
    for (const occ::FaceTriangulation& f : tess.faces)
      boundary.insert(boundary.end(), f.nodes.begin(), f.nodes.end());
    return tess.ok();
  };
  if (!tessellate(size)) {
    r.diagnostics.push_back(core::make_error("grid_failed",
                                             "The grid mesher could not "
                                             "tessellate the solid: " +
                                                 tess.error));
    return r;
  }

  detail::GridFrame frame;
  detail::CoreCells core;
  double share = 0, left_out = 0;
  bool split = false;
  std::vector<core::Diagnostic> uniform_notes;  // the uniform refinements' warnings
  const double solid_volume = std::max(std::abs(solid.volume()), 1e-300);
  // A core still thin or split after the uniform refinements: the grid refined locally, from
  // the size asked for, instead (used when its core holds more of the volume).
  std::optional<detail::AdaptiveCore> local;
  detail::GridFrame first_frame;  // at the size asked for, where local refinement starts
  auto try_local = [&]() {
    detail::AdaptiveCoreOptions ao;
    ao.size = options.size;
    ao.margin = options.core_margin;
    ao.deflection = to.linear_deflection;
    ao.max_level = options.max_levels;
    ao.max_cells = options.max_local_cells;
    detail::AdaptiveCore a = detail::adaptive_core(first_frame, solid, tess, ao, progress);
    if (progress.cancelled()) return;
    const double a_share = a.core_volume / solid_volume, a_left = a.left_out_volume / solid_volume;
    const bool use = a.core.size() > 0 && a_share > share && a_left <= std::max(0.01, left_out);
    std::ostringstream s;
    s << "The uniform grid's core holds " << std::lround(100 * share) << "% of the volume at size "
      << size << (split ? " and falls apart into pieces" : "") << "; refined locally by thirds "
      << "near walls thinner than about two cells (up to " << a.levels_used << " times, cells "
      << "down to " << options.size / std::pow(3.0, a.levels_used) << "), its core holds "
      << std::lround(100 * a_share) << "% (" << a.core.size() << " hexahedra"
      << (a.budget_reached ? ", refinement stopped at max_local_cells" : "") << ")"
      << (use ? ": the locally refined grid is used." : ": the uniform grid is kept.");
    r.diagnostics.push_back(core::make_info("grid_refined_locally", s.str()));
    if (!use) return;
    frame = first_frame;
    size = options.size / std::pow(3.0, a.levels_used);
    local = std::move(a);
  };
  for (int attempt = 0;; ++attempt) {
    frame = detail::grid_frame(solid, boundary, size);
    if (attempt == 0) first_frame = frame;
    const double cells = double(frame.cells(0)) * frame.cells(1) * frame.cells(2);
    if (cells > 4.0 * double(options.max_hexes)) {
      std::ostringstream s;
      s << "The grid would have " << cells << " cells at size " << size
        << ", more than allowed by max_hexes = " << options.max_hexes << ".";
      r.diagnostics.push_back(core::make_error("too_many_hexes", s.str()));
      return r;
    }
    core = detail::core_cells(frame, solid, tess, size, options.core_margin, to.linear_deflection);
    if (progress.cancelled()) {
      r.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
      return r;
    }
    // The core's share of the volume: a thin core (walls thinner than about three cells)
    // leaves most of the solid to the pillow layer, whose hexes then span whole walls.
    double core_volume = 0;
    if (core.core > 0)
      for (int k = 0; k < core.cells[2]; ++k)
        for (int j = 0; j < core.cells[1]; ++j)
          for (int i = 0; i < core.cells[0]; ++i)
            if (core.at(i, j, k))
              core_volume += (frame.lines[0][i + 1] - frame.lines[0][i]) *
                             (frame.lines[1][j + 1] - frame.lines[1][j]) *
                             (frame.lines[2][k + 1] - frame.lines[2][k]);
    share = core_volume / solid_volume;
    // Pieces joined by thin walls: the smaller ones are left out, and their volume with
    // them; past about 1% of the solid the volume check fails (HexMe i14: 150 cells left
    // out, 2.5%, volume error 12%), so the grid is refined as for a thin core.
    left_out = double(core.removed_components) * size * size * size / solid_volume;
    split = core.removed_components > core.core / 4 || left_out > 0.01;
    const bool thin = share < options.min_core_share || split;
    if (!thin) break;
    // No core at all gives no mesh: halved on, past max_refinements, within the cells.
    const double inside = 8.0 * solid_volume / (size * size * size);
    if ((attempt >= options.max_refinements && core.core > 0) ||
        inside > double(options.max_refined_cells) ||
        8.0 * cells > std::min(4.0 * double(options.max_hexes), double(options.max_grid_cells))) {
      if (options.max_levels > 0) try_local();
      break;
    }
    std::ostringstream s;
    s << "The grid's core at size " << size << " holds " << std::lround(100 * share)
      << "% of the volume (walls thinner than about three cells); the grid was refined to size "
      << size / 2 << ".";
    uniform_notes.push_back(core::make_warning("size_reduced", s.str()));
    size /= 2;
    if (!tessellate(size)) {
      r.diagnostics.push_back(core::make_error(
          "grid_failed", "The grid mesher could not tessellate the solid again: " + tess.error));
      return r;
    }
  }
  if (progress.cancelled()) {
    r.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
    return r;
  }
  if (!local) r.diagnostics.insert(r.diagnostics.end(), uniform_notes.begin(), uniform_notes.end());
  r.stats.size_used = size;
  r.stats.local_levels = local ? local->levels_used : 0;
  r.stats.grid_cells =
      local ? std::array<int, 3>{frame.cells(0), frame.cells(1), frame.cells(2)} : core.cells;
  r.stats.axes_from = frame.how;
  r.stats.classifier_calls = core.classifier_calls + (local ? local->classifier_calls : 0);
  r.stats.removed_for_manifold = local ? local->removed_for_manifold : core.removed_for_manifold;
  r.stats.seconds_core = seconds_since(t0);
  if (!local && core.core == 0) {
    r.diagnostics.push_back(core::make_error(
        "grid_no_core", "No grid cell lies well inside the solid, even at size " +
                            std::to_string(size) + ": it is too thin for the grid mesher."));
    return r;
  }
  if (!local && core.removed_components > 0) {
    std::ostringstream s;
    s << "The grid's core falls apart into pieces joined only by walls thinner than about two "
      << "cells; " << core.removed_components << " cells away from the largest piece were "
      << "left out, so the mesh will not fill the solid there.";
    r.diagnostics.push_back(core::make_warning("grid_core_split", s.str()));
  }
  progress.report("grid", 0.3);

  t0 = std::chrono::steady_clock::now();
  detail::PillowMesh pillow =
      local ? detail::pillow_mesh(local->grid.points, local->core, frame.axes, solid)
            : detail::pillow_mesh(frame, core, solid);
  r.stats.core_hexes = pillow.core_hexes;
  r.stats.pillow_hexes = pillow.pillow_hexes;
  r.stats.seconds_pillow = seconds_since(t0);
  if (pillow.mesh.num_hexes() > options.max_hexes) {
    std::ostringstream s;
    s << "The grid mesh has " << pillow.mesh.num_hexes()
      << " hexahedra, more than max_hexes = " << options.max_hexes
      << "; increase the size or the limit.";
    r.diagnostics.push_back(core::make_error("too_many_hexes", s.str()));
    return r;
  }
  progress.report("grid", 0.5);
  if (progress.cancelled()) {
    r.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
    return r;
  }

  t0 = std::chrono::steady_clock::now();
  std::vector<std::string> joined;  // edges whose chain shares another edge's nodes
  bool tangent_last = false;        // the tangent edges' chains were made last
  if (options.capture_features) {
    r.absorbed = find_small_features(solid, tess, size);
    core::HexMesh before = pillow.mesh;
    detail::FeatureCapture fc = detail::capture_features(
        pillow.mesh, pillow.outer_quads, pillow.outer_nodes, pillow.outer_normals, solid,
        r.absorbed, size, false, options.share_cusps);
    // Missed features: once more with the tangent edges' chains last, kept if it misses
    // fewer, or as many with fewer inverted hexahedra (HexMe s10). Not always last: that lowered
    // the minima of HexMe i14's, i18's and n03's grid meshes, which miss nothing in the model's
    // order (n03's inverted).
    if (!fc.missed.empty()) {
      detail::FeatureCapture again = detail::capture_features(
          before, pillow.outer_quads, pillow.outer_nodes, pillow.outer_normals, solid, r.absorbed,
          size, true, options.share_cusps);
      double m0, m1, mean;
      std::size_t i0, i1;
      measure(pillow.mesh, m0, mean, i0);
      measure(before, m1, mean, i1);
      if (again.missed.size() < fc.missed.size() ||
          (again.missed.size() == fc.missed.size() && i1 < i0)) {
        fc = std::move(again);
        pillow.mesh = std::move(before);
        tangent_last = true;
      }
    }
    for (core::VertexId v : fc.cusps) r.stats.cusp_points.push_back(solid.vertex_point(v));
    r.absorbed_names = fc.absorbed;
    joined = fc.joined;
    r.stats.vertices = fc.vertices, r.stats.vertices_captured = fc.vertices_captured;
    r.stats.edges = fc.edges, r.stats.edges_captured = fc.edges_captured;
    r.stats.faces = fc.faces, r.stats.faces_captured = fc.faces_captured;
    if (!fc.absorbed.empty()) {
      std::ostringstream s;
      s << fc.absorbed.size() << " model entities smaller than a quarter of the size (and "
        << "faces they enclose) were absorbed, not resolved (";
      for (std::size_t i = 0; i < fc.absorbed.size() && i < 8; ++i)
        s << (i ? ", " : "") << fc.absorbed[i];
      s << (fc.absorbed.size() > 8 ? ", ..." : "") << "): no mesh edge follows them; they "
        << "form " << r.absorbed.composites.size() << " composite faces with their neighbours "
        << "(";
      for (std::size_t c = 0; c < r.absorbed.composites.size() && c < 4; ++c)
        s << (c ? "; " : "") << r.absorbed.composites[c].summary();
      s << (r.absorbed.composites.size() > 4 ? "; ..." : "") << "), each boundary node near "
        << "them on the nearest face of its composite.";
      r.diagnostics.push_back(core::make_warning("features_absorbed", s.str(), fc.absorbed));
    }
    r.stats.features_missed = fc.missed.size();
    if (!fc.missed.empty()) {
      std::ostringstream s;
      s << "The grid mesh could not capture " << fc.missed.size() << " model entities (";
      for (std::size_t i = 0; i < fc.missed.size() && i < 8; ++i)
        s << (i ? ", " : "") << fc.missed[i];
      s << (fc.missed.size() > 8 ? ", ..." : "") << "): no chain of mesh edges or region of "
        << "quads follows them; the mesh cuts across them.";
      r.diagnostics.push_back(core::make_warning("features_not_captured", s.str(), fc.missed));
    }
  }
  r.stats.seconds_features = seconds_since(t0);
  progress.report("grid", 0.7);
  if (progress.cancelled()) {
    r.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
    return r;
  }

  t0 = std::chrono::steady_clock::now();
  double mean = 0;
  measure(pillow.mesh, r.stats.min_sj_before_optimisation, mean,
          r.stats.inverted_before_optimisation);
  if (options.laplacian_iterations > 0 || options.optimisation_passes > 0) {
    smooth::SmoothOptions so;
    so.laplacian_iterations = options.laplacian_iterations;
    so.optimisation_passes = options.optimisation_passes;
    so.quality_target = options.quality_target;
    const smooth::SmoothResult sm = smooth::smooth_mesh(pillow.mesh, solid, so, progress);
    if (sm.status == smooth::SmoothStatus::cancelled) {
      r.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
      return r;
    }
  }
  measure(pillow.mesh, r.stats.min_sj, r.stats.mean_sj, r.stats.inverted);
  r.stats.seconds_optimisation = seconds_since(t0);
  if (!r.absorbed.empty() &&
      (options.laplacian_iterations > 0 || options.optimisation_passes > 0)) {
    const CompositeDeviation d = composite_deviation(pillow.mesh, solid, r.absorbed);
    r.stats.absorbed_deviation = d.max;
    r.diagnostics.push_back(deviation_diagnostic(r.absorbed, d));
  }
  progress.report("grid", 1.0);

  std::ostringstream s;
  s << "Grid of " << r.stats.grid_cells[0] << " x " << r.stats.grid_cells[1] << " x "
    << r.stats.grid_cells[2] << " cells of size " << (local ? options.size : size);
  if (local) s << " refined locally " << local->levels_used << " times (down to " << size << ")";
  s << " along the part's " << frame.how << ": " << r.stats.core_hexes << " core hexahedra and "
    << r.stats.pillow_hexes << " in the pillow layer; captured " << r.stats.vertices_captured << "/"
    << r.stats.vertices << " vertices, " << r.stats.edges_captured << "/" << r.stats.edges
    << " edges";
  if (tangent_last) s << " (the tangent edges' chains made after the others)";
  if (!joined.empty()) {
    s << " (" << joined.size() << " sharing nodes of another edge's chain where the two run "
      << "within a cell: ";
    for (std::size_t i = 0; i < joined.size() && i < 4; ++i) s << (i ? ", " : "") << joined[i];
    s << (joined.size() > 4 ? ", ...)" : ")");
  }
  const bool optimised = options.laplacian_iterations > 0 || options.optimisation_passes > 0;
  s << ", " << r.stats.faces_captured << "/" << r.stats.faces << " faces; min scaled Jacobian "
    << r.stats.min_sj_before_optimisation;
  // Not optimised here (the pipeline's smoothing follows): the minimum as built, which the
  // smoothing raises; a negative one read as the result's alarmed users.
  if (optimised)
    s << " -> " << r.stats.min_sj << " after optimisation.";
  else
    s << " as built, before the smoothing.";
  r.diagnostics.push_back(core::make_info("grid", s.str()));
  r.mesh = std::move(pillow.mesh);
  if (r.stats.inverted > 0 && optimised) {
    std::ostringstream e;
    e << r.stats.inverted << " of " << r.mesh.num_hexes() << " grid hexahedra are inverted "
      << "after optimisation (min scaled Jacobian " << r.stats.min_sj << "): no valid grid mesh.";
    r.diagnostics.push_back(core::make_error("grid_inverted", e.str()));
    return r;
  }
  r.ok = true;
  return r;
}

}  // namespace vorohex::grid
