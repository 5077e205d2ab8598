#include "pipeline/generate_mesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "core/isolated_call.h"
#include "core/progress.h"
#include "io/named_groups.h"
#include "mesh/assemble.h"
#include "mesh/mesh_sub_volumes.h"
#include "mesh/midpoint.h"
#include "pipeline/detail/decompose_isolated.h"
#include "pipeline/detail/fallback.h"
#include "pipeline/detail/fallback_bytes.h"
#include "pipeline/detail/finish.h"
#include "pipeline/detail/mesh_decomposed.h"
#include "pipeline/detail/part_warnings.h"
#include "pipeline/detail/schemes.h"
#include "quality/check_mesh.h"
#include "quality/scaled_jacobian.h"

namespace vorohex::pipeline {
namespace {

using core::append;
using core::seconds_since;
using detail::add_deviation;
using detail::fallback;
using detail::FallbackOutcome;
using detail::kWhyLater;
using detail::local_sizes_ignored;
using detail::run_fallback;

}  // namespace

void MeshOptions::validate() const {
  if (!std::isfinite(size) || size < 0) {
    std::ostringstream s;
    s << "size must be a positive length (or 0 for automatic), got " << size;
    throw std::invalid_argument(s.str());
  }
  if (max_hexes == 0) throw std::invalid_argument("max_hexes must be at least 1");
  if (!std::isfinite(decomposition_time_limit) || decomposition_time_limit <= 0) {
    std::ostringstream s;
    s << "decomposition_time_limit must be a number of seconds > 0, got "
      << decomposition_time_limit;
    throw std::invalid_argument(s.str());
  }
  if (!std::isfinite(time_limit) || time_limit < 0) {
    std::ostringstream s;
    s << "time_limit must be a number of seconds >= 0 (0: none), got " << time_limit;
    throw std::invalid_argument(s.str());
  }
  if (std::string why = graph.validate(); !why.empty()) throw std::invalid_argument(why);
  if (!std::isfinite(sharp_angle) || sharp_angle <= 0 || sharp_angle > 180) {
    std::ostringstream s;
    s << "sharp_angle must be in (0, 180] degrees, got " << sharp_angle;
    throw std::invalid_argument(s.str());
  }
  if (fallback_scheme != "grid" && fallback_scheme != "tet-split")
    throw std::invalid_argument("fallback_scheme must be \"grid\" or \"tet-split\", got \"" +
                                fallback_scheme + "\"");
  if (!std::isfinite(size_grading) || size_grading <= 0 || size_grading > 10) {
    std::ostringstream s;
    s << "size_grading must be in (0, 10] (growth of the size per unit distance), got "
      << size_grading;
    throw std::invalid_argument(s.str());
  }
  for (const core::LocalSize& l : local_sizes) {
    char kind = 0;
    int id = 0;
    if (!core::parse_entity_name(l.entity, kind, id))
      throw std::invalid_argument("local size: '" + l.entity +
                                  "' is not an entity name (expected FaceN, EdgeN or VertexN)");
    if (!std::isfinite(l.size) || l.size <= 0) {
      std::ostringstream s;
      s << "local size of " << l.entity << " must be a positive length, got " << l.size;
      throw std::invalid_argument(s.str());
    }
  }
  if (order != 1 && order != 2)
    throw std::invalid_argument("order must be 1 (8-node hexahedra) or 2 (20-node), got " +
                                std::to_string(order));
  smoothing.validate();
  check.validate();
  for (std::size_t i = 0; i < schemes.size(); ++i) {
    (void)detail::make_schemes({schemes[i]});  // throws naming an unknown scheme
    for (std::size_t j = 0; j < i; ++j)
      if (schemes[j] == schemes[i])
        throw std::invalid_argument("scheme '" + schemes[i] + "' is given twice");
  }
}

namespace {
MeshResult generate(const occ::Solid& solid, const MeshOptions& options,
                    const core::Progress& progress);
MeshResult generate_once(const occ::Solid& solid, const MeshOptions& options,
                         const core::Progress& progress);
}  // namespace

const std::vector<std::string>& scheme_names() {
  return detail::scheme_names();
}

namespace {

// A second-order mesh left off the CAD because mid-edge nodes put on a curved face folded an
// element (one element across a concave fillet: the ring of a round pocket's filleted floor at
// the automatic size) is made again at half the size, up to twice, where that stays within
// max_hexes; the finer mesh is used where valid (warning size_reduced_for_second_order).
// FreeCAD's panel asks for second order by default.
constexpr int kSecondOrderHalvings = 2;

bool straightened_off_cad(const MeshResult& r) {
  bool straightened = false, off = false;
  for (const core::Diagnostic& d : r.diagnostics) {
    straightened |= d.code == "mid_nodes_straightened";
    off |= d.code == "nodes_off_cad";
  }
  return straightened && off && !r.ok;
}

}  // namespace

MeshResult generate_mesh(const occ::Solid& solid, const MeshOptions& options,
                         const core::Progress& progress) {
  options.validate();
  const auto t0 = std::chrono::steady_clock::now();
  MeshResult r = generate_once(solid, options, progress);
  MeshOptions finer = options;
  for (int k = 0; k < kSecondOrderHalvings && options.order == 2 && straightened_off_cad(r) &&
                  r.stats.size_used > 0 && !progress.cancelled();
       ++k) {
    finer.size = r.stats.size_used / 2;
    if (double(r.mesh.num_hexes()) * 8 > double(options.max_hexes)) break;
    if (options.time_limit > 0) {  // the limit holds for all the runs together
      finer.time_limit = options.time_limit - seconds_since(t0);
      if (finer.time_limit <= 0) break;
    }
    MeshResult again = generate_once(solid, finer, progress);
    if (!again.ok && !straightened_off_cad(again)) break;
    std::ostringstream m;
    m << "At size " << r.stats.size_used << " the second-order mesh had nodes off the CAD "
      << "(mid-edge nodes put on a curved face folded an element, and were put back straight); "
      << "made again at size " << finer.size;
    if (again.ok) {
      m << ", it is valid: that mesh is used, with " << again.mesh.num_hexes()
        << " hexahedra, finer than the size asked for.";
      again.diagnostics.insert(again.diagnostics.begin(),
                               core::make_warning("size_reduced_for_second_order", m.str()));
      return again;
    }
    r = std::move(again);
  }
  return r;
}

namespace {
// One run, stopped at options.time_limit.
MeshResult generate_once(const occ::Solid& solid, const MeshOptions& options,
                         const core::Progress& progress) {
  if (!(options.time_limit > 0)) return generate(solid, options, progress);
  const core::Progress limited = progress.with_time_limit(options.time_limit);
  MeshResult r = generate(solid, options, limited);
  if (limited.timed_out() && !r.ok) {
    for (core::Diagnostic& d : r.diagnostics)
      if (d.code == "cancelled" || d.message.find("cancelled") != std::string::npos) {
        d.code = "time_limit";
        d.message = "Meshing stopped at the time limit of " + std::to_string(options.time_limit) +
                    " s (" + d.message + ")";
      }
    if (!core::has_error(r.diagnostics))
      r.diagnostics.push_back(core::make_error(
          "time_limit",
          "Meshing stopped at the time limit of " + std::to_string(options.time_limit) + " s."));
    r.mesh = core::HexMesh();  // a stopped run hands over nothing
  }
  return r;
}

// The smallest scaled Jacobian of a mesh's hexahedra (1 for an empty mesh).
double min_scaled_jacobian(const core::HexMesh& mesh) {
  const std::vector<double> sj = quality::scaled_jacobians(mesh);
  return sj.empty() ? 1 : *std::min_element(sj.begin(), sj.end());
}

// A decomposition's structured mesh below kPoorStructured after smoothing (and the pillow at
// tangent edges) is compared with the fallback's mesh made beside the decomposition, which
// gets up to kPoorStructuredWait seconds more to end, and replaced by it where that one is
// valid and kPoorStructuredGain better. A block with its top edges filleted at radius 5 and
// size 1 (40 x 20 x 10): the mapped slab's corners, where two fillets meet the top face
// tangentially, reach 0.133 (pillowed; 0.048 before), the grid 0.500 in 3.1 s. HexMe i11
// (0.169 at its crescent's point; the grid's mesh of it is not ready in time, and was not
// valid when it was the fallback) waits the 5 s for nothing.
constexpr double kPoorStructured = 0.2;
constexpr double kPoorStructuredWait = 5;
constexpr double kPoorStructuredGain = 0.05;

// A decomposition's mesh `result`, still below kPoorStructured, against the fallback's mesh
// made beside it (`made`: taken in time, into `fallback`; `why` says how poor `result` is).
// True where `fallback` replaces it: valid and kPoorStructuredGain better; it then says what
// made `result` (after the first `small` diagnostics where the tet split's second chance
// starts with them too) and warns structured_replaced. Else `result` stays, with the info
// structured_kept.
bool replaced_by_fallback(MeshResult& result, FallbackOutcome& fallback, bool made,
                          const std::string& why, std::size_t small) {
  MeshResult& f = fallback.result;
  std::ostringstream m;
  m << why << "; the ";
  if (made && f.ok &&
      f.check.scaled_jacobian.min >= result.check.scaled_jacobian.min + kPoorStructuredGain) {
    const std::vector<core::Diagnostic> making = detail::diagnostics_of_making(result);
    const auto skip = std::ptrdiff_t(fallback.second_chance ? std::min(small, making.size()) : 0);
    f.diagnostics.insert(f.diagnostics.begin() + skip, making.begin() + skip, making.end());
    m << f.stats.scheme << " fallback's mesh, made beside it, is valid with min "
      << std::setprecision(3) << f.check.scaled_jacobian.min << ": that mesh is used ("
      << f.mesh.num_hexes() << " hexahedra).";
    f.diagnostics.push_back(core::make_warning("structured_replaced", m.str()));
    f.stats.local_sizes = result.stats.local_sizes;
    return true;
  }
  m << "fallback's mesh made beside it ";
  if (!made)
    m << "was not ready within " << kPoorStructuredWait << " s more";
  else if (!f.ok)
    m << "is invalid (" << core::error_codes(f.diagnostics) << ")";
  else
    m << "is not better (min " << std::setprecision(3) << f.check.scaled_jacobian.min << ")";
  m << ": the structured mesh stays.";
  result.diagnostics.push_back(core::make_info("structured_kept", m.str()));
  return false;
}

// How mesh_solid hands a solid no structured scheme meshes to the fallback: at once (the
// several-solids path, which smooths all solids' meshes together), or back to the caller
// (`deferred`: `needed` and `why` set; the caller runs it, perhaps started beside the
// decomposition by `before_decomposition`).
struct DeferredFallback {
  std::function<void()> before_decomposition;  // called when the decomposition starts
  bool needed = false;
  std::string why;  // the fallback warning's reason
};

// Meshes one solid with the first scheme that applies, without smoothing or checking:
// true when result.mesh holds its mesh (else result.diagnostics say why not, or `deferred`
// says the fallback is left to the caller).
bool mesh_solid(const occ::Solid& solid, const MeshOptions& options, const core::SizeField& sizes,
                const core::Progress& progress, MeshResult& result,
                DeferredFallback* deferred = nullptr) {
  const auto t0 = std::chrono::steady_clock::now();
  const double size = sizes.global();
  result.stats.size_used = size;

  progress.report("scheme", 0.0);
  // Schemes in the order of options.schemes (map, sweep, multisweep, revolve, midpoint by
  // default): the first that applies and succeeds meshes the solid. One that does not apply
  // says why; one that applies but fails (a sweep whose layers fold, a region whose quads
  // fold) hands over to the next with its reason.
  std::string why_not_structured;
  auto add_reason = [&](const std::string& why) {
    why_not_structured += (why_not_structured.empty() ? "" : ". ") + why;
  };
  auto take = [&](const detail::Scheme& scheme, detail::SchemeMesh& meshed) {
    append(result.diagnostics, meshed.diagnostics);
    result.stats.intervals = meshed.intervals;
    result.stats.scheme = scheme.name();
    result.mesh = std::move(meshed.mesh);
    result.absorbed = std::move(meshed.absorbed);
    if (!meshed.summary.code.empty()) result.diagnostics.push_back(meshed.summary);
    if (!sizes.uniform() && !scheme.grades()) {
      result.diagnostics.push_back(local_sizes_ignored(scheme.name()));
      result.stats.local_sizes.clear();  // none applied
    }
  };
  // A midpoint subdivision poorer than mesh::kPoorMidpointQuality before smoothing (a convex
  // block with chamfered edges: 0.07, 0.15 smoothed) is held while the decomposition is
  // tried: a decomposition that meshes at least as well replaces it (the chamfered block: a
  // block and a tapered slab, 0.58), else it is taken.
  const auto schemes = detail::make_schemes(options.schemes);
  const detail::Scheme* held_scheme = nullptr;
  detail::SchemeMesh held;
  double held_min = 0;
  for (const auto& scheme : schemes) {
    const detail::SchemeCheck check = scheme->applicable(solid);
    if (!check.ok) {
      add_reason(check.reason);
      continue;
    }
    const detail::SchemeEstimate estimate = scheme->evaluate(solid, sizes);
    if (estimate.hexes > options.max_hexes) {
      std::ostringstream s;
      s << "The mesh would have " << estimate.hexes
        << " hexahedra, more than max_hexes = " << options.max_hexes
        << "; increase the size or the limit.";
      result.diagnostics.push_back(core::make_error("too_many_hexes", s.str()));
      return false;
    }
    detail::SchemeMesh meshed = scheme->compute(solid, sizes, progress);
    result.stats.seconds_meshing = seconds_since(t0);
    if (meshed.ok && std::string(scheme->name()) == "midpoint" && options.decompose &&
        !held_scheme) {
      const double m = min_scaled_jacobian(meshed.mesh);
      if (m < mesh::kPoorMidpointQuality) {
        held_scheme = scheme.get(), held = std::move(meshed), held_min = m;
        continue;
      }
    }
    if (meshed.ok) {
      take(*scheme, meshed);
      return true;
    }
    if (progress.cancelled()) {
      append(result.diagnostics, meshed.diagnostics);
      return false;
    }
    // Its errors become the reason; its warnings and notes stay.
    std::string why = "The " + std::string(scheme->name()) + " scheme applied but failed (";
    for (const core::Diagnostic& d : meshed.diagnostics) {
      if (d.severity != core::Severity::error) {
        result.diagnostics.push_back(d);
        continue;
      }
      std::string m = d.message;
      if (!m.empty() && m.back() == '.') m.pop_back();
      why += (why.back() == '(' ? "" : "; ") + m;
    }
    add_reason(why + ")");
    result.diagnostics.push_back(
        core::make_info("scheme_failed", why + "); the next scheme is tried.", {scheme->name()}));
  }
  if (options.schemes.empty()) why_not_structured = "No single-solid scheme is enabled";
  why_not_structured += ".";
  std::string not_decomposed = "decomposition is off";
  if (held_scheme) {
    // The held midpoint mesh against the decomposition's (no fallback needed either way).
    MeshResult before = result;
    std::ostringstream m;
    m.precision(3);
    m << "The midpoint subdivision's minimum scaled Jacobian is only " << held_min
      << " before smoothing";
    if (detail::mesh_decomposed(solid, options, sizes, progress, result, not_decomposed)) {
      const double cut = min_scaled_jacobian(result.mesh);
      if (cut >= held_min) {
        m << "; its decomposition's is " << cut << ": that is used.";
        result.diagnostics.push_back(core::make_info("midpoint_replaced", m.str(), {"midpoint"}));
        return true;
      }
      m << "; its decomposition's is lower (" << cut << "): the midpoint subdivision is used.";
    } else {
      m << ", and its decomposition did not help (" << not_decomposed
        << "): the midpoint subdivision is used.";
    }
    if (progress.cancelled()) return false;
    result = std::move(before);
    take(*held_scheme, held);
    result.diagnostics.push_back(core::make_info("midpoint_kept", m.str(), {"midpoint"}));
    return true;
  }
  if (options.decompose) {
    if (deferred && deferred->before_decomposition && options.fallback)
      deferred->before_decomposition();
    if (detail::mesh_decomposed(solid, options, sizes, progress, result, not_decomposed))
      return true;
    if (progress.cancelled() || core::has_error(result.diagnostics)) return false;
  }
  if (!options.fallback) {
    result.diagnostics.push_back(core::make_error(
        "not_supported_yet", "This solid is not supported yet: no single scheme meshes it, and " +
                                 not_decomposed + ". " + why_not_structured));
    return false;
  }
  result.stats.intervals = {0, 0, 0};
  if (!sizes.uniform()) {
    result.diagnostics.push_back(local_sizes_ignored(options.fallback_scheme));
    result.stats.local_sizes.clear();  // none applied
  }
  const std::string why =
      "No structured scheme applies (" + why_not_structured + ") and " + not_decomposed + ".";
  if (deferred) {
    deferred->needed = true;
    deferred->why = why;
    return false;
  }
  return fallback(solid, options, size, why, progress, t0, result);
}

// Several solids glued at common faces: each meshed with the same size, joined into one
// mesh (nodes on shared faces merged where the meshes coincide), then smoothed and checked
// as a whole, so nodes on a shared face stay on it and the check sees the interfaces.
MeshResult generate_parts(const occ::Solid& whole, const MeshOptions& options,
                          const core::SizeField& sizes, const core::Progress& progress) {
  const double size = sizes.global();
  MeshResult result;
  result.stats.size_used = size;
  const auto t0 = std::chrono::steady_clock::now();
  // Every solid a block or a sweep: one interval assignment over all of them makes the
  // shared faces conform (mesh/mesh_sub_volumes.h). Otherwise each solid on its own below.
  {
    mesh::SubVolumeMeshOptions o;
    o.size = size;
    o.size_field = &sizes;
    o.max_hexes = options.max_hexes;
    // Blocks and sweeps only: a multisweep's face mesh may differ from its neighbour's (an
    // edge its cross-section splits), and the solids on their own below are the way then.
    o.multisweep = false;
    mesh::SubVolumeMeshResult m = mesh::mesh_sub_volumes(whole, o, progress);
    if (m.ok) {
      result.mesh = std::move(m.mesh);
      result.stats.scheme = detail::joined_schemes(m.stats.schemes);
      result.stats.sub_volume_schemes = m.stats.schemes;
      result.stats.sub_volume_types = m.stats.types;
      result.stats.sub_volumes = whole.num_solids();
      result.stats.seconds_meshing = seconds_since(t0);
      std::ostringstream s;
      const int shared = whole.num_interface_faces();
      s << whole.num_solids() << " solids meshed with one interval assignment over "
        << m.stats.curves << " curves, so that their meshes match on the " << shared
        << (shared == 1 ? " face they share; " : " faces they share; ") << m.stats.nodes_merged
        << " nodes merged.";
      result.diagnostics.push_back(core::make_info("solids_joined", s.str()));
      detail::finish(result, whole, options, progress, sizes);
      detail::pillow_flat_doublets(result, whole, options, progress, sizes);
      return result;
    }
    if (progress.cancelled()) {
      result.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
      return result;
    }
    for (const core::Diagnostic& d : m.diagnostics)
      if (d.code == "too_many_hexes") {
        result.diagnostics.push_back(d);
        return result;
      }
  }
  const double tolerance = std::max(1e-9 * whole.diagonal(), whole.tolerance());
  std::vector<std::string> schemes;
  std::size_t merged = 0;
  for (int k = 0; k < whole.num_solids(); ++k) {
    const occ::Solid part = whole.part(k);
    MeshResult one;
    const bool meshed = mesh_solid(part, options, sizes, progress, one);
    const std::string prefix = "Solid " + std::to_string(k + 1) + ": ";
    for (core::Diagnostic d : one.diagnostics) {
      d.message = prefix + d.message;
      result.diagnostics.push_back(std::move(d));
    }
    if (!meshed) return result;
    merged += mesh::append_part(result.mesh, whole, one.mesh, part, k + 1, tolerance).nodes_merged;
    if (std::find(schemes.begin(), schemes.end(), one.stats.scheme) == schemes.end())
      schemes.push_back(one.stats.scheme);
    result.stats.sub_volume_schemes.push_back(one.stats.scheme);
    result.stats.sub_volume_types.push_back(one.stats.sub_volume_types.size() == 1
                                                ? one.stats.sub_volume_types[0]
                                                : detail::type_of_scheme(one.stats.scheme));
    if (result.mesh.num_hexes() > options.max_hexes) {
      std::ostringstream s;
      s << "The solids' meshes have " << result.mesh.num_hexes() << " hexahedra after solid "
        << k + 1 << ", more than max_hexes = " << options.max_hexes
        << "; increase the size or the limit.";
      result.diagnostics.push_back(core::make_error("too_many_hexes", s.str()));
      result.mesh = core::HexMesh();
      return result;
    }
    if (progress.cancelled()) break;
  }
  result.stats.scheme = detail::joined_schemes(schemes);
  result.stats.sub_volumes = whole.num_solids();
  result.stats.seconds_meshing = seconds_since(t0);
  std::ostringstream s;
  const int shared = whole.num_interface_faces();
  s << whole.num_solids() << " solids meshed one by one and joined; " << merged << " nodes on the "
    << shared << (shared == 1 ? " shared face" : " shared faces")
    << " (with their edges and vertices) merged.";
  result.diagnostics.push_back(core::make_info("solids_joined", s.str()));
  detail::finish(result, whole, options, progress, sizes);
  detail::pillow_flat_doublets(result, whole, options, progress, sizes);
  return result;
}

MeshResult generate(const occ::Solid& solid, const MeshOptions& options,
                    const core::Progress& progress) {
  // Automatic size: 20 elements along the diagonal (of all solids together).
  const double size = options.size > 0 ? options.size : solid.diagonal() / 20.0;
  // Every scheme makes at least about one hexahedron per size^3 of volume: a size far too
  // small for the limit is refused before any work (the decomposition, the tetrahedra).
  {
    const double at_least = std::abs(solid.volume()) / (size * size * size);
    if (at_least > double(options.max_hexes)) {
      MeshResult refused;
      std::ostringstream s;
      s << "The size " << size << " would give at least about " << std::setprecision(3) << at_least
        << " hexahedra (the volume " << std::abs(solid.volume()) << " over size^3), more "
        << "than max_hexes = " << options.max_hexes << "; a size of at least "
        << std::cbrt(std::abs(solid.volume()) / double(options.max_hexes))
        << " or a larger limit is needed.";
      refused.diagnostics.push_back(core::make_error("too_many_hexes", s.str()));
      refused.stats.size_used = size;
      return refused;
    }
  }
  // Several solids are glued first, which renumbers their faces, edges and vertices: a name
  // given for the file's numbering would refine another entity, so they are refused.
  if (!options.local_sizes.empty() && solid.num_solids() > 1)
    throw std::invalid_argument(
        "local sizes are not supported yet on several solids: gluing them at their common "
        "faces renumbers their faces, edges and vertices (the file's " +
        options.local_sizes[0].entity +
        " is not the glued solid's), so a size would land on another entity; mesh the solids "
        "one by one, or without local sizes");
  // Local sizes (a uniform field without them); an unknown entity throws, naming it.
  const core::SizeField sizes =
      options.local_sizes.empty()
          ? core::SizeField(size)
          : core::SizeField(solid, size, options.local_sizes, options.size_grading);
  // The layers graded around local sizes hold at least about this many more hexahedra: a
  // tiny local size (a typo) is refused here, before any work.
  if (!sizes.uniform()) {
    const double at_least = std::abs(solid.volume()) / (size * size * size) + sizes.graded_cells();
    if (at_least > double(options.max_hexes)) {
      MeshResult refused;
      std::ostringstream s;
      s << "The local sizes (";
      for (std::size_t i = 0; i < sizes.applied().size(); ++i)
        s << (i ? ", " : "") << sizes.applied()[i].entity << " " << sizes.applied()[i].size;
      s << ") would give at least about " << std::setprecision(3) << at_least
        << " hexahedra (the layers graded around them at " << options.size_grading
        << " per unit of distance), more than max_hexes = " << options.max_hexes
        << "; give larger local sizes, a larger grading or a larger limit.";
      std::vector<std::string> names;
      for (const core::LocalSize& l : sizes.applied()) names.push_back(l.entity);
      refused.diagnostics.push_back(core::make_error("too_many_hexes", s.str(), names));
      refused.stats.size_used = size;
      refused.stats.local_sizes = sizes.applied();
      return refused;
    }
  }
  std::vector<core::Diagnostic> small = detail::small_features(solid, sizes);
  append(small, detail::sharp_edge_info(solid));
  append(small, sizes.diagnostics());
  if (solid.num_solids() > 1) {
    MeshResult parts = generate_parts(solid, options, sizes, progress);
    parts.diagnostics.insert(parts.diagnostics.begin(), small.begin(), small.end());
    parts.stats.local_sizes = sizes.applied();
    return parts;
  }
  MeshResult result;
  result.diagnostics = small;
  result.stats.local_sizes = sizes.applied();
  const auto t0 = std::chrono::steady_clock::now();
  // The fallback beside the decomposition: started in a second child process as the
  // decomposition starts, taken if that fails, killed (with the job) if it succeeds.
  core::IsolatedJob beside;
  DeferredFallback deferred;
  if (options.fallback_beside && std::thread::hardware_concurrency() >= 2)
    deferred.before_decomposition = [&] {
      beside = core::IsolatedJob(
          [&](const core::Progress& in_child) {
            const FallbackOutcome o =
                run_fallback(solid, options, sizes, small, kWhyLater, in_child, t0);
            return detail::fallback_to_bytes(o.result, o.second_chance);
          },
          progress);
    };
  // The fallback's mesh made beside, taken: true with `outcome` filled; `got` says why not.
  FallbackOutcome outcome;
  auto take_beside = [&](const core::Progress& p, core::IsolatedResult& got) {
    got = beside.take(p, {options.fallback_scheme});
    if (!got.ok() || !detail::fallback_from_bytes(got.data, outcome.result, outcome.second_chance))
      return false;
    // What does not cross the process boundary, from the mesh (the same check the child
    // made: its diagnostics are among those carried).
    MeshResult& r = outcome.result;
    r.stats.fallback_beside = true;
    // Meshing: until the fallback's mesh was taken, less its smoothing and check (which
    // the child made before), never less than the child measured.
    r.stats.seconds_meshing =
        std::max(r.stats.seconds_meshing,
                 seconds_since(t0) - r.stats.seconds_smoothing - r.stats.seconds_checking);
    r.groups = io::named_groups(r.mesh, solid);
    r.check = quality::check_mesh(r.mesh, &solid, options.check, &r.scaled_jacobian);
    for (core::Diagnostic& d : r.diagnostics)
      for (std::size_t at; (at = d.message.find(kWhyLater)) != std::string::npos;)
        d.message.replace(at, kWhyLater.size(), deferred.why);
    return true;
  };
  if (mesh_solid(solid, options, sizes, progress, result, &deferred)) {
    // A decomposition's mesh poor before smoothing keeps the fallback beside running: where it
    // stays poor, the better of the two is used.
    if (beside.started() && min_scaled_jacobian(result.mesh) >= kPoorStructured) beside.cancel();
    detail::finish(result, solid, options, progress, sizes);
    detail::pillow_flat_doublets(result, solid, options, progress, sizes);
    add_deviation(result, solid);
    if (beside.started() && result.ok && result.check.scaled_jacobian.min < kPoorStructured &&
        !progress.cancelled()) {
      std::ostringstream why;
      why << "The decomposition's structured mesh (" << result.stats.scheme << ", "
          << result.stats.sub_volumes << " sub-volumes) has min scaled Jacobian "
          << std::setprecision(3) << result.check.scaled_jacobian.min << ", below "
          << kPoorStructured;
      deferred.why = why.str() + ".";
      core::IsolatedResult got;
      const bool made = take_beside(progress.with_time_limit(kPoorStructuredWait), got);
      if (progress.cancelled()) {
        result.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
        result.ok = false;
        result.mesh = core::HexMesh();
        return result;
      }
      if (replaced_by_fallback(result, outcome, made, why.str(), small.size()))
        return std::move(outcome.result);
    }
    beside.cancel();
    return result;
  }
  if (!deferred.needed) return result;  // an error (or a cancel) said why
  bool taken = false;
  if (beside.started()) {
    core::IsolatedResult got;
    taken = take_beside(progress, got);
    if (got.status == core::IsolatedResult::Status::cancelled) {
      result.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
      return result;
    }
    if (!taken) {
      result.diagnostics.push_back(
          core::make_info("fallback_beside_failed",
                          "The fallback computed beside the decomposition gave no "
                          "result (" +
                              got.message + "); it was computed again."));
    }
  }
  if (!taken) outcome = run_fallback(solid, options, sizes, small, deferred.why, progress, t0);
  MeshResult& r = outcome.result;
  // What the schemes and the decomposition said (scheme_failed, sweep_untangled, ...) goes
  // before the fallback's own diagnostics; the second chance's result already starts with
  // the small features, as `result` does.
  const auto skip =
      std::ptrdiff_t(outcome.second_chance ? std::min(small.size(), result.diagnostics.size()) : 0);
  r.diagnostics.insert(r.diagnostics.begin() + skip, result.diagnostics.begin() + skip,
                       result.diagnostics.end());
  r.ok = r.ok && !core::has_error(result.diagnostics);
  r.stats.local_sizes = result.stats.local_sizes;
  return std::move(r);
}

}  // namespace

}  // namespace vorohex::pipeline
