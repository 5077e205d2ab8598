// Submapping (paper §5.1, Whiteley et al.): a planar face of one wire whose corners all
// turn by +90, -90 or 0 degrees (within 15) (an L, a T, a U, a stepped outline) is a union of
// mapped blocks. Each edge gets a direction (+u, +v, -u, -v) from the turns; when the
// intervals along +u equal those along -u (and +v / -v), the face is meshed as the cells
// of an integer lattice inside its outline, placed by a discrete harmonic map from the
// boundary nodes: every quad of a rectilinear outline is a rectangle.
#pragma once

#include <vector>

#include "core/geometry.h"
#include "mesh/interval_assignment.h"
#include "mesh/quad_face.h"
#include "occ/solid.h"

namespace vorohex::mesh {

// Per edge of the face's wire (in face_wires order): its direction 0 (+u), 1 (+v), 2 (-u),
// 3 (-v); empty when the face is not submappable (curved, holes, a corner of another
// angle, or four sides, which is a mapped face).
std::vector<int> submap_directions(const occ::Solid& solid, core::FaceId face);

// `loop`: the boundary nodes in wire order (first node not repeated), `counts`: intervals
// per wire edge (summing to loop.size()), `directions` from submap_directions. ok false
// (with a diagnostic) when the counts do not balance or the lattice outline touches itself.
QuadFaceMesh submap_face(const occ::Solid& solid, core::FaceId face,
                         const std::vector<core::Vec3>& loop, const std::vector<int>& counts,
                         const std::vector<int>& directions);

// Adds the face's two balance constraints (+u = -u, +v = -v) to an interval problem;
// `curves`: the problem's curve of each wire edge; `why` names the face for diagnostics.
void add_submap_balance(IntervalProblem& problem, const std::vector<int>& directions,
                        const std::vector<int>& curves, const std::string& why);

}  // namespace vorohex::mesh
