// Typing the sub-volumes and merging them (steps 6-7 of decompose(); docs/decomposition.md):
// each sub-volume judged by the meshers (block, sweep, multisweep, revolve, midpoint),
// neighbours united while the union keeps a scheme glued to its neighbours (the paper's
// §7), and the solid itself taken where its split's pieces fail the self-check but it has
// a scheme whole. Internal to App/decompose.
#pragma once

#include "core/progress.h"
#include "decompose/decompose.h"
#include "occ/solid.h"
#include "voronoi/voronoi_graph.h"

namespace vorohex::decompose::detail {

// Type (Vs/Ve) and scheme of r.sub_volumes[index] (`sv`), in the pipeline's order: a
// mapped block, a sweep (first for a Vs), a multisweep, a revolve (the solid's only
// sub-volume), midpoint subdivision; the options say which are allowed.
void type_sub_volume(const voronoi::VoronoiGraph& g, const DecompositionResult& r, int index,
                     const DecomposeOptions& options, SubVolume& sv);

// Unites neighbours while the union keeps a scheme (within `time_limit` seconds, 0: none;
// merge_stopped when it ends there), retyping the sub-volumes after each union.
void merge_pass(const occ::Solid& solid, const voronoi::VoronoiGraph& g, double tol,
                double time_limit, const DecomposeOptions& options, const core::Progress& progress,
                DecompositionResult& r);

// A block, sweep or multisweep alone that has no scheme once glued to all its neighbours
// loses it (its reason says why).
void judge_glued(DecompositionResult& r, bool multisweep);

// The solid as the one sub-volume where it has a scheme whole (true; the pieces' errors
// become the warning split_check_failed); false, nothing changed, where it has none.
bool take_whole_solid(const occ::Solid& solid, const voronoi::VoronoiGraph& g, double tol,
                      const DecomposeOptions& options, DecompositionResult& r);

}  // namespace vorohex::decompose::detail
