#include "pipeline/detail/fallback.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <initializer_list>
#include <iomanip>
#include <sstream>
#include <thread>

#include "core/isolated_call.h"
#include "core/progress.h"
#include "grid/boundary_pillow.h"
#include "io/named_groups.h"
#include "mesh/tet_split.h"
#include "pipeline/detail/fallback_bytes.h"
#include "pipeline/detail/finish.h"
#include "quality/check_mesh.h"

namespace vorohex::pipeline::detail {
namespace {

using core::append;
using core::seconds_since;

// Seconds the tetrahedral fallback may take when the grid mesher's mesh was invalid.
constexpr double kSecondChanceSeconds = 60;
// Scheduling priority of the second chance when it runs beside (IsolatedJob's nice).
constexpr int kSecondChanceNice = 10;

bool has_diagnostic(const std::vector<core::Diagnostic>& ds, const std::string& code) {
  for (const core::Diagnostic& d : ds)
    if (d.code == code) return true;
  return false;
}

// Where the grid fallback's warning turns from why to what (the tet split's second chance
// keeps the why).
const std::string kMeshedByTheGrid = " Meshed by the grid mesher instead";

// A grid mesh left invalid is made once more on a finer uniform grid - a third of the
// grid's size, or half where that grid would pass kFinerGridCells cells - made at that size
// from the start (tessellation included), smoothed and checked within kFinerGridSeconds,
// and replaces `result` if it is valid (warning `grid_refined`: the mesh is finer than
// asked); else `result` stays, with the second grid's errors in an info
// (`grid_refined_failed`). On HexMe: i21 valid (min 0.398, 445,248 hexahedra, 19 s; it had
// no valid mesh), i02 valid (0.313) where the tet split gave 0.153, s08 (a cross cylinder
// 2.7 cells across, its end circles cut off) 0.5; i13 (0.021), i17 (0.406) and i19 (0.020)
// valid since vertices take nodes with enough quads for their angles; i23 valid (0.388)
// since its first mesh, 15 % off the volume, is not smoothed (run_fallback): smoothed, it
// ended after the deadline below (ending by 50 s instead, i23's finer grid was still
// stopped and i04's and i07's, not valid, made them 36 -> 51 s); i04 keeps 7 inverted
// hexahedra at a third of the size, and i07's (valid, 721,111 hexahedra) takes 53 s on its
// own. A valid mesh below kPoorGridQuality is made again too, at half the size, and
// replaced only by a valid mesh with a higher minimum.
// Not after local refinement (its cells are already finer where walls are thin). Where the
// first grid's core holds less than kFinerGridCore of the volume (walls far thinner than its
// cells, still after the grid mesher's own halvings), the finer grid is at half the size, and
// the grid mesher halves it again while its core is thin: HexMe i09 (walls a sixteenth of the
// size asked for), invalid at a quarter of the size, is valid at a sixteenth (360,424
// hexahedra, min 0.001; its finer grid, halved twice, smoothed and checked, takes 12 to 15
// times the first grid's time). It gets kThinGridSeconds within kThinGridDeadline of the
// start of meshing (with 30 s, the finer grid's usual time, i09 was valid in one run of the
// benchmark and stopped at its limit in the next: it needs about 21-24 s beside the
// decomposition), and is made only where it is predicted to end in time, kThinGridGrowth
// times the first grid's own time (core, pillow, features): HexMe i08 (3 % core at a quarter
// of the size, 3.8 s, so 61 s predicted; at an eighth 52-59 s alone and still invalid) is not
// made again, as before (its finer grid ran to its limit beside the decomposition and the tet
// split, and the run went 37 -> 66 s).
// Its time: at most kFinerGridSeconds, and only what is left of kFinerGridDeadline since
// meshing started (none under 5 s): a finer grid that does not end valid costs its time
// (HexMe i04 26 -> 64 s, i08 60 -> 90 s with 30 s each and 45 s, for nothing).
constexpr double kFinerGridCells = 3'000'000;
constexpr double kFinerGridSeconds = 30;
constexpr double kFinerGridDeadline = 30;
constexpr double kFinerGridCore = 0.1;
constexpr double kThinGridGrowth = 16;
constexpr double kThinGridSeconds = 40;
constexpr double kThinGridDeadline = 45;
constexpr double kCuspGridDeadline = 50;
// The jittered grid (jittered_grid): its size against the mesh's, its deadline since the start
// of meshing.
constexpr double kJitterFactor = 0.93;
constexpr double kJitterDeadline = 50;
// A first grid mesh whose volume is off by more than this before smoothing (run_fallback).
constexpr double kTangledVolume = 0.1;

// A valid grid mesh whose minimum scaled Jacobian is below this is made again on a grid half
// its size, and the finer mesh used where it is valid and better (finer_grid). On HexMe the
// grid mesher alone at half the default size: s05 (a cube with a spherical pit) 0.169 ->
// 0.500, n07 (a cube with a pyramid on it) 0.123 -> 0.500 (at a third of the size n07 has 2
// inverted hexahedra, hence half); the finer meshes of i03, i13 and i19, valid but poor, are
// not made finer again (at half their first size instead of a third: i03 0.041 and 0.021,
// i13 and i19 invalid).
constexpr double kPoorGridQuality = 0.2;
constexpr int kPoorGridFactor = 2;

// Whether the first grid's core holds less than kFinerGridCore of the volume.
bool thin_core(const occ::Solid& solid, const grid::GridStats& first) {
  const double volume = std::max(std::abs(solid.volume()), 1e-300);
  return double(first.core_hexes) * std::pow(first.size_used, 3) / volume < kFinerGridCore;
}

// The finer grid's time: at most kFinerGridSeconds, and only what is left of
// kFinerGridDeadline since meshing started at t0 (for a thin core kThinGridSeconds and
// kThinGridDeadline).
double finer_seconds(std::chrono::steady_clock::time_point t0, bool thin) {
  return thin ? std::min(kThinGridSeconds, kThinGridDeadline - seconds_since(t0))
              : std::min(kFinerGridSeconds, kFinerGridDeadline - seconds_since(t0));
}

// How many times finer the finer grid below would be (3 or 2, or only `only` if given), or 0
// where it is not made (after local refinement, too many cells or hexahedra, a thin core's
// finer grid predicted to take longer than `seconds`). `hexes`: the first grid mesh's; the finer
// one has about factor^3 times its core and factor^2 its pillow layer.
int finer_factor(const occ::Solid& solid, const grid::GridStats& first, std::size_t hexes,
                 std::size_t max_hexes, double seconds, int only = 0) {
  if (first.local_levels > 0) return 0;
  if (thin_core(solid, first)) {  // thin walls: half the size, the grid halves on itself
    const double inside = 8 * std::abs(solid.volume()) / std::pow(first.size_used, 3);
    const double predicted =
        kThinGridGrowth * (first.seconds_core + first.seconds_pillow + first.seconds_features);
    return (only == 0 || only == 2) && inside <= std::min(kFinerGridCells, double(max_hexes)) &&
                   predicted <= seconds
               ? 2
               : 0;
  }
  const double cells =
      double(first.grid_cells[0]) * double(first.grid_cells[1]) * double(first.grid_cells[2]);
  const double core = double(first.core_hexes);
  const double pillow = std::max(0.0, double(hexes) - core);
  for (int factor : {3, 2})
    if ((only == 0 || factor == only) && factor * factor * factor * cells <= kFinerGridCells &&
        factor * factor * (factor * core + pillow) <= double(max_hexes))
      return factor;
  return 0;
}

// An invalid grid mesh with inverted hexahedra gets a second pillow layer under its whole
// boundary (grid/boundary_pillow.h) and is smoothed and checked again; used if valid.
// The inverted hexahedra of a grid mesh mostly have two faces on the boundary across a model
// edge, or a face squeezed between a feature chain and the core; in the layer each hexahedron
// has one boundary face. HexMe n10 (a bent tube with a hole drilled out through its side): the
// first grid's 175 inverted hexahedra all untangled (min 0.109), the 3 times finer grid's
// down to 5, at boundary quads folded across an edge the grid did not capture.
void pillowed_grid(const occ::Solid& solid, const MeshOptions& options,
                   const core::SizeField& sizes, const core::Progress& progress,
                   MeshResult& result) {
  if (result.stats.scheme != "grid" || result.ok || result.mesh.num_hexes() == 0 ||
      progress.cancelled() || !has_diagnostic(result.diagnostics, "inverted_elements") ||
      has_diagnostic(result.diagnostics, "grid_pillow_failed"))
    return;
  MeshResult again;
  again.stats = result.stats;
  again.mesh = result.mesh;
  again.absorbed = result.absorbed;
  // What made the mesh stays said (the fallback, the grid's notes); what its smoothing and
  // check said is said again of the new mesh.
  again.diagnostics = diagnostics_of_making(result);
  const grid::BoundaryPillowResult p = grid::pillow_boundary(again.mesh);
  if (again.mesh.num_hexes() > options.max_hexes) return;
  detail::finish(again, solid, options, progress, sizes);
  add_deviation(again, solid);
  if (progress.cancelled()) return;
  std::ostringstream s;
  s << "The grid mesh (" << result.mesh.num_hexes() << " hexahedra, " << result.check.non_positive
    << " inverted) was invalid (" << core::error_codes(result.diagnostics)
    << "); a second pillow layer was put under its "
    << "boundary (" << p.hexes_added << " hexahedra, one per boundary quad) and smoothed";
  if (again.ok) {
    s << ": valid with min scaled Jacobian " << std::setprecision(3)
      << again.check.scaled_jacobian.min << ", that mesh is used.";
    again.diagnostics.push_back(core::make_warning("grid_pillowed", s.str()));
    result = std::move(again);
    return;
  }
  s << ", still invalid (" << core::error_codes(again.diagnostics) << "; "
    << again.check.non_positive << " hexahedra inverted, volume error " << std::setprecision(3)
    << 100 * std::abs(again.check.mesh_volume - again.check.cad_volume) /
           std::max(std::abs(again.check.cad_volume), 1e-300)
    << " %): the mesh before stands.";
  result.diagnostics.push_back(core::make_info("grid_pillow_failed", s.str()));
}

// The diagnostics of `from` with one of `codes` put before those of `to`, in their order: a
// mesh made again in its place still says how the size it started from came about
// (size_reduced: a reducing tee's grid went from 6.1 to 1.5, then 0.77, and said only the
// last) and what was made before it.
void carry_diagnostics(const MeshResult& from, std::initializer_list<const char*> codes,
                       MeshResult& to) {
  std::vector<core::Diagnostic> carried;
  for (const core::Diagnostic& d : from.diagnostics)
    if (std::any_of(codes.begin(), codes.end(), [&](const char* c) { return d.code == c; }))
      carried.push_back(d);
  to.diagnostics.insert(to.diagnostics.begin(), carried.begin(), carried.end());
}

// `first`: the stats of the grid that made `result`; the finer grid's once it replaces it.
void finer_grid(const occ::Solid& solid, const MeshOptions& options, const core::SizeField& sizes,
                const std::string& why, const core::Progress& progress,
                std::chrono::steady_clock::time_point t0, grid::GridStats& first,
                MeshResult& result) {
  if (result.stats.scheme != "grid" || progress.cancelled() ||
      has_diagnostic(result.diagnostics, "too_many_hexes"))
    return;
  const double first_min = result.check.scaled_jacobian.min;
  const bool poor = result.ok && result.check.valid && first_min < kPoorGridQuality;
  if (result.ok && !poor) return;
  const double seconds = finer_seconds(t0, thin_core(solid, first));
  const int factor = finer_factor(solid, first, result.mesh.num_hexes(), options.max_hexes, seconds,
                                  poor ? kPoorGridFactor : 0);
  if (factor == 0 || seconds < 5) return;
  const core::Progress budget = progress.with_time_limit(seconds).labelled("finer grid");
  MeshResult finer;
  finer.stats.size_used = result.stats.size_used;
  grid::GridStats second;
  const bool made =
      fallback(solid, options, first.size_used / factor, why, budget, t0, finer, &second);
  if (made) {
    detail::finish(finer, solid, options, budget, sizes);
    add_deviation(finer, solid);
    pillowed_grid(solid, options, sizes, budget, finer);
  }
  if (progress.cancelled()) return;
  std::ostringstream s;
  s << "The grid mesh at size " << first.size_used << " (" << result.mesh.num_hexes()
    << " hexahedra"
    << (has_diagnostic(result.diagnostics, "smoothing_skipped")
            ? ", not smoothed: its volume far off the solid's"
            : "")
    << ") was ";
  if (poor)
    s << "valid but poor (min scaled Jacobian " << std::setprecision(3) << first_min << ", below "
      << kPoorGridQuality << ")";
  else
    s << "invalid (" << core::error_codes(result.diagnostics) << ")";
  s << "; made again on a grid " << factor << " times finer, size " << first.size_used / factor;
  if (made && second.size_used < 0.99 * first.size_used / factor)
    s << " (halved to " << second.size_used << " where its core was thin)";
  const double finer_min = finer.check.scaled_jacobian.min;
  if (made && finer.ok && (!poor || (finer.check.valid && finer_min > first_min))) {
    s << ", it is valid";
    if (poor) s << " (min scaled Jacobian " << finer_min << ")";
    s << ": that mesh is used, with " << finer.mesh.num_hexes()
      << " hexahedra, finer than the size asked for.";
    finer.diagnostics.insert(finer.diagnostics.begin(),
                             core::make_warning("grid_refined", s.str()));
    carry_diagnostics(result, {"size_reduced"}, finer);
    result = std::move(finer);
    first = second;
    return;
  }
  if (budget.timed_out())
    s << ", it was stopped at its time limit (" << std::lround(seconds) << " s)";
  else if (poor && made && finer.ok)
    s << ", it is not better (min scaled Jacobian " << finer_min << ")";
  else
    s << ", it is not valid" << (poor ? "" : " either") << " ("
      << core::error_codes(finer.diagnostics) << ")"
      << (has_diagnostic(finer.diagnostics, "grid_pillow_failed")
              ? ", nor with a second pillow layer under its boundary"
              : "");
  s << ": the first mesh stands.";
  result.diagnostics.push_back(core::make_info("grid_refined_failed", s.str()));
}

// What making the grid mesh `used` describes again took: its grid alone (tessellation,
// core, pillow layer, capture), or with the smoothing and check of its mesh (`result`).
double grid_seconds(const grid::GridStats& used) {
  return used.seconds_core + used.seconds_pillow + used.seconds_features;
}
double grid_seconds(const grid::GridStats& used, const MeshResult& result) {
  return grid_seconds(used) + result.stats.seconds_smoothing + result.stats.seconds_checking;
}

// Whether a retry predicted to take `predicted` seconds fits in the `seconds` left; if not,
// an info says so (`what` begins its sentence: "... not made again"). HexMe i09, whose worst
// hexahedron lies at a cusp: its cusp retry, given the 20 s left, was stopped at that limit
// (the run 40 -> 52 s, for nothing); a grid mesh like its own takes about 25 s.
bool in_time(const std::string& what, double predicted, double seconds, MeshResult& result) {
  if (predicted <= seconds) return true;
  std::ostringstream s;
  s << what << " not made again: that would take about " << std::lround(predicted) << " s, and "
    << std::max(0L, std::lround(seconds)) << " s are left.";
  result.diagnostics.push_back(core::make_info("grid_retry_skipped", s.str()));
  return false;
}

// A valid grid mesh below kPoorGridQuality whose worst hexahedron lies within six cells of
// a cusp (two edges of one face leaving a vertex tangentially) is made again on its grid with
// the chains at cusps sharing nodes (grid::GridOptions::share_cusps) within what is left of
// kCuspGridDeadline, and used if valid and better. HexMe i03: 0.001 -> 0.26 (its worst 3.6
// cells from the point). Not always: sharing broke HexMe i19 and i09 and lowered i21. Within
// kFinerGridDeadline, as the finer grid, it needs 12-16 s and got 8-14 s on i03: stopped in
// three of six runs; by 50 s it ends in time (i03 in 28-36 s in all).
void cusp_grid(const occ::Solid& solid, const MeshOptions& options, const core::SizeField& sizes,
               const std::string& why, const core::Progress& progress,
               std::chrono::steady_clock::time_point t0, const grid::GridStats& used,
               MeshResult& result) {
  const double min = result.check.scaled_jacobian.min;
  if (result.stats.scheme != "grid" || !result.ok || !result.check.valid ||
      min >= kPoorGridQuality || used.local_levels > 0 || result.check.worst.empty() ||
      progress.cancelled())
    return;
  const core::Vec3 worst = result.check.worst[0].centre;
  const auto near =
      std::find_if(used.cusp_points.begin(), used.cusp_points.end(),
                   [&](const core::Vec3& p) { return (p - worst).norm() < 6 * used.size_used; });
  const double seconds = std::min(kFinerGridSeconds, kCuspGridDeadline - seconds_since(t0));
  if (near == used.cusp_points.end()) return;
  if (!in_time("The grid mesh's worst hexahedron lies at a cusp of the model, but it is",
               grid_seconds(used, result), seconds, result))
    return;
  const core::Progress budget = progress.with_time_limit(seconds).labelled("cusp retry");
  MeshResult again;
  again.stats.size_used = result.stats.size_used;
  const bool made = fallback(solid, options, used.size_used, why, budget, t0, again, nullptr, true);
  if (made) {
    detail::finish(again, solid, options, budget, sizes);
    add_deviation(again, solid);
  }
  if (progress.cancelled()) return;
  std::ostringstream s;
  s << "The grid mesh's worst hexahedron (min scaled Jacobian " << std::setprecision(3) << min
    << ") lies at a cusp of the model (two edges of one face leaving a vertex tangentially, at ("
    << (*near)[0] << ", " << (*near)[1] << ", " << (*near)[2] << ")); made again with the chains "
    << "of such edges sharing nodes while within 0.3 cells of each other (the face's tip, "
    << "narrower than that, absorbed)";
  const double again_min = again.check.scaled_jacobian.min;
  if (made && again.ok && again.check.valid && again_min > min) {
    s << ", it is valid with min scaled Jacobian " << again_min << ": that mesh is used.";
    carry_diagnostics(result, {"size_reduced", "grid_refined"}, again);
    again.diagnostics.push_back(core::make_warning("grid_cusps_shared", s.str()));
    result = std::move(again);
    return;
  }
  if (budget.timed_out())
    s << ", it was stopped at its time limit (" << std::lround(seconds) << " s)";
  else if (made && again.ok && again.check.valid)
    s << ", it is not better (min scaled Jacobian " << again_min << ")";
  else
    s << ", it is not valid (" << core::error_codes(again.diagnostics) << ")";
  s << ": the first mesh stands.";
  result.diagnostics.push_back(core::make_info("grid_cusps_failed", s.str()));
}

// A grid mesh still valid but below kPoorGridQuality after the finer grid and the cusp retry,
// on a grid that left model features uncaptured, is made once more on a grid kJitterFactor
// times its size, within kJitterDeadline of the start of meshing, and replaced where that one
// is valid and better. The worst hexahedra of a grid mesh sit where the cells happen to fall
// at a model vertex or edge (a chain not captured, a vertex node whose quads do not fit its
// angles); a grid a little finer puts them elsewhere. HexMe i25 (grid only, no retry: 3 of
// 117 edges not captured, min 0.007) at 0.93, 0.97, 1.03 and 1.07 times its finer grid's
// size: min 0.299 (every edge captured), 0.038, 0.067, invalid; i19 (4 of 65 not captured)
// invalid at each; i13 (all captured) 0.020-0.031 at each: its vertices where a line leaves
// a circle tangentially are the same at any size, so a grid that captured everything is not
// made again. Invalid meshes neither: i04, i05, n10 and i12 stay invalid at each size (the
// tet split's second chance follows). Finer rather than coarser: it captures more.
void jittered_grid(const occ::Solid& solid, const MeshOptions& options,
                   const core::SizeField& sizes, const std::string& why,
                   const core::Progress& progress, std::chrono::steady_clock::time_point t0,
                   const grid::GridStats& used, MeshResult& result) {
  const double min = result.check.scaled_jacobian.min;
  const bool poor = result.ok && result.check.valid && min < kPoorGridQuality;
  if (result.stats.scheme != "grid" || !poor || used.features_missed == 0 ||
      used.local_levels > 0 || used.size_used <= 0 || progress.cancelled() ||
      has_diagnostic(result.diagnostics, "too_many_hexes"))
    return;
  const double seconds = std::min(kFinerGridSeconds, kJitterDeadline - seconds_since(t0));
  const double size = used.size_used * kJitterFactor;
  const double cells = double(used.grid_cells[0]) * double(used.grid_cells[1]) *
                       double(used.grid_cells[2]) / std::pow(kJitterFactor, 3);
  if (cells > kFinerGridCells ||
      double(result.mesh.num_hexes()) / std::pow(kJitterFactor, 3) > double(options.max_hexes))
    return;
  // Its grid's time only: the smoothing of the mesh before, untangling what its grid missed,
  // says little of the smoothing of one that captures more (HexMe i25: 23 s, against about 3 s
  // for its jittered mesh), and one that does not is not smoothed (below).
  if (!in_time("The poor grid mesh, whose grid left model features uncaptured, is",
               grid_seconds(used) / std::pow(kJitterFactor, 3), seconds, result))
    return;
  const core::Progress budget = progress.with_time_limit(seconds).labelled("jittered grid");
  MeshResult again;
  again.stats.size_used = result.stats.size_used;
  grid::GridStats stats;
  const bool made = fallback(solid, options, size, why, budget, t0, again, &stats);
  // Smoothed and checked only where it captures more: on HexMe the jittered grids that miss as
  // many features as the mesh before did not end better (i19: the same four edges missed at
  // 0.93, 0.97, 1.03 and 1.07 times its size, invalid at each; i25: 0.299 where none is missed,
  // 0.038 to invalid where 4 to 8 are, 3 before).
  const bool captures_more = made && stats.features_missed < used.features_missed;
  if (captures_more) {
    detail::finish(again, solid, options, budget, sizes);
    add_deviation(again, solid);
  }
  if (progress.cancelled()) return;
  std::ostringstream s;
  s << "The grid mesh at size " << std::setprecision(4) << used.size_used
    << " was valid but poor (min scaled Jacobian " << std::setprecision(3) << min << ", "
    << used.features_missed << " model features not captured); made again on a grid "
    << std::setprecision(3) << kJitterFactor << " times its size (" << std::setprecision(4)
    << stats.size_used << "), where its cells fall differently at the model's vertices and edges";
  const double again_min = again.check.scaled_jacobian.min;
  if (captures_more && again.ok && again.check.valid && again_min > min) {
    s << ", it is valid with min scaled Jacobian " << std::setprecision(3) << again_min
      << ": that mesh is used, with " << again.mesh.num_hexes() << " hexahedra.";
    carry_diagnostics(result, {"size_reduced", "grid_refined", "grid_cusps_shared"}, again);
    again.diagnostics.push_back(core::make_warning("grid_jittered", s.str()));
    result = std::move(again);
    return;
  }
  if (budget.timed_out())
    s << ", it was stopped at its time limit (" << std::lround(seconds) << " s)";
  else if (made && !captures_more)
    s << ", it leaves as many model features uncaptured or more (" << stats.features_missed
      << "; not smoothed)";
  else if (made && again.ok && again.check.valid)
    s << ", it is not better (min scaled Jacobian " << std::setprecision(3) << again_min << ")";
  else
    s << ", it is not valid (" << core::error_codes(again.diagnostics) << ")";
  s << ": the mesh before stands.";
  result.diagnostics.push_back(core::make_info("grid_jittered_failed", s.str()));
}

}  // namespace

// The grid mesher's composites: how far the final boundary strays from the real surface.
void add_deviation(MeshResult& result, const occ::Solid& solid) {
  if (result.absorbed.empty() || result.mesh.num_hexes() == 0) return;
  const grid::CompositeDeviation d = grid::composite_deviation(result.mesh, solid, result.absorbed);
  result.stats.absorbed_deviation = d.max;
  result.diagnostics.push_back(grid::deviation_diagnostic(result.absorbed, d));
}

core::Diagnostic local_sizes_ignored(const std::string& scheme) {
  return core::make_warning("local_sizes_ignored",
                            "The " + scheme +
                                " scheme meshes at the global size: the local sizes are not "
                                "applied to this solid.");
}

// No structured scheme: the grid mesher (or, on request, tetrahedra split into
// hexahedra), said so in a warning.
// The grid mesher's stats go to grid_stats when given.
bool fallback(const occ::Solid& solid, const MeshOptions& options, double size,
              const std::string& why, const core::Progress& progress,
              std::chrono::steady_clock::time_point t0, MeshResult& result,
              grid::GridStats* grid_stats, bool share_cusps) {
  if (options.fallback_scheme == "grid") {
    result.stats.scheme = "grid";
    grid::GridOptions o;
    o.size = size;
    o.share_cusps = share_cusps;
    o.max_hexes = options.max_hexes;
    // The optimisation is the global smoothing every result goes through (detail::finish).
    o.laplacian_iterations = 0;
    o.optimisation_passes = 0;
    grid::GridResult g = grid::grid_mesh(solid, o, progress);
    if (grid_stats) *grid_stats = g.stats;
    append(result.diagnostics, g.diagnostics);
    result.stats.seconds_meshing = seconds_since(t0);
    if (!g.ok) return false;
    result.mesh = std::move(g.mesh);
    result.absorbed = std::move(g.absorbed);
    // The features it could not capture are a warning of their own (features_not_captured).
    const bool all_captured =
        std::none_of(g.diagnostics.begin(), g.diagnostics.end(),
                     [](const core::Diagnostic& d) { return d.code == "features_not_captured"; });
    result.diagnostics.push_back(core::make_warning(
        "fallback", why + kMeshedByTheGrid + " (core grid, one pillow layer to the CAD, " +
                        (all_captured ? "features captured"
                                      : "features captured where it could: see "
                                        "features_not_captured") +
                        "); expect poorer elements at the boundary than a structured mesh."));
    return true;
  }
  result.stats.scheme = "tet-split";
  mesh::TetSplitOptions tet_options;
  tet_options.size = size;
  tet_options.max_hexes = options.max_hexes;
  mesh::TetSplitResult split = mesh::tet_split(solid, tet_options, progress);
  append(result.diagnostics, split.diagnostics);
  result.stats.seconds_meshing = seconds_since(t0);
  if (!split.ok) return false;
  result.mesh = std::move(split.mesh);
  result.diagnostics.push_back(core::make_warning(
      "fallback",
      why + " Meshed by the tetrahedral fallback instead: " + std::to_string(split.tetrahedra) +
          " tetrahedra, each split into four hexahedra; expect poorer elements than a "
          "structured mesh."));
  return true;
}

FallbackOutcome run_fallback(const occ::Solid& solid, const MeshOptions& options,
                             const core::SizeField& sizes,
                             const std::vector<core::Diagnostic>& small, const std::string& why,
                             const core::Progress& progress,
                             std::chrono::steady_clock::time_point t0) {
  const double size = sizes.global();
  FallbackOutcome out;
  MeshResult& result = out.result;
  result.stats.size_used = size;
  // The grid mesher is not yet valid on every part the tetrahedral fallback meshes validly
  // (several of HexMe's industrial models): when its mesh is invalid, the tet split gets a
  // second chance, within kSecondChanceSeconds, and is used if its mesh is valid. Why the
  // fallback was needed (no scheme, the decomposition's failure) stays in its message: the
  // grid's fallback warning is not part of the second result.
  auto second_chance = [&](const std::string& why_grid, const core::Progress& p, bool& timed_out,
                           bool limited) {
    MeshOptions tet = options;
    tet.fallback_scheme = "tet-split";
    const core::Progress budget =
        (limited ? p.with_time_limit(kSecondChanceSeconds) : p).labelled("second chance");
    MeshResult second;
    second.stats.size_used = size;  // the tet split meshes at the global size
    if (fallback(solid, tet, size,
                 (why_grid.empty() ? "" : why_grid + " ") + "The grid mesher's mesh is invalid.",
                 budget, std::chrono::steady_clock::now(), second))
      detail::finish(second, solid, tet, budget, sizes);
    timed_out = budget.timed_out();
    return second;
  };
  std::string why_grid;
  // On two cores or more the second chance starts beside the grid's smoothing and check
  // (which decide whether it is needed: on HexMe's industrial models, mostly yes), and is
  // taken or killed once they have. Its 60 s count from then, as after them (the caller
  // stops it): it shares the cores with them and with the decomposition before, and a limit
  // counted from its start cut HexMe i03's and i12's short. It runs at a lower priority
  // (nice 10): beside the decomposition, a third process on two cores, it slowed the cuts
  // until HexMe i22's merges ran into their limit, and the structured mesh was lost.
  core::IsolatedJob beside;
  grid::GridStats grid_stats;
  if (fallback(solid, options, size, why, progress, t0, result, &grid_stats)) {
    for (const core::Diagnostic& d : result.diagnostics)
      if (d.code == "fallback") why_grid = d.message.substr(0, d.message.find(kMeshedByTheGrid));
    if (options.fallback_scheme == "grid" && options.fallback_beside &&
        std::thread::hardware_concurrency() >= 2)
      beside = core::IsolatedJob(
          [&](const core::Progress& in_child) {
            bool timed_out = false;
            const MeshResult second = second_chance(why_grid, in_child, timed_out, false);
            return detail::fallback_to_bytes(second, timed_out);
          },
          progress, kSecondChanceNice);
    // A first grid mesh whose volume is far off before smoothing (features missed, the
    // pillow layer tangled) is not smoothed when a finer grid follows: its time goes to the
    // finer grid (HexMe i23: 27 s of smoothing for a mesh 15 % off, then no time left for
    // its finer grid, valid at 0.396). On HexMe the grid meshes that end valid are at most
    // 5.5 % off before smoothing (n01), the ones above kTangledVolume all end invalid.
    MeshOptions first_options = options;
    if (result.stats.scheme == "grid" &&
        finer_factor(solid, grid_stats, result.mesh.num_hexes(), options.max_hexes,
                     finer_seconds(t0, thin_core(solid, grid_stats))) > 0 &&
        !has_diagnostic(result.diagnostics, "too_many_hexes")) {
      const double cad = std::max(std::abs(solid.volume()), 1e-300);
      const double off = std::abs(quality::mesh_volume(result.mesh) - solid.volume()) / cad;
      if (off > kTangledVolume) {
        first_options.smoothing.laplacian_iterations = 0;
        first_options.smoothing.optimisation_passes = 0;
        std::ostringstream s;
        s << "The grid mesh at size " << grid_stats.size_used << " was not smoothed: its volume "
          << "differs from the solid's by " << std::setprecision(3) << 100 * off
          << " % before smoothing (features missed or its pillow layer tangled), which "
             "smoothing does not mend; a finer grid is made instead.";
        result.diagnostics.push_back(core::make_info("smoothing_skipped", s.str()));
      }
    }
    detail::finish(result, solid, first_options, progress, sizes);
    add_deviation(result, solid);
    finer_grid(solid, options, sizes, why, progress, t0, grid_stats, result);
    // Where no finer grid was made: its time is not the pillow layer's.
    if (!has_diagnostic(result.diagnostics, "grid_refined") &&
        !has_diagnostic(result.diagnostics, "grid_refined_failed"))
      pillowed_grid(solid, options, sizes, progress, result);
    cusp_grid(solid, options, sizes, why, progress, t0, grid_stats, result);
    jittered_grid(solid, options, sizes, why, progress, t0, grid_stats, result);
  }
  const bool grid_invalid =
      result.stats.scheme == "grid" && has_diagnostic(result.diagnostics, "fallback") && !result.ok;
  if (!grid_invalid || options.fallback_scheme != "grid" || progress.cancelled() ||
      has_diagnostic(result.diagnostics, "too_many_hexes"))
    return out;  // (a second chance beside is killed with its job)
  MeshResult second;
  bool timed_out = false, taken = false;
  if (beside.started()) {
    const core::IsolatedResult got =
        beside.take(progress.with_time_limit(kSecondChanceSeconds), {"tetrahedra"});
    if (got.status == core::IsolatedResult::Status::cancelled) {
      if (progress.cancelled()) {
        result.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
        return out;
      }
      timed_out = true;  // its 60 s ran out: no second result, as after the check
      second.diagnostics.push_back(
          core::make_error("cancelled", "The tetrahedral fallback was stopped at its time limit."));
      taken = true;
    } else {
      taken = got.ok() && detail::fallback_from_bytes(got.data, second, timed_out);
    }
    if (taken && second.mesh.num_hexes() > 0) {
      second.groups = io::named_groups(second.mesh, solid);
      second.check =
          quality::check_mesh(second.mesh, &solid, options.check, &second.scaled_jacobian);
    }
  }
  if (!taken) second = second_chance(why_grid, progress, timed_out, true);
  // Each error code once (the smoothing and the check both name inverted hexahedra).
  const std::string grid_errors = core::error_codes(result.diagnostics);
  if (second.ok) {
    second.diagnostics.insert(second.diagnostics.begin(), small.begin(), small.end());
    if (!sizes.uniform()) second.diagnostics.push_back(local_sizes_ignored("tet-split"));
    second.diagnostics.push_back(core::make_warning(
        "grid_invalid", "The grid mesher's mesh was invalid (" + grid_errors +
                            (has_diagnostic(result.diagnostics, "grid_refined_failed")
                                 ? "; and again on a finer grid"
                                 : "") +
                            (has_diagnostic(result.diagnostics, "grid_pillow_failed")
                                 ? "; and with a second pillow layer under its boundary"
                                 : "") +
                            "); the tetrahedral fallback's mesh is valid and is used."));
    out.result = std::move(second);
    out.second_chance = true;
    return out;
  }
  const std::string tet_errors = core::error_codes(second.diagnostics);
  result.diagnostics.push_back(core::make_info(
      "second_fallback_failed",
      std::string("The tetrahedral fallback, tried after the grid mesher's invalid mesh, gave "
                  "no valid mesh either") +
          (timed_out ? " within " + std::to_string(int(kSecondChanceSeconds)) + " s" : "") +
          (tet_errors.empty() ? "." : " (" + tet_errors + ").")));
  return out;
}

}  // namespace vorohex::pipeline::detail
