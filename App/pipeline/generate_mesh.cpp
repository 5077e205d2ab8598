#include "pipeline/generate_mesh.h"

#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "mesh/map_block.h"
#include "quality/scaled_jacobian.h"

namespace vorohex::pipeline {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

void MeshOptions::validate() const {
  if (!std::isfinite(size) || size < 0) {
    std::ostringstream s;
    s << "size must be a positive length (or 0 for automatic), got " << size;
    throw std::invalid_argument(s.str());
  }
  if (max_hexes == 0) throw std::invalid_argument("max_hexes must be at least 1");
  check.validate();
}

MeshResult generate_mesh(const occ::Solid& solid, const MeshOptions& options,
                         const core::Progress& progress) {
  options.validate();
  MeshResult result;
  const auto t0 = std::chrono::steady_clock::now();

  // Automatic size: 20 elements along the diagonal.
  const double size = options.size > 0 ? options.size : solid.diagonal() / 20.0;
  result.stats.size_used = size;

  progress.report("scheme", 0.0);
  const mesh::Applicability map = mesh::map_block_applicable(solid);
  if (!map.ok) {
    result.diagnostics.push_back(core::make_error(
        "not_supported_yet",
        "This solid is not supported yet: this version meshes only topological hexahedra (six "
        "faces of four edges each); " +
            map.reason + "."));
    return result;
  }

  mesh::MapBlockOptions map_options;
  map_options.size = size;
  const mesh::MapBlockEstimate estimate = mesh::map_block_evaluate(solid, map_options);
  result.stats.intervals = estimate.intervals;
  if (estimate.hexes > options.max_hexes) {
    std::ostringstream s;
    s << "The mesh would have " << estimate.hexes << " hexahedra (intervals "
      << estimate.intervals[0] << " x " << estimate.intervals[1] << " x " << estimate.intervals[2]
      << "), more than max_hexes = " << options.max_hexes << "; increase the size or the limit.";
    result.diagnostics.push_back(core::make_error("too_many_hexes", s.str()));
    return result;
  }

  mesh::MapBlockResult mapped = mesh::map_block(solid, map_options, progress);
  result.diagnostics.insert(result.diagnostics.end(), mapped.diagnostics.begin(),
                            mapped.diagnostics.end());
  result.stats.seconds_meshing = seconds_since(t0);
  if (!mapped.ok) return result;
  result.mesh = std::move(mapped.mesh);
  result.stats.intervals = mapped.intervals;
  result.stats.sub_volumes = 1;
  result.stats.scheme = "map";

  if (progress.cancelled()) {
    result.diagnostics.push_back(core::make_error("cancelled", "Meshing was cancelled."));
    return result;
  }

  // Never hand over an unchecked mesh: the validity check runs on every result.
  progress.report("check", 0.0);
  const auto t1 = std::chrono::steady_clock::now();
  result.check = quality::check_mesh(result.mesh, &solid, options.check);
  result.scaled_jacobian = quality::scaled_jacobians(result.mesh);
  result.stats.seconds_checking = seconds_since(t1);
  progress.report("check", 1.0);
  result.diagnostics.insert(result.diagnostics.end(), result.check.diagnostics.begin(),
                            result.check.diagnostics.end());
  result.ok = result.check.valid && !core::has_error(result.diagnostics);
  return result;
}

}  // namespace vorohex::pipeline
