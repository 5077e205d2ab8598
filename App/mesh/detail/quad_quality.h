// Quality of a face's quad mesh built on the CAD (mapped grids, submapped lattices): the
// 2-D scaled Jacobian of each quad about the face normal (or its opposite, when the quads
// run the other way round, as a sweep's target seen in its source's order).
#pragma once

#include "core/geometry.h"
#include "core/mesh_domain.h"
#include "mesh/quad_face.h"

namespace vorohex::mesh::detail {

// Sets m.min_quality and m.mean_quality from m.points and m.quads.
void measure_quads(const core::MeshDomain& solid, core::FaceId face, QuadFaceMesh& m);

}  // namespace vorohex::mesh::detail
