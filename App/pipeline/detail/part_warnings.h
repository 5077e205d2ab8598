// What is said about the part before meshing: features smaller than the size (which no
// structured scheme absorbs) and sharp edges that bound the quality of any hex mesh.
#pragma once

#include <vector>

#include "core/diagnostic.h"
#include "core/size_field.h"
#include "occ/solid.h"

namespace vorohex::pipeline::detail {

// Warnings tiny_edges and sliver_faces: model edges shorter than, and faces narrower than,
// a quarter of the size (where they are, with local sizes), named, with what the user can do.
std::vector<core::Diagnostic> small_features(const occ::Solid& solid, const core::SizeField& sizes);

// Warning geometry_bounds_quality naming the sharpest edges (quality/sharp_edges.h); none
// when every bound is 0.5 or more.
std::vector<core::Diagnostic> sharp_edge_info(const occ::Solid& solid);

}  // namespace vorohex::pipeline::detail
