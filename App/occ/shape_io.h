// Reading CAD files (STEP, BREP, IGES) and BREP strings into exactly one solid, with
// errors that name the problem; writing solids back for tests and examples.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/diagnostic.h"
#include "occ/solid.h"

namespace vorohex::occ {

struct ReadResult {
  std::unique_ptr<Solid> solid;               // null when reading failed
  std::vector<core::Diagnostic> diagnostics;  // errors when solid is null; notes otherwise
  bool ok() const { return solid != nullptr; }
};

struct ReadOptions {
  // Accept several solids (meshing): they are glued at the faces they have in common
  // (OCCT's general fuse) into one Solid whose parts share those faces; overlapping solids
  // are refused (overlapping_solids). Other commands take one solid (several_solids error).
  bool several_solids = false;
  // Seconds OCCT's shape healing of a solid that fails OCCT's check may take (0: no
  // limit); it runs in a child process that is stopped then (error invalid_shape).
  double repair_time_limit = 120;
};

// Format from the extension (.step/.stp, .brep/.brp, .iges/.igs, case-insensitive).
// Errors (codes): file_not_found, empty_file, unsupported_format, unreadable_file,
// no_solid, several_solids (message says how many), overlapping_solids, non_manifold
// (solids touching along an edge or at a vertex only; names them), open_shell (names free
// edges), invalid_shape.
ReadResult read_solid(const std::string& path, const ReadOptions& options = {});

// The same checks on a BREP string (FreeCAD's Part.Shape.exportBrepToString()).
ReadResult read_solid_from_brep_string(const std::string& brep, const ReadOptions& options = {});

// Glues solids (e.g. the sub-volumes of a decomposition) at the faces they have in common,
// as ReadOptions::several_solids does: one Solid whose parts share those faces, or errors
// (overlapping_solids, non_manifold, invalid_shape). `where` starts the messages.
struct GlueOptions {
  // Their volumes must add up to the glued volume (they share none): overlapping_solids.
  bool check_overlap = true;
  // None touches another only along an edge or at a vertex: non_manifold. Off for a
  // neighbourhood cut out of pieces that are checked as a whole elsewhere (the solids that
  // join two such neighbours by faces may be outside it).
  bool check_manifold = true;
  // The solids only touch, without crossing (pieces of one exact split, and unions of
  // such pieces): OCCT's gluing mode (BOPAlgo_GlueShift) then skips the intersections of
  // their faces that cannot exist. Wrong for solids whose faces cross.
  bool only_touching = false;
};
ReadResult glue_solids(const std::vector<const Solid*>& solids, const std::string& where,
                       const GlueOptions& options = {});

// Writes a solid; format from the extension (.step/.stp or .brep). Returns false and
// fills error on failure.
bool write_solid(const Solid& solid, const std::string& path, std::string* error);

}  // namespace vorohex::occ
