// Gluing solids at the faces they have in common (OCCT's general fuse), with the checks that
// the glued compound can be meshed as one: shared by reading a file of several solids
// (occ/shape_io.cpp) and occ::glue_solids.
#pragma once

#include <TopoDS_Solid.hxx>

#include <string>
#include <vector>

#include "occ/shape_io.h"

namespace vorohex::occ::detail {

// Several solids glued into one compound: OCCT's general fuse makes faces the solids have in
// common (touching boxes, fragments) one shared face. Overlapping solids are refused: their
// common volume would be meshed twice.
// Errors added to r's diagnostics (overlapping_solids, non_manifold, invalid_shape), else
// r.solid holds the compound and an info says how many solids share how many faces.
ReadResult glue(const std::vector<TopoDS_Solid>& solids, const std::string& where, ReadResult r,
                const GlueOptions& options = {});

}  // namespace vorohex::occ::detail
