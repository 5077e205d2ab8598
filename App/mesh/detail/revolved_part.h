// A solid of revolution among the sub-volumes (mesh_sub_volumes): its circles and arcs in the
// interval assignment as their shares of one count of sectors, and the options it is revolved
// with beside its neighbours (its sectors starting at the vertex of a circle it shares, the
// counts and nodes of the seams it shares). Internal to App/mesh.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/progress.h"
#include "mesh/interval_assignment.h"
#include "mesh/revolve.h"
#include "occ/solid.h"

namespace vorohex::mesh::detail {

// Per edge id of `solid` (entry 0 unused): the share of a turn the edge spans about the axis
// through `origin` along unit `axis` (1 for a whole circle), 0 for an edge that is no circle
// about it (a meridian circle, a torus's seam, turns by nothing).
std::vector<double> turns_about_axis(const occ::Solid& solid, const core::Vec3& origin,
                                     const core::Vec3& axis);

struct RevolvedPart {
  const occ::Solid& solid;
  core::Vec3 origin, axis;               // its axis (unit)
  const std::vector<bool>& shared_edge;  // by edge id: a neighbour has it too
  const std::vector<double>& turns;      // by edge id: turns_about_axis
};

// Its circles' counts as their shares of a curve of sectors (a multiple of 4, at least 8; an
// arc between vertices a quarter of a turn apart its share, an arc of another share left to
// its neighbour), the seams it shares even (edges of its section, which the quad mesher may
// mesh). `curve`: the problem's curve of an edge of the part.
void add_revolved_constraints(IntervalProblem& problem, const RevolvedPart& part,
                              const std::function<int(core::EdgeId)>& curve,
                              const std::string& who);

// `base` with the sectors of its circles' assigned counts (per part edge id), starting at the
// vertex of a circle it shares, and the counts of the seams it shares.
RevolveOptions revolved_options(const RevolvedPart& part, RevolveOptions base,
                                const std::vector<int>& counts);

// Revolved with those options and the nodes its neighbours meshed before placed on the seams
// it shares (per part edge id); error revolve_misaligned where a circle it shares ends at an
// angle no sector meets.
RevolveResult mesh_revolved(const RevolvedPart& part, const RevolveOptions& base,
                            const std::vector<int>& counts,
                            const std::vector<std::vector<core::Vec3>>& edge_nodes,
                            const core::Progress& progress);

}  // namespace vorohex::mesh::detail
