// The plane cuts' pieces judged and merged (decompose/plane_cuts.cpp): whether a piece has
// a scheme once glued to its neighbours, which pieces touch, and the merge of neighbours
// while their union keeps a scheme. Internal to App/decompose.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/progress.h"
#include "decompose/plane_cuts.h"
#include "occ/shape_io.h"
#include "occ/solid.h"

namespace vorohex::decompose::detail {

// Relative difference allowed between the pieces' volume sum and the solid's: the cuts are
// exact surfaces, so only the volume integration's error (1e-11 relative each) remains.
inline constexpr double kVolumeTolerance = 1e-6;

// Gluing the pieces of one exact split, or unions of them: only touching (occ::GlueOptions).
occ::GlueOptions touching_only();

// A block, a sweep, a prismatic part (o.multisweep) or a solid of revolution (o.revolve):
// what mesh::mesh_sub_volumes meshes. `glued`: a piece glued to the others (its sweep's
// linking sides may carry their imprints).
bool meshable(const occ::Solid& s, const PlaneCutOptions& o, bool glued = false);

// The pieces glued (imprinting each other's edges where they touch).
occ::ReadResult glued(const std::vector<const occ::Solid*>& pieces);

// Each part of the glued pieces `g` a block, a sweep or prismatic; `why` (when given) names
// the first that is none. `imprinted`: sweeps' linking sides may carry imprints.
bool all_meshable(const occ::ReadResult& g, const PlaneCutOptions& o, std::string* why = nullptr,
                  bool imprinted = false);
bool all_meshable(const std::vector<const occ::Solid*>& pieces, const PlaneCutOptions& o,
                  std::string* why = nullptr, bool imprinted = false);

// Every piece has volume, and they fill the solid (volume `whole`); false with why.
// `volumes` gets each piece's.
bool volumes_fill(const std::vector<occ::Solid>& pieces, double whole, std::vector<double>& volumes,
                  std::string& why);

// The bounding box of each solid, and the index among them of the piece whose box `part`
// has (-1 when none or several): a glued part told by its box.
std::vector<core::BoundingBox> boxes_of(const std::vector<const occ::Solid*>& solids);
int piece_of(const occ::Solid& part, const std::vector<core::BoundingBox>& boxes);

// Which pieces touch once glued (`r`: the pieces glued), per pair.
using Touching = std::vector<std::vector<char>>;
Touching touching(const std::vector<const occ::Solid*>& pieces, const occ::ReadResult& r);

// Merges neighbouring pieces while the union is a block, a sweep or prismatic (and, when
// `careful`, every piece around it stays so once glued), each merge taking one piece away,
// until none is left or `seconds()` reaches options.time_limit. `volume`, `touch`: per
// piece; `cut_into`: the pieces' count before merging (for the progress). `history`, where
// given, gets the unions made.
void merge_neighbours(std::vector<occ::Solid>& pieces, std::vector<double>& volume, Touching touch,
                      const PlaneCutOptions& options, bool careful, double cut_into,
                      const std::function<double()>& seconds, const core::Progress& progress,
                      MergeHistory* history = nullptr);

}  // namespace vorohex::decompose::detail
