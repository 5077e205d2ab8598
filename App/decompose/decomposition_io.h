// Output of a decomposition: the sub-volumes as one compound in a BREP file, and a JSON
// report for people and scripts.
//
// JSON layout:
//   {"status": "ok"|"partial"|"failed", "partial_reason": "..." (partial only: why),
//    "counts": {"sub_volumes_before_merge": n, "sub_volumes": n, "decomposition_faces": n,
//               "quads": n, "edges_of_interest": n, "projected_edges": n},
//    "sub_volumes": [{"id": i, "type": "Vs"|"Ve", "scheme": "sweep"|"map"|"multisweep"|
//                     "revolve"|"midpoint"|"none", "reason": "...", "volume": v, "merged_from": n,
//                     "f_s_face": voronoi id or null, "source": "Face3", "target": "Face5",
//                     "faces": [{"face": "Face1", "on": "Face4" or null,
//                                "decomposition_face": k or null}],
//                     "edges": [{"edge": "Edge1", "on": "Edge7" | "Face4" | null}]}],
//    "decomposition_faces": [{"id": i, "sub_volumes": [a, b], "edges": n, "area": a, "min_angle":
//    degrees,
//                             "voronoi_elements": [ids], "governors": ["Face1", ...]}],
//    "edges": [{"voronoi_id": i, "type": "[1e]", "targets": ["Face2", "Edge7"]}]
//             (edges of interest and [C] edges only),
//    "vertices": [{"voronoi_id": i, "row": "[2,2,2,2]", "rectangles": [["Face1","Face3"]]}],
//    "diagnostics": [...], "stats": {"seconds": s}}
#pragma once

#include <string>

#include "decompose/decompose.h"
#include "decompose/plane_cuts.h"

namespace vorohex::decompose {

// The report as JSON text (indented).
std::string decomposition_json(const DecompositionResult& result);

// The decomposition faces as VTK XML PolyData (ASCII): one polygon per quad of each final
// decomposition face, with cell data `face` (index in result.faces), `sub_volume_a` and
// `sub_volume_b` (the sub-volumes on either side, -1 for none), `voronoi_element` (the
// generating Voronoi edge or vertex) and `rectangle` (1 for a vertex's closing rectangle).
std::string decomposition_vtp(const DecompositionResult& result);

// Writes the sub-volumes compound (`brep_path`), the JSON report (`json_path`) and the
// decomposition faces as VTP (`vtp_path`); each is skipped if its path is empty. False
// with `error` when a file cannot be written.
bool write_decomposition(const DecompositionResult& result, const std::string& brep_path,
                         const std::string& json_path, std::string* error,
                         const std::string& vtp_path = "");

// The plane cuts' pieces (plane_cuts.h), each with the scheme it gets once glued to the
// others, or why it has none; when the pieces cannot be glued, `glue_error` says why and
// no piece has a scheme.
struct PlaneCutSchemes {
  std::vector<std::string> schemes;  // per piece ("" when none)
  // Per piece that is a sweep on its own: its source and target (its own faces' ids).
  std::vector<std::pair<core::FaceId, core::FaceId>> ends;
  std::vector<std::string> reasons;  // per piece: why it has none
  std::string glue_error;
};
PlaneCutSchemes plane_cut_schemes(const PlaneCutResult& cut, bool multisweep = true);

// The plane cuts as JSON text, in the layout above where it applies:
//   {"method": "plane-cuts", "status": "ok"|"failed",
//    "counts": {"planes": n, "cylinders": n, "sub_volumes_before_merge": n, "sub_volumes": n},
//    "sub_volumes": [{"id": i, "scheme": "sweep"|...|"none", "reason": "...", "volume": v}],
//    "cut_surfaces": [{"id": i, "kind": "plane"|"cylinder", "face": "Face7" (the model face
//    it extends), "concave_edges": ["Edge12", ...] (where it is taken), "used": false when
//    left out}],
//    "decomposition_faces": [], "diagnostics": [{"code": "plane_cuts_failed" or
//    "cut_surfaces_left_out", "message": ...}]}
std::string plane_cuts_json(const PlaneCutResult& cut, const PlaneCutSchemes& schemes);

// A solid the mesher meshes whole (whole_solid_scheme), in the same layout: {"method":
// "whole", "status": "ok", one sub-volume with its scheme, reason and volume, the info
// "not_cut"}.
std::string whole_solid_json(Scheme scheme, const std::string& reason, double volume,
                             std::pair<core::FaceId, core::FaceId> ends = {});

}  // namespace vorohex::decompose
