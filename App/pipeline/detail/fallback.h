// The fallback for a solid no structured scheme meshes: the grid mesher (or, on request, the
// tetrahedral split), with its retries - a finer grid where its mesh is invalid or poor, the
// chains at cusps sharing nodes, the tet split's second chance beside - as the pipeline runs it
// (pipeline/generate_mesh.cpp).
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "core/progress.h"
#include "core/size_field.h"
#include "grid/grid_mesh.h"
#include "occ/solid.h"
#include "pipeline/generate_mesh.h"

namespace vorohex::pipeline::detail {

// The warning that a scheme meshes at the global size, not the local sizes asked for.
core::Diagnostic local_sizes_ignored(const std::string& scheme);

// The grid mesher's composites (result.absorbed): how far the final boundary strays from the
// real surface, in result.stats and a diagnostic.
void add_deviation(MeshResult& result, const occ::Solid& solid);

// No structured scheme: the grid mesher (or, on request, tetrahedra split into
// hexahedra) meshes `solid` at `size` into `result`, said so in a warning starting with `why`.
// False where it made no mesh (its errors in result.diagnostics). The grid mesher's stats go
// to grid_stats when given; share_cusps: grid::GridOptions::share_cusps.
bool fallback(const occ::Solid& solid, const MeshOptions& options, double size,
              const std::string& why, const core::Progress& progress,
              std::chrono::steady_clock::time_point t0, MeshResult& result,
              grid::GridStats* grid_stats = nullptr, bool share_cusps = false);

// Stands for the fallback's reason in a run computed before the reason is known (beside
// the decomposition); replaced in the messages once it is.
inline const std::string kWhyLater = "\x1f(why)\x1f";

// What the fallback makes of a solid no structured scheme meshed: its mesh, smoothed and
// checked, with only the fallback's own diagnostics (the caller puts the run's before
// them); or, where the grid mesher's mesh is invalid and the tet split's second chance
// valid, that result, standing alone (`second_chance`: with the part's small features
// first, as a run of its own).
struct FallbackOutcome {
  MeshResult result;
  bool second_chance = false;
};

// The fallback's mesh of `solid`, smoothed and checked, with its retries (see the .cpp).
// `small`: the part's small-feature diagnostics, put before a second chance's own.
FallbackOutcome run_fallback(const occ::Solid& solid, const MeshOptions& options,
                             const core::SizeField& sizes,
                             const std::vector<core::Diagnostic>& small, const std::string& why,
                             const core::Progress& progress,
                             std::chrono::steady_clock::time_point t0);

}  // namespace vorohex::pipeline::detail
